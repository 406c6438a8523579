// LineAnalysis mode shapes. Each mode belongs to one symmetry class; in that class's line the
// mode is the null vector of the assembled K(omega^2), found by inverse iteration just off the
// root (a block of vectors when the class has the root more than once; for the rigid modes the
// null space of K(0), by inverse iteration at a small negative lambda) on nodes at the sample
// positions. Inside each gap the displacements at every base-piece node follow by running the
// doubling's condensation backwards; a base piece's transfer matrix exp(A s) is well
// conditioned, so the state y = [q; f] at its left node (f from its dynamic stiffness) gives
// the exact field of the prism ODE anywhere in it. Modal masses int q^T A02 q dx and
// participations int q^T A02 r_d dx are GSL quadratures of that field; the sampled values are
// the section response of the nodal fields (rigid-body fit of a beam's prisms, linear in y
// between a plate's strip lines).
#include "modalbench/dtfm/analysis.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "analysis_detail.hpp"
#include "modalbench/numerics/balancing.hpp"
#include "modalbench/numerics/line_system.hpp"
#include "modalbench/numerics/quadrature.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"
#include "modalbench/numerics/symmetric_factor.hpp"

namespace modalbench::dtfm {

namespace {

using detail::to_fields;

/// Relative distance below which two roots of one class are one (repeated) eigenvalue.
constexpr double kSameRoot = 1e-8;
/// Inverse iteration shift above a root, relative.
constexpr double kShift = 1e-10;
constexpr int kInverseSteps = 2;

double component(const Deflection& d, int dof) {
  switch (dof) {
    case 0: return d.u;
    case 1: return d.v;
    case 2: return d.w;
    case 3: return d.theta_x;
    case 4: return d.theta_y;
    case 5: return d.theta_z;
    default: throw std::invalid_argument(fmt::format("dtfm: no shape component {}", dof));
  }
}

/// exp(A s) of one state matrix (balanced), memoized by s: segments of one length share their
/// quadrature abscissae, so each distinct s is exponentiated once.
class Transfer {
 public:
  explicit Transfer(Eigen::MatrixXd A) : A_(std::move(A)) {}
  const Eigen::MatrixXd& operator()(double s) {
    if (const auto it = memo_.find(s); it != memo_.end()) return it->second;
    Eigen::MatrixXd B = A_ * s;
    const Eigen::VectorXd d = balance_in_place(B, 20);
    Eigen::MatrixXd T = d.asDiagonal() * Eigen::MatrixXd(B.exp()) * d.cwiseInverse().asDiagonal();
    return memo_.emplace(s, std::move(T)).first->second;
  }

 private:
  Eigen::MatrixXd A_;
  std::map<double, Eigen::MatrixXd> memo_;
};

/// Sorted distinct values (to a tolerance).
std::vector<double> distinct(std::vector<double> v, double tol) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || x - out.back() > tol) out.push_back(x);
  return out;
}

/// A gap between two nodes as a long segment of 2^levels base pieces: K[j] is the dynamic
/// stiffness of a piece of length h / 2^j (K[0] the gap's, K[levels] the base piece's), built
/// by doubling exactly as the assembly builds it; S[j - 1] (j >= 1) the factorized middle block
/// K[j]_22 + K[j]_11 joining two pieces of length h / 2^j.
struct Gap {
  double h = 0, h_base = 0;
  int levels = 0, piece = 0;  ///< piece: of a stepped line
  std::vector<Eigen::MatrixXd> K;
  std::vector<SymFactor> S;
  double min_pivot_rel = 1;  ///< of the middle blocks (a conditioning hint, as LongSegment's)
};

Gap make_gap(const Eigen::MatrixXd& A, double h, double h_base, int piece) {
  Gap g;
  g.h = h;
  g.piece = piece;
  g.levels = detail::doubling_levels(h, h_base);
  g.h_base = std::ldexp(h, -g.levels);
  for (int j = 0; j <= g.levels; ++j) {
    const LongSegment seg = long_segment_dynamic_stiffness(A, std::ldexp(h, -j), g.levels - j);
    g.K.push_back(seg.K);
    if (j == 0) g.min_pivot_rel = seg.min_pivot_rel;
  }
  const Eigen::Index m = A.rows() / 2;
  for (int j = 1; j <= g.levels; ++j)
    g.S.emplace_back(Eigen::MatrixXd(g.K[j].bottomRightCorner(m, m) + g.K[j].topLeftCorner(m, m)));
  return g;
}

