// LineAnalysis forced responses: static deflection under point loads and receptance FRFs.
#include "modalbench/dtfm/analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include "analysis_detail.hpp"
#include "modalbench/numerics/balancing.hpp"
#include "modalbench/numerics/line_system.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"
#include "modalbench/numerics/symmetric_factor.hpp"

#include <unsupported/Eigen/MatrixFunctions>

namespace modalbench::dtfm {

namespace {

/// A probe or observation point within `delta` of a node is not made a node (a piece that short is
/// so stiff that eliminating it cancels every digit: 3e-7 L from a load did): it is attached to the
/// node and reached from it by the transfer matrix exp(A t).
struct Attached {
  double anchor = 0;  // the node it is reached from (itself when it is a node)
  double t = 0;       // offset from that node
};

/// Points that become nodes (appended to `kept`, which holds the loads) and, for the others, the
/// node within `delta` they are reached from.
std::vector<Attached> attach(const std::vector<double>& points, std::vector<double>& kept, double L, double delta) {
  std::vector<Attached> out(points.size());
  for (std::size_t j = 0; j < points.size(); ++j) {
    const double x = std::clamp(points[j], 0.0, L);
    double anchor = 0.0;
    for (double k : {0.0, L}) if (std::abs(x - k) < std::abs(x - anchor)) anchor = k;
    for (double k : kept) if (std::abs(x - k) < std::abs(x - anchor)) anchor = k;
    if (std::abs(x - anchor) >= delta) {
      kept.push_back(x);
      anchor = x;
    }
    out[j] = {anchor, x - anchor};
  }
  return out;
}

LongSegment segment_k(const Eigen::MatrixXd& A, double h, int levels) { return long_segment_dynamic_stiffness(A, h, levels); }
LongSegmentC segment_k(const Eigen::MatrixXcd& A, double h, int levels) { return long_segment_dynamic_stiffness(A, h, levels); }

using detail::SegmentLoad;
using detail::particular;

}  // namespace

Eigen::VectorXd detail::particular(const Eigen::MatrixXd& A, const SegmentLoad& ld, double t) {
  const Eigen::Index n = A.rows();
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(n + 2, n + 2);
  E.topLeftCorner(n, n) = A;
  E.block(0, n, n, 1) = ld.g1;
  E.block(0, n + 1, n, 1) = ld.g0;
  E(n, n + 1) = 1.0;
  E *= t;
  const Eigen::VectorXd sc = balance_in_place(E, 20);
  const Eigen::MatrixXd X = sc.asDiagonal() * Eigen::MatrixXd(E.exp()) * sc.cwiseInverse().asDiagonal();
  return X.col(n + 1).head(n);
}

namespace {

/// Class displacements (nodes with conditions out of their B coordinates) at x[i] + t from a
/// solution d: the state of node i on the side of t (its displacement and the adjacent segment's
/// end force) carried by exp(A t), with the segment's distributed load (`loads`, per segment,
/// empty: none) as its particular solution.
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> near_node(const LineAnalysis::ClassLine& c, Scalar lambda,
                                                   const std::vector<double>& x, double h_base,
                                                   const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& d, int i, double t,
                                                   const std::vector<std::optional<SegmentLoad>>& loads = {}) {
  using Mat = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vec = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const int nn = static_cast<int>(x.size()), mc = c.mc;
  auto node_d = [&](int k) {
    Vec v = d.segment(static_cast<Eigen::Index>(k) * mc, mc);
    if (const auto* e = c.condition_at(x, static_cast<std::size_t>(k))) v = e->B.template cast<Scalar>() * v;
    return v;
  };
  if (t == 0.0) return node_d(i);
  const bool right = t > 0;
  const int a = right ? i : i - 1;
  if (a < 0 || a + 1 >= nn) return node_d(i);  // cannot happen: points lie in [0, L]
  const Mat A = c.state(lambda, c.piece_of(x[static_cast<std::size_t>(a)], x[static_cast<std::size_t>(a) + 1]));
  const double h = x[static_cast<std::size_t>(a) + 1] - x[static_cast<std::size_t>(a)];
  const int levels = detail::doubling_levels(h, h_base);
  const Mat K = segment_k(A, h, levels).K;
  const std::optional<SegmentLoad>* ld =
      static_cast<std::size_t>(a) < loads.size() && loads[static_cast<std::size_t>(a)] ? &loads[static_cast<std::size_t>(a)] : nullptr;
  Vec yp_h = Vec::Zero(2 * mc);  // the particular solution at the segment's right end
  if constexpr (std::is_same_v<Scalar, double>)
    if (ld) yp_h = particular(A, **ld, h);
  Vec dd(2 * mc), eta(2 * mc);
  dd << node_d(a), node_d(a + 1) - yp_h.head(mc);
  // K [d_a; d_b - d_p(h)] = [-F(a+); F(b-) - f_p(h)].
  if (right) eta << node_d(i), -(K.topRows(mc) * dd);
  else eta << node_d(i), K.bottomRows(mc) * dd + yp_h.tail(mc);
  Mat B = A * Scalar(t);
  const Eigen::VectorXd s = balance_in_place(B, 20);
  const Mat T = s.template cast<Scalar>().asDiagonal() * Mat(B.exp()) * s.cwiseInverse().template cast<Scalar>().asDiagonal();
  Vec y = T * eta;
  if constexpr (std::is_same_v<Scalar, double>)
    if (ld) {  // the particular solution from node i: from the left end, or back from the right
      SegmentLoad from_i = **ld;
      if (!right) from_i.g0 += from_i.g1 * h;
      y += particular(A, from_i, t);
    }
  return y.head(mc);
}

/// K(0) d = f split into rigid amplitudes and the anchored elastic part (detail::RigidLine,
/// detail::condense_rigid): `K` is the assembled K(0) of rl.line (its anchors get held), `e` the
/// elastic nodal values, `a` the amplitudes. Throws std::runtime_error (numerical) if the elastic
/// part is not positive definite or a condensed pivot is not resolved.
void solve_split(const detail::RigidLine& rl, BlockTridiagonal& K, const std::vector<double>& x,
                 const Eigen::VectorXd& f, Eigen::VectorXd& e, Eigen::VectorXd& a) {
  const auto& c = rl.line;
  const int nn = static_cast<int>(x.size()), mc = c.mc;
  const Eigen::Index r = rl.V0.cols();
  detail::RigidCondensed cd = detail::condense_rigid(rl, K, x);
  Eigen::VectorXd fa = Eigen::VectorXd::Zero(r);
  for (int i = 0; i < nn; ++i)
    fa += cd.psi[static_cast<std::size_t>(i)].transpose() * f.segment(static_cast<Eigen::Index>(i) * mc, mc);
  const Eigen::VectorXd y = K.solve(f, 0.0);
  const Eigen::Index rf = static_cast<Eigen::Index>(rl.free_a.size());
  Eigen::VectorXd rhs(rf);
  for (Eigen::Index p = 0; p < rf; ++p) {
    const int ap = rl.free_a[static_cast<std::size_t>(p)];
    rhs[p] = fa[ap] - cd.B.col(ap).dot(y);
  }
  const Eigen::VectorXd piv = graded_ldlt(cd.S);
  for (Eigen::Index k = 0; k < rf; ++k)
    if (!std::isfinite(piv[k]) || !(piv[k] > 0))
      throw std::runtime_error(fmt::format(
          "static solve of the {} family: the stiffness of rigid-body motion {} of {} against its supports "
          "(condensed pivot {:.3g}) is not resolved in double precision",
          to_string(c.family), k + 1, rf, piv[k]));
  const Eigen::VectorXd af = graded_ldlt_solve(cd.S, piv, rhs);
  a = Eigen::VectorXd::Zero(r);
  for (Eigen::Index p = 0; p < rf; ++p) a[rl.free_a[static_cast<std::size_t>(p)]] = af[p];
  if (!a.allFinite())
    throw std::runtime_error(fmt::format("static solve of the {} family: the rigid-body amplitudes overflow "
                                         "(supports too soft for double precision)", to_string(c.family)));
  e = y - cd.Y * af;
}

}  // namespace

namespace {

/// The generalized forces per unit length of the distributed loads at x (physical fields), on the
/// side of x towards `inside` (a load's ends along x are nodes: within a segment each is linear).
/// Beams: the line loads' section resultants; plates: the pressures' strip-line shares.
Eigen::VectorXd density(const PrismModel& model, const std::vector<DistributedLoad>& loads, double x, double inside) {
  const double tol = 1e-12 * model.length;
  PointLoad q;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(model.m);
  for (const DistributedLoad& d : loads) {
    const double lo = d.from[0], hi = d.to[0];
    const bool covers = inside >= x ? (x >= lo - tol && x < hi - tol) : (x > lo + tol && x <= hi + tol);
    if (!covers) continue;
    if (model.kind == SceneKind::Plate) {
      f += model.pressure_vector(d);
      continue;
    }
    q.Fx += d.at(d.qx, x);
    q.Fy += d.at(d.qy, x);
    q.Fz += d.at(d.qz, x);
  }
  if (model.kind != SceneKind::Plate) f = model.load_vector(q);
  return f;
}

/// Each segment's distributed load in class c (none where it carries none), and its equivalent
/// nodal forces added to f: the forces of the segment held at both nodes under the load, from
/// the particular solution y_p and the segment's dynamic stiffness at lambda = 0.
std::vector<std::optional<SegmentLoad>> segment_loads(const LineAnalysis::ClassLine& c, const std::vector<double>& x,
                                                      const std::vector<DistributedLoad>& distributed,
                                                      const PrismModel& model, Eigen::VectorXd& f) {
  const int nn = static_cast<int>(x.size()), mc = c.mc;
  std::vector<std::optional<SegmentLoad>> out(static_cast<std::size_t>(nn > 0 ? nn - 1 : 0));
  auto g_at = [&](double xx, double inside) {
    Eigen::VectorXd g = Eigen::VectorXd::Zero(2 * mc);
    g.tail(mc) = -(c.W.transpose() * density(model, distributed, xx, inside) / c.sigma);
    return g;
  };
  // Segments of one length and load (a plate's base pieces under a pressure) share their segment
  // stiffness and particular solution: each is an exponential of a 2 mc matrix.
  std::map<std::pair<int, long long>, Eigen::MatrixXd> stiffness;
  std::map<std::vector<double>, Eigen::VectorXd> particulars;
  const double L = x.empty() ? 1.0 : x.back();
  for (int i = 0; i + 1 < nn; ++i) {
    const double xa = x[static_cast<std::size_t>(i)], xb = x[static_cast<std::size_t>(i) + 1], h = xb - xa;
    const Eigen::VectorXd ga = g_at(xa, xb), gb = g_at(xb, xa);
    if (ga.norm() == 0.0 && gb.norm() == 0.0) continue;
    SegmentLoad ld{ga, (gb - ga) / h};
    const int piece = c.piece_of(xa, xb);
    const long long hkey = std::llround(h / (1e-12 * L));
    const Eigen::MatrixXd A = c.state(0.0, piece);
    std::vector<double> key = {static_cast<double>(piece), static_cast<double>(hkey)};
    key.insert(key.end(), ld.g0.data(), ld.g0.data() + ld.g0.size());
    key.insert(key.end(), ld.g1.data(), ld.g1.data() + ld.g1.size());
    auto pit = particulars.find(key);
    if (pit == particulars.end()) pit = particulars.emplace(std::move(key), particular(A, ld, h)).first;
    const Eigen::VectorXd& yp = pit->second;
    auto kit = stiffness.find({piece, hkey});
    if (kit == stiffness.end()) kit = stiffness.emplace(std::make_pair(piece, hkey), segment_k(A, h, 0).K).first;
    const Eigen::MatrixXd& K = kit->second;
    // Held at both nodes: the homogeneous part takes d(h) = -d_p(h), so F(a+) = K_ab d_p(h) and
    // F(b-) = f_p(h) - K_bb d_p(h); the nodes carry [F(a+); -F(b-)].
    Eigen::VectorXd fa = K.topRightCorner(mc, mc) * yp.head(mc);
    Eigen::VectorXd fb = -(yp.tail(mc) - K.bottomRightCorner(mc, mc) * yp.head(mc));
    if (const auto* e = c.condition_at(x, static_cast<std::size_t>(i))) fa = e->B.transpose() * fa;
    if (const auto* e = c.condition_at(x, static_cast<std::size_t>(i) + 1)) fb = e->B.transpose() * fb;
    f.segment(static_cast<Eigen::Index>(i) * mc, mc) += fa;
    f.segment(static_cast<Eigen::Index>(i + 1) * mc, mc) += fb;
    out[static_cast<std::size_t>(i)] = ld;
  }
  return out;
}

/// Each class's share of the loads (physical units): the squared norm of their projection on its
/// fields; `total` gets their sum. (`Lines`: LineAnalysis's class lines.)
template <class Lines>
std::vector<double> class_shares(const Lines& lines, const PrismModel& model,
                                 const std::vector<PointLoad>& loads, const std::vector<DistributedLoad>& distributed,
                                 double& total) {
  std::vector<double> share(lines.size(), 0.0);
  for (std::size_t ci = 0; ci < lines.size(); ++ci) {
    for (const auto& p : loads) share[ci] += (lines[ci]->W.transpose() * model.load_vector(p)).squaredNorm();
    for (const auto& d : distributed)
      for (double x : {d.from[0], d.to[0]}) {
        const double L = model.length;
        share[ci] += (lines[ci]->W.transpose() * density(model, {d}, x, x == d.from[0] ? L : 0.0)).squaredNorm() * L * L;
      }
    total += share[ci];
  }
  return share;
}

/// The supports' actions on the fields, per node, as the section's forces and moments.
std::vector<PointReaction> point_reactions(const PrismModel& model, const std::map<double, Eigen::VectorXd>& react) {
  std::vector<PointReaction> out;
  for (const auto& [xr, fields] : react) {
    PointReaction pr;
    pr.x = xr;
    const Eigen::VectorXd F = model.rigid_motions.transpose() * fields;
    for (int k = 0; k < 6; ++k) pr.F[static_cast<std::size_t>(k)] = F[k];
    out.push_back(pr);
  }
  return out;
}

}  // namespace

std::vector<Deflection> LineAnalysis::statics(const std::vector<PointLoad>& loads,
                                              const std::vector<std::array<double, 2>>& probes,
                                              const std::vector<DistributedLoad>& distributed,
                                              std::vector<PointReaction>* reactions, FieldIntegrals* integrals) {
  std::vector<double> required;
  for (const auto& p : loads) required.push_back(std::clamp(p.x, 0.0, model_.length));
  for (const auto& d : distributed)
    for (double x : {d.from[0], d.to[0]}) required.push_back(std::clamp(x, 0.0, model_.length));
  std::vector<double> probe_x;
  for (const auto& p : probes) probe_x.push_back(p[0]);
  const std::vector<Attached> at = attach(probe_x, required, model_.length, 1e-4 * model_.length);
  const int m = model_.m;
  std::vector<Eigen::VectorXd> qp(probes.size(), Eigen::VectorXd::Zero(m));
  std::map<double, Eigen::VectorXd> react;  // per support node: its action on the fields
  // Each class's share of the loads (physical units): a class is unloaded when its share is
  // rounding of the total (a moment at an end leaks 1e-17 of itself into other classes), not
  // when it is exactly 0.
  if (integrals) {
    *integrals = FieldIntegrals{};
    for (Eigen::VectorXd* v : {&integrals->q, &integrals->xq, &integrals->q0, &integrals->qL}) *v = Eigen::VectorXd::Zero(m);
  }
  double total_share = 0;
  const std::vector<double> share = class_shares(lines_, model_, loads, distributed, total_share);
  // Without any load every class is judged as loaded: zero is no answer for a mechanism, whose
  // rigid motions are then undetermined (the other back-ends refuse it too; fuzz seed 7, case 1532).
  const bool unloaded = !(total_share > 0);
  for (const auto& line : lines_) {
    ClassLine& c0 = *line;
    if (!unloaded && !(share[static_cast<std::size_t>(c0.index)] > 1e-24 * total_share)) continue;
    // A class with rigid motions of its own (beams) is solved split into them and its elastic part
    // (detail::RigidLine): a mechanism is then a rigid motion no support reaches, structurally, and
    // a near-mechanism keeps its digits however soft its springs.
    const std::optional<detail::RigidLine> rl = detail::rigid_line(c0, model_.length);
    if (rl && rl->unrestrained > 0)
      throw std::runtime_error(fmt::format(
          "mechanism: the supports leave {} rigid-body motion(s) of the {}{} family free ({} / {})",
          rl->unrestrained, unloaded ? "" : "loaded ", to_string(c0.family), model_.ends[0].text, model_.ends[1].text));
    if (!rl) {
      // Otherwise a loaded class must be free of rigid-body motions by its count just above zero:
      // its static solve would give rounding noise divided by rounding noise.
      const double delta = kRigidThreshold * model_.lambda_scale;
      const Mesh near_zero = mesh_for(c0, delta, {});
      if (const int rigid = count_det(c0, delta, near_zero).count; rigid > 0)
        throw std::runtime_error(fmt::format(
            "mechanism: the supports leave {} rigid-body motion(s) of the {}{} family free, or restrain them "
            "below 1e-10 of the model's stiffness scale, which dtfm cannot resolve ({} / {})",
            rigid, unloaded ? "" : "loaded ", to_string(c0.family), model_.ends[0].text, model_.ends[1].text));
    }
    const ClassLine& c = rl ? rl->line : c0;
    Mesh mesh = mesh_for(c0, 0.0, required);
    // Distributed loads and integrals: segments no longer than a base piece (the particular
    // solution's exponential, the integrands' transfer).
    if ((!distributed.empty() || integrals) && mesh.h_base < model_.length)
      mesh = mesh_for(c0, 0.0, required, static_cast<int>(std::ceil(model_.length / mesh.h_base)));
    const auto& x = mesh.x;
    const int nn = static_cast<int>(x.size());
    auto node = [&](double xx) {
      for (int i = 0; i < nn; ++i)
        if (std::abs(x[i] - xx) <= 1e-12 * model_.length) return i;
      return static_cast<int>(std::lower_bound(x.begin(), x.end(), xx) - x.begin());
    };
    Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nn) * c.mc);
    for (const auto& p : loads) {
      const int i = node(std::clamp(p.x, 0.0, model_.length));
      Eigen::VectorXd fc = c.W.transpose() * model_.load_vector(p) / c.sigma;
      if (const auto* e = c.condition_at(x, static_cast<std::size_t>(i))) fc = e->B.transpose() * fc;
      f.segment(static_cast<Eigen::Index>(i) * c.mc, c.mc) += fc;
    }
    std::vector<std::optional<SegmentLoad>> seg_loads;
    if (!distributed.empty()) seg_loads = segment_loads(c, x, distributed, model_, f);
    Assembled a = assemble(c, 0.0, mesh);
    Eigen::VectorXd d, amp;  // d: nodal values (the elastic part when split), amp: rigid amplitudes
    if (rl) {
      solve_split(*rl, a.K, x, f, d, amp);
    } else {
      // Rigid motions were excluded above, structurally: a failure here is numerical, not the
      // supports' (and no pivot-ratio test: a short piece is stiff, not singular).
      try {
        d = a.K.solve(f, 0.0);
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(fmt::format("static solve of the {} family failed numerically: {}",
                                             to_string(c.family), e.what()));
      }
    }
    for (std::size_t j = 0; j < probes.size(); ++j) {
      // The elastic field from its nodal values (its section forces are those of the whole
      // solution: K(0) times a rigid motion is zero), the rigid motions exactly.
      Eigen::VectorXd dc = near_node<double>(c, 0.0, x, mesh.h_base, d, node(at[j].anchor), at[j].t, seg_loads);
      if (rl) dc += rl->phi(std::clamp(probes[j][0], 0.0, model_.length)) * amp;
      qp[j] += c.W * dc;
    }
    if (reactions && model_.kind == SceneKind::Beam) add_reactions(c, mesh, rl ? &*rl : nullptr, d, amp, f, react);
    if (integrals && rl) integrals->complete = false;
    if (integrals && !rl) {
      detail::integrate_fields(c, x, mesh.h_base, d, f, seg_loads, *integrals);
    }
  }
  if (reactions) *reactions = point_reactions(model_, react);
  std::vector<Deflection> out;
  for (std::size_t j = 0; j < probes.size(); ++j) {
    Deflection d = model_.section_response(qp[j], probes[j][1]);
    d.position = probes[j];
    out.push_back(d);
  }
  return out;
}

