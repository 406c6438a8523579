// LineAnalysis forced responses: static deflection under point loads and receptance FRFs.
#include "modalbench/dtfm/analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

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

/// Class displacements (end nodes out of their B coordinates) at x[i] + t from a solution d: the
/// state of node i on the side of t (its displacement and the adjacent segment's end force)
/// carried by exp(A t).
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> near_node(const LineAnalysis::ClassLine& c, Scalar lambda,
                                                   const std::vector<double>& x, double h_base,
                                                   const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& d, int i, double t) {
  using Mat = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vec = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const int nn = static_cast<int>(x.size()), mc = c.mc;
  auto node_d = [&](int k) {
    Vec v = d.segment(static_cast<Eigen::Index>(k) * mc, mc);
    if (k == 0) v = c.ends[0].B.template cast<Scalar>() * v;
    if (k == nn - 1) v = c.ends[1].B.template cast<Scalar>() * v;
    return v;
  };
  if (t == 0.0) return node_d(i);
  const bool right = t > 0;
  const int a = right ? i : i - 1;
  if (a < 0 || a + 1 >= nn) return node_d(i);  // cannot happen: points lie in [0, L]
  const Mat A = c.state(lambda);
  const double h = x[static_cast<std::size_t>(a) + 1] - x[static_cast<std::size_t>(a)];
  const int levels = detail::doubling_levels(h, h_base);
  const Mat K = segment_k(A, h, levels).K;
  Vec dd(2 * mc), eta(2 * mc);
  dd << node_d(a), node_d(a + 1);
  // K [d_a; d_b] = [-F(a+); F(b-)].
  if (right) eta << node_d(i), -(K.topRows(mc) * dd);
  else eta << node_d(i), K.bottomRows(mc) * dd;
  Mat B = A * Scalar(t);
  const Eigen::VectorXd s = balance_in_place(B, 20);
  const Mat T = s.template cast<Scalar>().asDiagonal() * Mat(B.exp()) * s.cwiseInverse().template cast<Scalar>().asDiagonal();
  return (T * eta).head(mc);
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

std::vector<Deflection> LineAnalysis::statics(const std::vector<PointLoad>& loads,
                                              const std::vector<std::array<double, 2>>& probes) {
  std::vector<double> required;
  for (const auto& p : loads) required.push_back(std::clamp(p.x, 0.0, model_.length));
  std::vector<double> probe_x;
  for (const auto& p : probes) probe_x.push_back(p[0]);
  const std::vector<Attached> at = attach(probe_x, required, model_.length, 1e-4 * model_.length);
  const int m = model_.m;
  std::vector<Eigen::VectorXd> qp(probes.size(), Eigen::VectorXd::Zero(m));
  // Each class's share of the loads (physical units): a class is unloaded when its share is
  // rounding of the total (a moment at an end leaks 1e-17 of itself into other classes), not
  // when it is exactly 0.
  std::vector<double> share(lines_.size(), 0.0);
  double total_share = 0;
  for (std::size_t ci = 0; ci < lines_.size(); ++ci) {
    for (const auto& p : loads) share[ci] += (lines_[ci]->W.transpose() * model_.load_vector(p)).squaredNorm();
    total_share += share[ci];
  }
  for (const auto& line : lines_) {
    ClassLine& c0 = *line;
    if (!(share[static_cast<std::size_t>(c0.index)] > 1e-24 * total_share)) continue;
    // A class with rigid motions of its own (beams) is solved split into them and its elastic part
    // (detail::RigidLine): a mechanism is then a rigid motion no support reaches, structurally, and
    // a near-mechanism keeps its digits however soft its springs.
    const std::optional<detail::RigidLine> rl = detail::rigid_line(c0, model_.length);
    if (rl && rl->unrestrained > 0)
      throw std::runtime_error(fmt::format(
          "mechanism: the supports leave {} rigid-body motion(s) of the loaded {} family free ({} / {})",
          rl->unrestrained, to_string(c0.family), model_.ends[0].text, model_.ends[1].text));
    if (!rl) {
      // Otherwise a loaded class must be free of rigid-body motions by its count just above zero:
      // its static solve would give rounding noise divided by rounding noise.
      const double delta = kRigidThreshold * model_.lambda_scale;
      const Mesh near_zero = mesh_for(c0, delta, {});
      if (const int rigid = count_det(c0, delta, near_zero).count; rigid > 0)
        throw std::runtime_error(fmt::format(
            "mechanism: the supports leave {} rigid-body motion(s) of the loaded {} family free, or restrain them "
            "below 1e-10 of the model's stiffness scale, which dtfm cannot resolve ({} / {})",
            rigid, to_string(c0.family), model_.ends[0].text, model_.ends[1].text));
    }
    const ClassLine& c = rl ? rl->line : c0;
    const Mesh mesh = mesh_for(c0, 0.0, required);
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
      if (i == 0) fc = c.ends[0].B.transpose() * fc;
      if (i == nn - 1) fc = c.ends[1].B.transpose() * fc;
      f.segment(static_cast<Eigen::Index>(i) * c.mc, c.mc) += fc;
    }
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
      Eigen::VectorXd dc = near_node<double>(c, 0.0, x, mesh.h_base, d, node(at[j].anchor), at[j].t);
      if (rl) dc += rl->phi(std::clamp(probes[j][0], 0.0, model_.length)) * amp;
      qp[j] += c.W * dc;
    }
  }
  std::vector<Deflection> out;
  for (std::size_t j = 0; j < probes.size(); ++j) {
    Deflection d = model_.section_response(qp[j], probes[j][1]);
    d.position = probes[j];
    out.push_back(d);
  }
  return out;
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
    if (ie == 0) fc = c.ends[0].B.transpose() * fc;
    if (ie == nn - 1) fc = c.ends[1].B.transpose() * fc;
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