/// Displacements at the 2^levels - 1 interior nodes of a gap from those at its ends: the middle
/// node of a piece of length h / 2^j solves S[j] d_mid = -(K21 d_left + K12 d_right) with
/// K = K[j + 1] (its halves): the condensation of the doubling, run backwards.
std::vector<Eigen::MatrixXd> interior(const Gap& g, const Eigen::MatrixXd& left, const Eigen::MatrixXd& right) {
  const std::size_t n = std::size_t{1} << g.levels;
  std::vector<Eigen::MatrixXd> d(n + 1);
  d[0] = left;
  d[n] = right;
  const Eigen::Index m = left.rows();
  for (int j = 0; j < g.levels; ++j) {
    const std::size_t step = n >> j, half = step / 2;
    const Eigen::MatrixXd& K = g.K[static_cast<std::size_t>(j) + 1];
    for (std::size_t k = 0; k < n; k += step)
      d[k + half] = -g.S[static_cast<std::size_t>(j)].solve(K.bottomLeftCorner(m, m) * d[k] +
                                                           K.topRightCorner(m, m) * d[k + step]);
  }
  return {d.begin() + 1, d.end() - 1};
}

/// A cluster's shapes along its line, refined to every base-piece node: the displacements D there
/// (class coordinates; the end nodes' in the ends' bases) and the states Y = [q; f].
struct FineNodes {
  std::vector<Eigen::MatrixXd> D, Y;
  std::vector<const Gap*> piece;     // per fine segment: its gap (base piece length and matrix)
  std::vector<std::size_t> fine_of;  // each node's index among D's
};

/// The Gram matrix int q_a^T M q_b dx of a cluster's shapes, their participations int q_a^T M r_d dx
/// and the directions the class moves in.
struct MassIntegrals {
  Eigen::MatrixXd G, Gamma;
  std::vector<int> dirs;
};

/// The distinct gaps of nodes x (per piece and length) and the worst conditioning of their middle
/// blocks (`worst`, lowered from its value).
std::vector<Gap> make_gaps(const LineAnalysis::ClassLine& c, const std::vector<Eigen::MatrixXd>& A,
                           const std::vector<double>& x, double h_base, double& worst) {
  std::vector<Gap> gaps;
  for (std::size_t g = 0; g + 1 < x.size(); ++g) {
    const double h = x[g + 1] - x[g];
    const int piece = c.piece_of(x[g], x[g + 1]);
    if (std::any_of(gaps.begin(), gaps.end(),
                    [&](const Gap& e) { return e.piece == piece && std::abs(h - e.h) <= 1e-9 * h; }))
      continue;
    gaps.push_back(make_gap(A[static_cast<std::size_t>(piece)], h, h_base, piece));
    worst = std::min(worst, gaps.back().min_pivot_rel);
  }
  return gaps;
}

/// The null vectors V (nodes x of the gaps) carried to every base-piece node and their states there.
FineNodes fine_nodes(const LineAnalysis::ClassLine& c, const std::vector<double>& x, const std::vector<Gap>& gaps,
                     const Eigen::MatrixXd& V) {
  const int mc = c.mc;
  const int nc = static_cast<int>(x.size());
  const auto p = V.cols();
  // Displacements at every base-piece node (class coordinates; the end nodes' in the ends'
  // bases), the gaps' interiors by condensation at lambda, and the state [q; f] at each node
  // (f from the base piece's dynamic stiffness).
  FineNodes fn;
  auto& D = fn.D;
  auto& Y = fn.Y;
  fn.fine_of.assign(static_cast<std::size_t>(nc), 0);
  for (int i = 0; i < nc; ++i) {
    Eigen::MatrixXd d = V.middleRows(static_cast<Eigen::Index>(i) * mc, mc);
    if (const auto* e = c.condition_at(x, static_cast<std::size_t>(i))) d = e->B * d;
    if (i == 0) {
      D.push_back(d);
      continue;
    }
    const double h = x[i] - x[i - 1];
    const int pc = c.piece_of(x[i - 1], x[i]);
    const Gap* gap = &gaps.front();
    for (const auto& e : gaps)
      if (e.piece == pc && std::abs(h - e.h) <= 1e-9 * h) gap = &e;
    const std::vector<Eigen::MatrixXd> inner = interior(*gap, D.back(), d);
    const std::size_t pieces = inner.size() + 1;
    for (std::size_t k = 0; k < pieces; ++k) {
      D.push_back(k + 1 == pieces ? d : inner[k]);
      fn.piece.push_back(gap);
    }
    fn.fine_of[static_cast<std::size_t>(i)] = D.size() - 1;
  }
  const int nn = static_cast<int>(D.size());
  Y.assign(static_cast<std::size_t>(nn), Eigen::MatrixXd(2 * mc, p));
  for (int i = 0; i + 1 < nn; ++i) {
    Eigen::MatrixXd dd(2 * mc, p);
    dd << D[i], D[i + 1];
    const Eigen::MatrixXd fk = fn.piece[i]->K.back() * dd;  // [-f(0); f(h)]
    Y[i] << D[i], -fk.topRows(mc);
    if (i + 2 == nn) Y[i + 1] << D[i + 1], fk.bottomRows(mc);
  }
  return fn;
}