void LineAnalysis::add_reactions(const ClassLine& c, const Mesh& mesh, const detail::RigidLine* rl, const Eigen::VectorXd& d,
                                 const Eigen::VectorXd& amp, const Eigen::VectorXd& f,
                                 std::map<double, Eigen::VectorXd>& react) {
  const auto& x = mesh.x;
  const int nn = static_cast<int>(x.size()), mc = c.mc;
  // The whole nodal solution: the elastic part and the rigid motions.
  Eigen::VectorXd full = d;
  if (rl)
    for (int i = 0; i < nn; ++i)
      full.segment(static_cast<Eigen::Index>(i) * mc, mc) +=
          rl->node_psi(x[static_cast<std::size_t>(i)], c.condition_at(x, static_cast<std::size_t>(i))) * amp;
  // K without the rigid split's anchors; its held rows are the beam's own: K d - f there is what
  // the support adds, and a spring adds -k d.
  const Eigen::VectorXd Kd = assemble(c, 0.0, mesh).K.multiply(full);
  for (int i = 0; i < nn; ++i) {
    const auto* ce = c.condition_at(x, static_cast<std::size_t>(i));
    if (!ce) continue;
    const Eigen::Index o = static_cast<Eigen::Index>(i) * mc;
    Eigen::VectorXd rB = Eigen::VectorXd::Zero(mc);
    for (int j = ce->n_free; j < mc; ++j) rB[j] = Kd[o + j] - f[o + j];
    if (ce->n_free > 0 && ce->K.size() > 0) rB.head(ce->n_free) = -(ce->K * full.segment(o, ce->n_free));
    const Eigen::VectorXd fields = c.sigma * c.Winv.transpose() * (ce->B * rB);
    auto it = react.find(ce->x);
    if (it == react.end()) react.emplace(ce->x, fields);
    else it->second += fields;
  }
}

std::vector<std::complex<double>> LineAnalysis::receptance(std::array<double, 2> excite, std::array<double, 2> observe,
                                                           const std::vector<double>& omegas, double eta,
                                                           int* skipped, std::string* reason) {
  std::vector<std::complex<double>> H(omegas.size(), 0.0);
  if (skipped) *skipped = 0;
  if (omegas.empty()) return H;
  PointLoad unit;
  unit.x = excite[0];
  unit.y = excite[1];
  unit.Fz = 1.0;
  const Eigen::VectorXd f_full = model_.load_vector(unit);
  const Eigen::RowVectorXd o_full = model_.w_observer(observe[1]);
  const double w_max = *std::max_element(omegas.begin(), omegas.end());
  const std::complex<double> cdamp(1.0, eta);
  std::vector<char> bad(omegas.size(), 0);
  std::vector<std::string> failure(omegas.size());  // per sample (samples run side by side)
  for (const auto& line : lines_) {
    ClassLine& c = *line;
    const Eigen::VectorXd fc0 = c.W.transpose() * f_full / c.sigma;
    const Eigen::RowVectorXd oc = o_full * c.W;
    if (fc0.norm() == 0.0 || oc.norm() == 0.0) continue;
    std::vector<double> required = {std::clamp(excite[0], 0.0, model_.length)};
    const Attached ob = attach({observe[0]}, required, model_.length, 1e-4 * model_.length)[0];
    const Mesh mesh = mesh_for(c, w_max * w_max, required);
    const auto& x = mesh.x;
    const int nn = static_cast<int>(x.size());
    auto node = [&](double xx) {
      for (int i = 0; i < nn; ++i)
        if (std::abs(x[i] - xx) <= 1e-12 * model_.length) return i;
      return 0;
    };
    const int ie = node(std::clamp(excite[0], 0.0, model_.length));
    const int io = node(ob.anchor);
    Eigen::VectorXd fc = fc0;
    if (const auto* e = c.condition_at(x, static_cast<std::size_t>(ie))) fc = e->B.transpose() * fc;
    // The observation point: a node, or reached from the node within 1e-4 L of it (near_node).
    auto observe_at = [&](const auto& d, auto lambda) {
      using Scalar = decltype(lambda);
      const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> dc = near_node<Scalar>(c, lambda, x, mesh.h_base, d, io, ob.t);
      return (oc.template cast<Scalar>() * dc)(0);
    };
    // The samples side by side: each solve reads the class and the mesh and writes its own slot.
    side_by_side(omegas.size(), [&](std::size_t s) {
      const double lam = omegas[s] * omegas[s];
      if (eta == 0.0) {
        Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nn) * c.mc);
        f.segment(static_cast<Eigen::Index>(ie) * c.mc, c.mc) = fc;
        try {
          const Eigen::VectorXd d = assemble(c, lam, mesh).K.solve(f);
          H[s] += observe_at(d, lam);
        } catch (const std::runtime_error& e) {
          bad[s] = 1;
          failure[s] = e.what();
        }
      } else {
        Eigen::VectorXcd f = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(nn) * c.mc);
        f.segment(static_cast<Eigen::Index>(ie) * c.mc, c.mc) = fc.cast<std::complex<double>>() / cdamp;
        try {
          const std::complex<double> lam_c = std::complex<double>(lam) / cdamp;
          const Eigen::VectorXcd d = assemble(c, lam_c, mesh).solve(f);
          H[s] += observe_at(d, lam_c);
        } catch (const std::runtime_error& e) {
          bad[s] = 1;
          failure[s] = e.what();
        }
      }
    });
  }
  for (std::size_t s = 0; s < omegas.size(); ++s) {
    if (bad[s] && reason && reason->empty()) *reason = fmt::format("at {:.6g} rad/s: {}", omegas[s], failure[s]);
    if (bad[s]) {
      H[s] = std::numeric_limits<double>::quiet_NaN();
      if (skipped) ++*skipped;
    }
  }
  return H;
}

}  // namespace modalbench::dtfm