/// The Gram matrix and participations of the fields between the fine nodes, by quadrature of the
/// exact field segment by segment (A: the state matrix per piece).
MassIntegrals mass_integrals(const PrismModel& model, const LineAnalysis::ClassLine& c,
                             const std::vector<Eigen::MatrixXd>& A, const Eigen::MatrixXd& translations,
                             const FineNodes& fn) {
  const int mc = c.mc;
  const auto& D = fn.D;
  const auto& Y = fn.Y;
  const auto& piece = fn.piece;
  const Eigen::Index p = D.front().cols();
  const int nn = static_cast<int>(D.size());
  // Gram matrix int q_a^T M q_b dx and participations int q_a^T M r_d dx, segment by segment.
  // Per piece: the class mass, the translations' forces and the transfer matrices.
  std::vector<Eigen::MatrixXd> Mqs, Rcs;
  std::vector<Transfer> T;
  for (int k = 0; k < c.pieces(); ++k) {
    const Eigen::MatrixXd& Mphys = k == 0 ? model.M : model.steps[static_cast<std::size_t>(k) - 1].M;
    Mqs.push_back(c.W.transpose() * Mphys * c.W);
    Rcs.push_back(c.W.transpose() * Mphys * translations);
    T.emplace_back(A[static_cast<std::size_t>(k)]);
  }
  MassIntegrals mi{Eigen::MatrixXd::Zero(p, p), Eigen::MatrixXd::Zero(p, 3), {}};
  auto& G = mi.G;
  auto& Gamma = mi.Gamma;
  for (int dir = 0; dir < 3; ++dir) {
    double nrm = 0, all = 0;
    for (const auto& Rc : Rcs) {
      nrm = std::max(nrm, Rc.col(dir).norm());
      all = std::max(all, Rc.norm());
    }
    if (nrm > 1e-14 * all) mi.dirs.push_back(dir);  // the class moves in dir
  }
  for (int i = 0; i + 1 < nn; ++i) {
    const double h = piece[i]->h_base;
    const auto k_piece = static_cast<std::size_t>(piece[i]->piece);
    const Eigen::MatrixXd& Mq = Mqs[k_piece];
    const Eigen::MatrixXd& Rc = Rcs[k_piece];
    // The field q (and M q) at the quadrature abscissae, shared by the integrands of this segment.
    std::map<double, std::pair<Eigen::MatrixXd, Eigen::MatrixXd>> field;
    auto at = [&](double s) -> const std::pair<Eigen::MatrixXd, Eigen::MatrixXd>& {
      if (const auto it = field.find(s); it != field.end()) return it->second;
      Eigen::MatrixXd d = T[k_piece](s).topRows(mc) * Y[i];
      Eigen::MatrixXd md = Mq * d;
      return field.emplace(s, std::make_pair(std::move(d), std::move(md))).first->second;
    };
    // Absolute tolerance on the natural scale of each integrand (a cross term or a
    // participation may cancel within a segment: GSL cannot reach a relative one there).
    const double size = std::max({D[i].norm(), D[i + 1].norm(), at(0.5 * h).first.norm()});
    auto integral = [&](auto&& g, double scale) {
      return integrate([&](double s) { return g(at(s)); }, 0.0, h, 1e-12, 1e-12 * h * scale).value;
    };
    using Field = std::pair<Eigen::MatrixXd, Eigen::MatrixXd>;
    for (Eigen::Index u = 0; u < p; ++u) {
      for (Eigen::Index v = u; v < p; ++v) {
        G(u, v) += integral([&](const Field& f) { return f.first.col(u).dot(f.second.col(v)); },
                            Mq.norm() * size * size);
        G(v, u) = G(u, v);
      }
      for (int dir : mi.dirs)
        Gamma(u, dir) += integral([&](const Field& f) { return Rc.col(dir).dot(f.first.col(u)); },
                                  Rc.col(dir).norm() * size);
    }
  }
  return mi;
}

/// Adds the point masses at nodes x to the Gram matrix and participations of null vectors V.
void add_point_masses(const LineAnalysis::ClassLine& c, const std::vector<double>& x, const Eigen::MatrixXd& V,
                      const Eigen::MatrixXd& translations, MassIntegrals& mi) {
  const int mc = c.mc;
  const int nc = static_cast<int>(x.size());
  // The point masses at their nodes.
  for (int i = 0; i < nc; ++i) {
    const auto* e = c.condition_at(x, static_cast<std::size_t>(i));
    if (!e || e->Mc.size() == 0) continue;
    const Eigen::MatrixXd d = e->B * V.middleRows(static_cast<Eigen::Index>(i) * mc, mc);
    mi.G += d.transpose() * e->Mc * d;
    const Eigen::MatrixXd Rp = c.W.transpose() * e->Mfields * translations;
    for (int dir : mi.dirs) mi.Gamma.col(dir) += d.transpose() * Rp.col(dir);
  }
}

/// The basis change Cb that mass-orthonormalizes p modes of Gram matrix G (identity for one).
Eigen::MatrixXd mass_orthonormal(const Eigen::MatrixXd& G, Eigen::Index p, double lambda) {
  // Several modes: mass-orthonormalized (G = L L^T, basis V L^-T), which keeps the first.
  Eigen::MatrixXd Cb = Eigen::MatrixXd::Identity(p, p);
  if (p > 1) {
    Eigen::LLT<Eigen::MatrixXd> llt(G);
    if (llt.info() != Eigen::Success)
      throw std::runtime_error(
          fmt::format("the {} modes at omega^2 = {:.6g} are not independent in the mass", p, lambda));
    Cb = llt.matrixU().solve(Eigen::MatrixXd::Identity(p, p));
  }
  return Cb;
}

/// The node of x at sample position xx (sample positions are nodes).
int sample_node(const std::vector<double>& x, double xx, double length) {
  const int nc = static_cast<int>(x.size());
  for (int i = 0; i < nc; ++i)
    if (std::abs(x[i] - xx) <= 1e-9 * length) return i;
  throw std::logic_error(fmt::format("dtfm: shape sample x = {} is not a node", xx));
}

/// Per component: the sampled section response of null vectors V (points x modes).
std::vector<Eigen::MatrixXd> sample_values(const PrismModel& model, const LineAnalysis::ClassLine& c,
                                           const std::vector<double>& x, const Eigen::MatrixXd& V,
                                           const ModeShapes& out) {
  const Eigen::Index p = V.cols();
  // Samples: the section response of the nodal fields (sample positions are nodes).
  std::vector<std::vector<Eigen::VectorXd>> q(static_cast<std::size_t>(p));
  for (Eigen::Index u = 0; u < p; ++u) q[u] = to_fields(c, Eigen::VectorXd(V.col(u)), x);
  const std::size_t np = out.points.size(), ncomp = out.components.size();
  std::vector<Eigen::MatrixXd> raw(ncomp, Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(np), p));
  for (std::size_t s = 0; s < np; ++s) {
    const auto& pt = out.points[s];
    const int i = sample_node(x, std::clamp(pt[0], 0.0, model.length), model.length);
    for (Eigen::Index u = 0; u < p; ++u) {
      const Deflection d = model.section_response(q[u][i], pt[1]);
      for (std::size_t k = 0; k < ncomp; ++k)
        raw[k](static_cast<Eigen::Index>(s), u) = component(d, out.components[k]);
    }
  }
  return raw;
}

/// The bending moment My at the sample points (points x modes) from the states at the fine nodes.
Eigen::MatrixXd sample_moments(const PrismModel& model, const LineAnalysis::ClassLine& c,
                               const std::vector<double>& x, const FineNodes& fn,
                               const std::vector<std::array<double, 2>>& points) {
  const int mc = c.mc;
  const Eigen::Index p = fn.D.front().cols();
  const std::size_t np = points.size();
  // My: the section's moment about y of the field forces f = sigma W^-T f_c (the class line's
  // scaled forces back to the fields, as the reactions'), with the rigid rotation theta_y's column
  // of the fields; sagging positive.
  const Eigen::RowVectorXd row = -c.sigma * model.rigid_motions.col(4).transpose() * c.Winv.transpose();
  Eigen::MatrixXd raw_m = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(np), p);
  for (std::size_t s = 0; s < np; ++s) {
    const int i = sample_node(x, std::clamp(points[s][0], 0.0, model.length), model.length);
    raw_m.row(static_cast<Eigen::Index>(s)) = row * fn.Y[fn.fine_of[static_cast<std::size_t>(i)]].bottomRows(mc);
  }
  return raw_m;
}

}  // namespace

ModeShapes LineAnalysis::mode_shapes(const ModeList& modes, const std::vector<std::array<double, 2>>& points,
                                     const std::vector<int>& components, std::array<bool, 3> directions,
                                     bool moments) {
  ModeShapes out;
  out.points = points;
  out.components = components;
  out.directions = directions;
  const std::size_t n = modes.omega_rad_s.size();
  if (modes.cls.size() != n) throw std::logic_error("dtfm: mode_shapes needs the class of every mode");
  out.values.assign(n, {});
  out.generalized_mass.assign(n, 0.0);
  out.participation.assign(n, {0.0, 0.0, 0.0});
  moments = moments && model_.kind == SceneKind::Beam;
  if (moments) out.moments.assign(n, {});
  if (n == 0 || points.empty()) return out;
  const double L = model_.length;
  std::vector<double> xs;
  for (const auto& p : points) xs.push_back(std::clamp(p[0], 0.0, L));
  xs = distinct(xs, 1e-12 * L);
  // Unit rigid translations of the section over the fields (columns x, y, z).
  const int m = model_.m;
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(m, 3);
  for (int d = 0; d < 3; ++d) {
    if (!directions[d]) continue;
    if (model_.kind == SceneKind::Plate) {
      for (int k = 0; k < m; ++k)
        if (model_.field_dof[k] == d) R(k, d) = 1.0;
    } else {
      R.col(d) = model_.rigid_motions.col(d);
    }
  }
  // Modes of one class at one root (all rigid ones of a class: root 0) are solved together.
  struct Cluster {
    int cls;
    double lambda;
    std::vector<std::size_t> modes;
  };
  std::vector<Cluster> clusters;
  for (std::size_t k = 0; k < n; ++k) {
    const double lam = k < static_cast<std::size_t>(modes.rigid) ? 0.0 : modes.omega_rad_s[k] * modes.omega_rad_s[k];
    Cluster* hit = nullptr;
    for (auto& c : clusters)
      if (c.cls == modes.cls[k] && std::abs(c.lambda - lam) <= kSameRoot * std::max(c.lambda, lam)) hit = &c;
    if (hit) hit->modes.push_back(k);
    else clusters.push_back({modes.cls[k], lam, {k}});
  }
  for (const auto& c : clusters) {
    if (c.cls < 0 || c.cls >= classes()) throw std::logic_error("dtfm: mode_shapes: a mode without a class");
    cluster_shapes(*lines_[static_cast<std::size_t>(c.cls)], c.lambda, c.modes, xs, R, moments, out);
  }
  return out;
}

void LineAnalysis::cluster_shapes(ClassLine& c, double lambda, const std::vector<std::size_t>& which,
                                  const std::vector<double>& xs, const Eigen::MatrixXd& translations,
                                  bool moments, ModeShapes& out) {
  const auto p = static_cast<Eigen::Index>(which.size());
  std::vector<Eigen::MatrixXd> A;  // per piece
  for (int k = 0; k < c.pieces(); ++k) A.push_back(c.state(lambda, k));
  // Nodes at the sample positions; each gap a long segment of 2^levels base pieces. A gap whose
  // condensed middle blocks are nearly singular at lambda (a sub-piece's clamped frequency)
  // is split (as count_det does), so that the interior recovery below stays well conditioned.
  Mesh mesh = mesh_for(c, lambda, xs);
  std::vector<Gap> gaps;
  for (int attempt = 0;; ++attempt) {
    double worst = 1.0;
    gaps = make_gaps(c, A, mesh.x, mesh.h_base, worst);
    if (worst >= 1e-10 || attempt >= 4) break;
    mesh = refined(mesh);
  }
  const Eigen::MatrixXd V = shape_null_space(c, lambda, mesh, p);
  const FineNodes fn = fine_nodes(c, mesh.x, gaps, V);
  MassIntegrals mi = mass_integrals(model_, c, A, translations, fn);
  add_point_masses(c, mesh.x, V, translations, mi);
  const Eigen::MatrixXd Cb = mass_orthonormal(mi.G, p, lambda);
  const Eigen::MatrixXd Gn = Cb.transpose() * mi.G * Cb, Gamman = Cb.transpose() * mi.Gamma;

  const std::vector<Eigen::MatrixXd> raw = sample_values(model_, c, mesh.x, V, out);
  Eigen::MatrixXd raw_m;
  if (moments) raw_m = sample_moments(model_, c, mesh.x, fn, out.points);
  const std::size_t np = out.points.size(), ncomp = out.components.size();
  for (Eigen::Index j = 0; j < p; ++j) {
    const std::size_t mode = which[static_cast<std::size_t>(j)];
    if (moments) {
      const Eigen::VectorXd col = raw_m * Cb.col(j);
      out.moments[mode].assign(col.data(), col.data() + col.size());
    }
    auto& vals = out.values[mode];
    vals.assign(ncomp, std::vector<double>(np, 0.0));
    for (std::size_t k = 0; k < ncomp; ++k) {
      const Eigen::VectorXd col = raw[k] * Cb.col(j);
      for (std::size_t s = 0; s < np; ++s) vals[k][s] = col[static_cast<Eigen::Index>(s)];
    }
    out.generalized_mass[mode] = Gn(j, j);
    for (int dir = 0; dir < 3; ++dir) out.participation[mode][dir] = Gamman(j, dir);
  }
}

/// The null space of class c's K at lambda on mesh (p vectors, orthonormal) by inverse iteration.
Eigen::MatrixXd LineAnalysis::shape_null_space(ClassLine& c, double lambda, const Mesh& mesh, Eigen::Index p) {
  const int mc = c.mc;
  const bool rigid = lambda == 0.0;
  const int nc = static_cast<int>(mesh.x.size());
  const Eigen::Index N = static_cast<Eigen::Index>(nc) * mc;
  // The null space by inverse iteration (orthonormalized block), just above the root (below 0
  // for the rigid modes: K is then positive definite, the rigid motions its smallest part). A
  // root known to rounding can put K(shift) within rounding of singular (a pivot of 1e-15 of its
  // block): the shift then moves out by factors of 100, with one more step each time (the
  // iteration's contraction, shift / gap to the next root of the class, stays far below 1e-4).
  Eigen::MatrixXd V(N, p);
  for (int attempt = 0;; ++attempt) {
    const double rel = kShift * std::pow(100.0, attempt);
    const double shift =
        rigid ? -std::max(kRigidThreshold * model_.lambda_scale, 10.0 * rigid_shift_) : lambda * (1.0 + rel);
    const long unknowns_before = max_unknowns_;
    const Assembled a = assemble(c, shift, mesh);
    max_shape_unknowns_ = std::max<long>(max_shape_unknowns_, a.K.free_dofs());
    max_unknowns_ = unknowns_before;  // the size of the modes' systems, as without shapes
    for (Eigen::Index i = 0; i < N; ++i)
      for (Eigen::Index j = 0; j < p; ++j)
        V(i, j) = 1.0 + 0.5 * std::sin(1.7 * static_cast<double>(i) + 0.3 + 1.1 * static_cast<double>(j));
    try {
      for (int step = 0; step < kInverseSteps + attempt; ++step) {
        for (Eigen::Index j = 0; j < p; ++j) V.col(j) = a.K.solve(Eigen::VectorXd(V.col(j)), 0.0);
        if (!V.allFinite() || V.norm() == 0.0)
          throw std::runtime_error(fmt::format("inverse iteration broke down at omega^2 = {:.6g}", lambda));
        Eigen::HouseholderQR<Eigen::MatrixXd> qr(V);
        V = qr.householderQ() * Eigen::MatrixXd::Identity(N, p);
      }
      break;
    } catch (const std::runtime_error&) {
      if (rigid || attempt >= 2) throw;
    }
  }
  return V;
}

}  // namespace modalbench::dtfm
