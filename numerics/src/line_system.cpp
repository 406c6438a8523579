#include "modalbench/numerics/line_system.hpp"
#include "modalbench/numerics/symmetric_factor.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <limits>
#include <stdexcept>
#include <string>

#include "modalbench/numerics/balancing.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"
#include "line_variation.hpp"

namespace modalbench {

int AssembledLine::node_at(double x) const {
  for (std::size_t i = 0; i < xi.size(); ++i)
    if (xi[i] == x) return static_cast<int>(i);
  throw std::invalid_argument("no node at xi = " + std::to_string(x));
}

int LineSystem::piece_at(double xi) const {
  int p = -1;
  for (std::size_t i = 0; i < steps.size(); ++i)
    if (xi >= steps[i].xi_from) p = static_cast<int>(i);
  return p;
}

Eigen::MatrixXd LineSystem::state_matrix_at(double lambda, double xi) const {
  const int p = piece_at(xi);
  return p < 0 ? state_matrix(lambda) : steps[static_cast<std::size_t>(p)].state_matrix(lambda);
}

double LineSystem::max_wavenumber_at(double lambda, double xi) const {
  const int p = piece_at(xi);
  return p < 0 ? max_wavenumber(lambda) : steps[static_cast<std::size_t>(p)].max_wavenumber(lambda);
}

const LineVariation& LineSystem::variation_at(double xi) const {
  const int p = piece_at(xi);
  return p < 0 ? variation : steps[static_cast<std::size_t>(p)].variation;
}

namespace {

/// exp(A t), balanced like the segment matrices.
Eigen::MatrixXd transfer(const Eigen::MatrixXd& A, double t) {
  if (t == 0.0) return Eigen::MatrixXd::Identity(A.rows(), A.cols());
  Eigen::MatrixXd B = A * t;
  const Eigen::VectorXd s = balance_in_place(B, 20);
  return s.asDiagonal() * Eigen::MatrixXd(B.exp()) * s.cwiseInverse().asDiagonal();
}

/// The state matrices of the line's segments at lambda, one per distinct piece (computed once).
class PieceMatrices {
 public:
  PieceMatrices(const LineSystem& sys, double lambda) : sys_(sys), lambda_(lambda), A_(sys.steps.size() + 1) {}
  const Eigen::MatrixXd& at(double xi) {
    const std::size_t p = static_cast<std::size_t>(sys_.piece_at(xi) + 1);
    if (A_[p].size() == 0) A_[p] = sys_.state_matrix_at(lambda_, xi);
    return A_[p];
  }

 private:
  const LineSystem& sys_;
  double lambda_;
  std::vector<Eigen::MatrixXd> A_;
};

/// The line's data are consistent (end springs, attachments and steps of the right sizes, inside
/// [0, 1]); throws std::invalid_argument naming what is not.
void check_line(const LineSystem& sys) {
  const int m = sys.m;
  if (static_cast<int>(sys.left_spring.size()) != m || static_cast<int>(sys.right_spring.size()) != m)
    throw std::invalid_argument("LineSystem: end springs must have m entries");
  for (double x : sys.nodes_at)
    if (!(x >= 0.0 && x <= 1.0)) throw std::invalid_argument("LineSystem: node outside [0, 1]");
  for (const LineAttachment& a : sys.attachments) {
    if (!(a.xi >= 0.0 && a.xi <= 1.0)) throw std::invalid_argument("LineSystem: attachment outside [0, 1]");
    if (static_cast<int>(a.spring.size()) != m || static_cast<int>(a.mass.size()) != m ||
        !(a.gyro.empty() || static_cast<int>(a.gyro.size()) == m))
      throw std::invalid_argument("LineSystem: an attachment needs m springs and m masses (and m gyro terms or none)");
  }
  for (const LinePiece& piece : sys.steps)
    if (!(piece.xi_from > 0.0 && piece.xi_from < 1.0)) throw std::invalid_argument("LineSystem: a step outside (0, 1)");
}

std::vector<double> line_nodes(const LineSystem& sys, double lambda) {
  check_line(sys);
  // Breakpoints: 0, the required interior nodes, 1; each gap cut so that |p| h <= 1.
  std::vector<double> breaks = {0.0, 1.0};
  for (double x : sys.nodes_at) breaks.push_back(x);
  for (const LineAttachment& a : sys.attachments) breaks.push_back(a.xi);
  for (const LinePiece& piece : sys.steps) breaks.push_back(piece.xi_from);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  std::vector<double> xi = {0.0};
  for (std::size_t g = 0; g + 1 < breaks.size(); ++g) {
    const double len = breaks[g + 1] - breaks[g];
    if (const LineVariation& v = sys.variation_at(0.5 * (breaks[g] + breaks[g + 1]))) {
      detail::cut_varying(v, lambda, breaks[g], breaks[g + 1], detail::kMinVaryingSegments, xi);
      continue;
    }
    const double p = std::max(sys.max_wavenumber_at(lambda, 0.5 * (breaks[g] + breaks[g + 1])), 1e-12);
    if (!std::isfinite(p)) throw std::runtime_error("LineSystem: wavenumber bound is not finite");
    const double pieces = std::ceil(len * p);
    if (pieces > 1e7) throw std::runtime_error("LineSystem: more than 1e7 segments needed at this frequency");
    const int n = std::max(1, static_cast<int>(pieces));
    for (int j = 1; j < n; ++j) xi.push_back(breaks[g] + len * j / n);
    xi.push_back(breaks[g + 1]);
  }
  return xi;
}

/// Whether two segments of a line on [0, 1] are the same length: the nodes of one gap are placed
/// at len * j / n and carry rounding of about 1e-16 each, so the differences of equal segments
/// differ by a few 1e-16 absolute (1e-13 of a 1e-3 segment: a relative test took almost every
/// segment of a 1000-mode count for a new one, an exponential and an LU each, O(k^2) in all).
bool same_length(double h, double last_h) { return std::abs(h - last_h) <= 1e-15; }

/// Where the line meets the ground or carries a point inertia: the ends and the attachments,
/// merged by position (an attachment at an end adds to its spring), springs per DOF ([0, inf])
/// and point masses per DOF.
struct Site {
  double xi = 0;
  std::vector<double> spring, mass, gyro;  ///< as LineAttachment's (gyro: m entries, 0 where none)
};
std::vector<Site> sites_of(const LineSystem& sys) {
  const std::size_t m = static_cast<std::size_t>(sys.m);
  const std::vector<double> zero(m, 0.0);
  std::vector<Site> out = {{0.0, sys.left_spring, zero, zero}, {1.0, sys.right_spring, zero, zero}};
  for (const LineAttachment& a : sys.attachments) {
    auto it = std::find_if(out.begin(), out.end(), [&](const Site& s) { return s.xi == a.xi; });
    if (it == out.end()) {
      out.push_back({a.xi, a.spring, a.mass, a.gyro.empty() ? zero : a.gyro});
      continue;
    }
    for (std::size_t j = 0; j < m; ++j) {
      it->spring[j] += a.spring[j];  // inf + k = inf
      it->mass[j] += a.mass[j];
      if (!a.gyro.empty()) it->gyro[j] += a.gyro[j];
    }
  }
  return out;
}

/// The rigid motions of the unsupported line (LineRigidity in the header).
struct Rigid {
  LineRigidity info;
  Eigen::MatrixXd Add;  // A_dd(0): Phi(xi) = exp(A_dd xi)
  Eigen::MatrixXd Rc;   // m x m: Phi(xi) Rc has unit value at one anchor, zero at the others
  struct Anchor {
    double xi = 0;
    int dof = 0;
  };
  std::vector<Anchor> anchors;
  Eigen::MatrixXd psi(double xi) const {
    const Eigen::MatrixXd X = Add * xi;
    return Eigen::MatrixXd(X.exp()) * Rc;
  }
  int anchor_of(double xi, int dof) const {
    for (std::size_t a = 0; a < anchors.size(); ++a)
      if (anchors[a].xi == xi && anchors[a].dof == dof) return static_cast<int>(a);
    return -1;
  }
};

Rigid rigid_of(const LineSystem& sys) {
  Rigid R;
  const int m = sys.m;
  const Eigen::MatrixXd A0 = sys.state_matrix(0.0);
  if (!(A0.bottomLeftCorner(m, m).array() == 0.0).all()) return R;
  for (const LinePiece& piece : sys.steps) {  // one rigid basis exp(A_dd xi) for every piece
    const Eigen::MatrixXd Ap = piece.state_matrix(0.0);
    if (!(Ap.bottomLeftCorner(m, m).array() == 0.0).all() || Ap.topLeftCorner(m, m) != A0.topLeftCorner(m, m)) return R;
  }
  R.Add = A0.topLeftCorner(m, m);
  struct Candidate {
    double xi;
    int dof;
    double k;
    Eigen::RowVectorXd row;
  };
  // Every supported DOF of the line (ends and attachments, stiffest first; the ends' free DOFs
  // after them), so that each spring acts on an amplitude of its own where it can: a stiff spring
  // written through another anchor's amplitude would round the soft one's share away (a beam
  // rocking on 1e-3 N/m about a 6.6e4 N/m end came out 1.7e-8 off with two masses at its end).
  std::vector<Candidate> cand;
  for (const Site& s : sites_of(sys)) {
    const Eigen::MatrixXd X = R.Add * s.xi;
    const Eigen::MatrixXd phi = X.exp();
    const bool end = s.xi == 0.0 || s.xi == 1.0;
    for (int j = 0; j < m; ++j) {
      const double k = s.spring[static_cast<std::size_t>(j)];
      if (end || k > 0) cand.push_back({s.xi, j, k, phi.row(j)});
    }
  }
  std::stable_sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) { return a.k > b.k; });
  std::vector<Eigen::RowVectorXd> basis;
  Eigen::MatrixXd G(m, m);
  for (const Candidate& c : cand) {
    if (static_cast<int>(R.anchors.size()) == m) break;
    Eigen::RowVectorXd v = c.row;
    for (const auto& q : basis) v -= v.dot(q) * q;
    if (!(v.norm() > 1e-8 * c.row.norm())) continue;
    basis.push_back(v / v.norm());
    G.row(static_cast<Eigen::Index>(R.anchors.size())) = c.row;
    R.anchors.push_back({c.xi, c.dof});
    if (std::isinf(c.k)) ++R.info.held_rank;
    if (c.k == 0.0) ++R.info.free_rigid;
  }
  if (static_cast<int>(R.anchors.size()) != m) return R;  // cannot happen: Phi(0) = I
  R.Rc = G.inverse();
  R.info.available = true;
  return R;
}

/// How many rigid motions of the unsupported line no spring or hold restrains (the ends' and the
/// attachments' together), from the kinematics alone; -1 where the line has no rigid motions of
/// its own (A_fd(0) != 0, or pieces with other kinematics). For lines the split does not serve.
int structural_free_rigid(const LineSystem& sys) {
  const int m = sys.m;
  const Eigen::MatrixXd A0 = sys.state_matrix(0.0);
  if (!(A0.bottomLeftCorner(m, m).array() == 0.0).all()) return -1;
  for (const LinePiece& piece : sys.steps) {
    const Eigen::MatrixXd Ap = piece.state_matrix(0.0);
    if (!(Ap.bottomLeftCorner(m, m).array() == 0.0).all() || Ap.topLeftCorner(m, m) != A0.topLeftCorner(m, m)) return -1;
  }
  const Eigen::MatrixXd Add = A0.topLeftCorner(m, m);
  Eigen::MatrixXd rows(0, m);
  auto restrain = [&](double xi, const std::vector<double>& k) {
    const Eigen::MatrixXd X = Add * xi;
    const Eigen::MatrixXd phi = X.exp();
    for (int j = 0; j < m && j < static_cast<int>(k.size()); ++j)
      if (k[static_cast<std::size_t>(j)] > 0) {
        rows.conservativeResize(rows.rows() + 1, m);
        rows.row(rows.rows() - 1) = phi.row(j);
      }
  };
  restrain(0.0, sys.left_spring);
  restrain(1.0, sys.right_spring);
  for (const LineAttachment& at : sys.attachments) restrain(at.xi, at.spring);
  if (rows.rows() == 0) return m;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(rows);
  lu.setThreshold(1e-8);
  return m - static_cast<int>(lu.rank());
}

/// The line in rigid amplitudes a and anchored elastic displacements e (header: LineRigidity):
/// [[E, B], [B^T, C]] [e; a] = [f_e; Psi^T f].
struct Split {
  BlockTridiagonal E;
  Eigen::MatrixXd B, C;
  std::vector<int> free_a;           // rigid amplitudes not held, in anchor (stiffness) order
  std::vector<Eigen::MatrixXd> Psi;  // per node, m x m
};

Split assemble_split(const LineSystem& sys, const Rigid& R, const std::vector<double>& xi, double lambda) {
  const int m = sys.m, n = static_cast<int>(xi.size());
  Split S{BlockTridiagonal(n, m), Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n) * m, m),
          Eigen::MatrixXd::Zero(m, m), {}, {}};
  for (double x : xi) S.Psi.push_back(R.psi(x));
  PieceMatrices A1(sys, lambda), A0(sys, 0.0);
  double last_h = -1;
  int last_piece = -2;
  SegmentDivided seg;
  Eigen::MatrixXd Ps(2 * m, m);
  for (int i = 0; i + 1 < n; ++i) {
    const double h = xi[i + 1] - xi[i], mid = 0.5 * (xi[i] + xi[i + 1]);
    const int piece = sys.piece_at(mid);
    if (const LineVariation& v = sys.variation_at(mid)) {
      seg = detail::varying_divided(v, lambda, xi[i], xi[i + 1]);
      last_piece = -2;
    } else if (!same_length(h, last_h) || piece != last_piece) {
      seg = segment_dynamic_stiffness_divided(A1.at(mid), A0.at(mid), lambda, h);
      last_h = h;
      last_piece = piece;
    }
    S.E.add_segment(i, seg.K);
    if (lambda != 0.0) {
      Ps << S.Psi[i], S.Psi[i + 1];
      const Eigen::MatrixXd W = lambda * (seg.dK * Ps);  // K(lambda) Ps, K(0) Ps = 0
      S.B.middleRows(static_cast<Eigen::Index>(i) * m, 2 * m) += W;
      S.C.noalias() += Ps.transpose() * W;
    }
  }
  std::vector<char> held_a(m, 0);
  for (const Site& site : sites_of(sys)) {
    const int node = static_cast<int>(std::lower_bound(xi.begin(), xi.end(), site.xi) - xi.begin());
    for (int j = 0; j < m; ++j) {
      const double k = site.spring[static_cast<std::size_t>(j)];
      const int a = R.anchor_of(site.xi, j);
      if (a >= 0) S.E.hold(node, j);
      if (std::isinf(k)) {
        // A held anchor holds its amplitude; any other held DOF depends on held anchors only
        // (they were chosen first), so its rigid part is zero and e is held there too.
        if (a >= 0) held_a[a] = 1;
        else S.E.hold(node, j);
        continue;
      }
      const auto jj = static_cast<std::size_t>(j);
      const double t = k - lambda * site.mass[jj] + (lambda > 0 ? std::sqrt(lambda) * site.gyro[jj] : 0.0);
      if (t == 0.0) continue;
      const Eigen::RowVectorXd psi = S.Psi[node].row(j);
      S.C.noalias() += t * psi.transpose() * psi;
      if (a < 0) {
        S.E.add_diagonal(node, j, t);
        S.B.row(static_cast<Eigen::Index>(node) * m + j) += t * psi;
      }
    }
  }
  for (int a = 0; a < m; ++a)
    if (!held_a[a]) S.free_a.push_back(a);
  return S;
}

/// The condensed rigid block S = C - B^T E^-1 B over the free amplitudes, and E^-1 B.
struct Condensed {
  Eigen::MatrixXd S, Y;  // Y = E^-1 B (free columns)
};
Condensed condense(const Split& sp) {
  const Eigen::Index r = static_cast<Eigen::Index>(sp.free_a.size());
  Condensed c{Eigen::MatrixXd(r, r), Eigen::MatrixXd(sp.B.rows(), r)};
  for (Eigen::Index q = 0; q < r; ++q) c.Y.col(q) = sp.E.solve(sp.B.col(sp.free_a[q]), 0.0);
  for (Eigen::Index p = 0; p < r; ++p)
    for (Eigen::Index q = 0; q < r; ++q) c.S(p, q) = sp.C(sp.free_a[p], sp.free_a[q]) - sp.B.col(sp.free_a[p]).dot(c.Y.col(q));
  return c;
}

/// The count from the split, or -1 where its elastic part is not positive definite.
int split_count(const Split& sp) {
  const BlockTridiagonal::Inertia in = sp.E.inertia();
  if (in.negative > 0 || in.zero > 0) return -1;
  Condensed c = condense(sp);
  const Eigen::VectorXd d = graded_ldlt(c.S);
  int neg = 0;
  for (Eigen::Index k = 0; k < d.size(); ++k) {
    if (std::isnan(d[k])) return -1;
    if (d[k] < 0) ++neg;
  }
  return neg;
}
}  // namespace

Eigen::MatrixXd line_transfer(const LineSystem& sys, double lambda, double x0, double x1) {
  if (const LineVariation& v = sys.variation_at(0.5 * (x0 + x1)))
    return detail::magnus_transfer([&](double x) { return v.state(lambda, x); }, x0, x1).T;
  return transfer(sys.state_matrix_at(lambda, 0.5 * (x0 + x1)), x1 - x0);
}

Eigen::MatrixXd line_segment_stiffness(const LineSystem& sys, double lambda, double x0, double x1) {
  if (sys.variation_at(0.5 * (x0 + x1))) return segment_stiffness_of_transfer(line_transfer(sys, lambda, x0, x1));
  return segment_dynamic_stiffness(sys.state_matrix_at(lambda, 0.5 * (x0 + x1)), x1 - x0);
}

AssembledLine assemble(const LineSystem& sys, double lambda) {
  const int m = sys.m;
  const std::vector<double> xi = line_nodes(sys, lambda);
  AssembledLine out{BlockTridiagonal(static_cast<int>(xi.size()), m), xi};
  PieceMatrices A(sys, lambda);
  // Equal-length segments of one piece share one segment matrix.
  double last_h = -1;
  int last_piece = -2;
  Eigen::MatrixXd k_seg;
  for (std::size_t i = 0; i + 1 < xi.size(); ++i) {
    const double h = xi[i + 1] - xi[i], mid = 0.5 * (xi[i] + xi[i + 1]);
    const int piece = sys.piece_at(mid);
    if (sys.variation_at(mid)) {
      k_seg = line_segment_stiffness(sys, lambda, xi[i], xi[i + 1]);
      last_piece = -2;
    } else if (!same_length(h, last_h) || piece != last_piece) {
      k_seg = segment_dynamic_stiffness(A.at(mid), h);
      last_h = h;
      last_piece = piece;
    }
    out.K.add_segment(static_cast<int>(i), k_seg);
  }
  const int last = static_cast<int>(xi.size()) - 1;
  for (int j = 0; j < m; ++j) {
    if (std::isinf(sys.left_spring[j])) out.K.hold(0, j);
    else out.K.add_diagonal(0, j, sys.left_spring[j]);
    if (std::isinf(sys.right_spring[j])) out.K.hold(last, j);
    else out.K.add_diagonal(last, j, sys.right_spring[j]);
  }
  for (const LineAttachment& a : sys.attachments) {
    const int node = out.node_at(a.xi);
    for (int j = 0; j < m; ++j) {
      if (std::isinf(a.spring[j])) out.K.hold(node, j);
      else out.K.add_diagonal(node, j, a.term(static_cast<std::size_t>(j), lambda));
    }
  }
  return out;
}

std::vector<LineReaction> line_reactions(const LineSystem& sys, const AssembledLine& asmb, const Eigen::VectorXd& d,
                                         const Eigen::VectorXd& f) {
  const int m = sys.m;
  const Eigen::VectorXd residual = asmb.K.multiply(d) - f;
  auto at = [&](double xi, const std::vector<double>& spring) {
    const int node = asmb.node_at(xi);
    LineReaction r{xi, Eigen::VectorXd::Zero(m)};
    for (int j = 0; j < m; ++j) {
      const Eigen::Index k = static_cast<Eigen::Index>(node) * m + j;
      r.r[j] = std::isinf(spring[static_cast<std::size_t>(j)]) ? residual[k] : -spring[static_cast<std::size_t>(j)] * d[k];
    }
    return r;
  };
  auto any = [](const std::vector<double>& spring) {
    return std::any_of(spring.begin(), spring.end(), [](double k) { return k != 0.0; });
  };
  std::vector<LineReaction> out;
  if (any(sys.left_spring)) out.push_back(at(0.0, sys.left_spring));
  if (any(sys.right_spring)) out.push_back(at(1.0, sys.right_spring));
  for (const LineAttachment& a : sys.attachments)
    if (any(a.spring)) out.push_back(at(a.xi, a.spring));
  return out;
}

namespace {

/// The line's features: 0, 1, the steps and the attachments (not the load and probe nodes, which
/// do not change the count).
std::vector<double> feature_nodes(const LineSystem& sys) {
  std::vector<double> xi = {0.0, 1.0};
  for (const LineAttachment& a : sys.attachments) xi.push_back(a.xi);
  for (const LinePiece& piece : sys.steps) xi.push_back(piece.xi_from);
  std::sort(xi.begin(), xi.end());
  xi.erase(std::unique(xi.begin(), xi.end()), xi.end());
  return xi;
}

}  // namespace

/// How close to singular a long segment's condensed middle blocks may come in a count
/// (LongSegment::min_pivot_scale) before the gap is cut unevenly.
constexpr double kCountPivot = 1e-4;

int count_below(const LineSystem& sys, double lambda) {
  check_line(sys);
  const int m = sys.m;
  const std::vector<double> xi = feature_nodes(sys);
  PieceMatrices A(sys, lambda);
  // Each gap one long segment (long_segment_dynamic_stiffness): a base piece with |p| h <= 1, as
  // line_nodes' segments (no clamped frequency below lambda), doubled to the gap's length; the
  // middle nodes' negative pivots are the gap's J0. A gap whose condensed middle blocks come
  // within kCountPivot of singular (lambda next to a clamped frequency of one of its halvings,
  // where the condensation loses digits) is cut once more, unevenly, so that its pieces have other
  // clamped frequencies.
  std::vector<std::pair<double, LongSegment>> gaps;  // (left end, segment)
  std::function<void(double, double, int)> add_gap = [&](double a, double b, int depth) {
    const double len = b - a, mid = 0.5 * (a + b);
    if (const LineVariation& v = sys.variation_at(mid)) {
      // A varying piece: segments that provably have no clamped frequency below lambda (J0 = 0).
      std::vector<double> cuts = {a};
      detail::cut_varying(v, lambda, a, b, 1, cuts);
      for (std::size_t j = 0; j + 1 < cuts.size(); ++j) {
        LongSegment seg;
        seg.K = line_segment_stiffness(sys, lambda, cuts[j], cuts[j + 1]);
        gaps.emplace_back(cuts[j], std::move(seg));
      }
      return;
    }
    const double p = std::max(sys.max_wavenumber_at(lambda, mid), 1e-12);
    if (!std::isfinite(p)) throw std::runtime_error("LineSystem: wavenumber bound is not finite");
    const int levels = static_cast<int>(std::ceil(std::log2(std::max(1.0, std::ceil(len * p)))));
    LongSegment seg = long_segment_dynamic_stiffness(A.at(mid), len, levels);
    if (seg.min_pivot_scale < kCountPivot && levels > 0 && depth < 8) {
      const double cut = a + len * 0.41421356237309503;  // sqrt(2) - 1: no halving's multiple
      add_gap(a, cut, depth + 1);
      add_gap(cut, b, depth + 1);
      return;
    }
    gaps.emplace_back(a, std::move(seg));
  };
  for (std::size_t i = 0; i + 1 < xi.size(); ++i) add_gap(xi[i], xi[i + 1], 0);
  std::vector<double> nodes;
  for (const auto& g : gaps) nodes.push_back(g.first);
  nodes.push_back(1.0);
  BlockTridiagonal K(static_cast<int>(nodes.size()), m);
  int j0 = 0;
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    j0 += gaps[i].second.clamped_below;
    K.add_segment(static_cast<int>(i), gaps[i].second.K);
  }
  const int last = static_cast<int>(nodes.size()) - 1;
  for (int j = 0; j < m; ++j) {
    if (std::isinf(sys.left_spring[j])) K.hold(0, j);
    else K.add_diagonal(0, j, sys.left_spring[j]);
    if (std::isinf(sys.right_spring[j])) K.hold(last, j);
    else K.add_diagonal(last, j, sys.right_spring[j]);
  }
  for (const LineAttachment& a : sys.attachments) {
    const int node = static_cast<int>(std::lower_bound(nodes.begin(), nodes.end(), a.xi) - nodes.begin());
    for (int j = 0; j < m; ++j) {
      if (std::isinf(a.spring[j])) K.hold(node, j);
      else K.add_diagonal(node, j, a.term(static_cast<std::size_t>(j), lambda));
    }
  }
  return j0 + K.inertia().negative;
}

Eigen::VectorXd solve_line(const LineSystem& sys, const AssembledLine& asmb, double lambda, const Eigen::VectorXd& f) {
  const int m = sys.m;
  const Rigid R = rigid_of(sys);
  if (R.info.available) {
    const Split sp = assemble_split(sys, R, asmb.xi, lambda);
    const BlockTridiagonal::Inertia in = sp.E.inertia();
    if (in.negative == 0 && in.zero == 0) {
      if (lambda == 0.0 && R.info.free_rigid > 0)
        throw std::runtime_error(
            "mechanism: " + std::to_string(R.info.free_rigid) +
            " rigid-body motion(s) of the line are restrained by no support: static solve impossible");
      const int n = static_cast<int>(asmb.xi.size());
      const Eigen::Index r = static_cast<Eigen::Index>(sp.free_a.size());
      Eigen::VectorXd fa = Eigen::VectorXd::Zero(m);
      for (int i = 0; i < n; ++i) fa += sp.Psi[i].transpose() * f.segment(static_cast<Eigen::Index>(i) * m, m);
      const Eigen::VectorXd y = sp.E.solve(f, 0.0);
      Condensed c = condense(sp);
      Eigen::VectorXd rhs(r);
      for (Eigen::Index p = 0; p < r; ++p) rhs[p] = fa[sp.free_a[p]] - sp.B.col(sp.free_a[p]).dot(y);
      Eigen::MatrixXd L = c.S;
      const Eigen::VectorXd d = graded_ldlt(L);
      for (Eigen::Index k = 0; k < r; ++k)
        if (std::isnan(d[k]))
          throw std::runtime_error("dynamic stiffness matrix is singular to working precision in the rigid-body "
                                   "motions of the line (a mechanism, or omega at a natural frequency)");
      const Eigen::VectorXd a_free = graded_ldlt_solve(L, d, rhs);
      Eigen::VectorXd a = Eigen::VectorXd::Zero(m);
      for (Eigen::Index p = 0; p < r; ++p) a[sp.free_a[p]] = a_free[p];
      Eigen::VectorXd e = y - c.Y * a_free;
      Eigen::VectorXd out(f.size());
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
          const Eigen::Index row = static_cast<Eigen::Index>(i) * m + j;
          out[row] = sp.Psi[i].row(j).dot(a) + (sp.E.held(i, j) ? 0.0 : e[row]);
        }
      return out;
    }
  }
  return asmb.K.solve(f);
}

namespace {

/// The node at x (>= 0), or -1 with `seg` the segment [xi[seg], xi[seg + 1]] holding x.
int locate(const AssembledLine& asmb, double x, int& seg) {
  const auto& xi = asmb.xi;
  if (!(x >= xi.front() && x <= xi.back())) throw std::invalid_argument("LineSystem: point outside [0, 1]");
  const auto it = std::lower_bound(xi.begin(), xi.end(), x);
  const int i = static_cast<int>(it - xi.begin());
  if (*it == x) return i;
  seg = i - 1;
  return -1;
}

/// Fixed-end state forces (left F_a, right F_c) of the clamped segment [a, c] under a point action
/// f at x: the state's force part jumps by -f there, and d = 0 at both ends.
std::pair<Eigen::VectorXd, Eigen::VectorXd> fixed_end(const LineSystem& sys, double lambda, double a, double c,
                                                      double x, const Eigen::VectorXd& f) {
  const int m = sys.m;
  const double h = c - a, s = x - a;  // a uniform piece's lengths as they always were formed
  const bool varies = static_cast<bool>(sys.variation_at(0.5 * (a + c)));
  const Eigen::MatrixXd A = varies ? Eigen::MatrixXd() : sys.state_matrix_at(lambda, 0.5 * (a + c));
  const Eigen::MatrixXd Th = varies ? line_transfer(sys, lambda, a, c) : transfer(A, h);
  const Eigen::MatrixXd Tr = varies ? line_transfer(sys, lambda, x, c) : transfer(A, h - s);
  const Eigen::VectorXd jump = -f;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu(Th.topRightCorner(m, m));
  const Eigen::VectorXd Fa = -lu.solve(Tr.topRightCorner(m, m) * jump);
  const Eigen::VectorXd Fc = Th.bottomRightCorner(m, m) * Fa + Tr.bottomRightCorner(m, m) * jump;
  return {Fa, Fc};
}

}  // namespace

void add_point_load(const LineSystem& sys, const AssembledLine& asmb, double lambda, const LinePoint& p,
                    Eigen::VectorXd& F) {
  const int m = sys.m;
  int seg = -1;
  const int node = locate(asmb, p.xi, seg);
  if (node >= 0) {
    F.segment(static_cast<Eigen::Index>(node) * m, m) += p.f;
    return;
  }
  const double a = asmb.xi[static_cast<std::size_t>(seg)], c = asmb.xi[static_cast<std::size_t>(seg) + 1];
  const auto [Fa, Fc] = fixed_end(sys, lambda, a, c, p.xi, p.f);
  // Equivalent nodal loads: minus the fixed-end reactions [-F_a; F_c] of K's convention.
  F.segment(static_cast<Eigen::Index>(seg) * m, m) += Fa;
  F.segment(static_cast<Eigen::Index>(seg + 1) * m, m) -= Fc;
}

Eigen::VectorXd state_at(const LineSystem& sys, const AssembledLine& asmb, double lambda, const Eigen::VectorXd& d,
                         const std::vector<LinePoint>& loads, double x) {
  const int m = sys.m;
  int seg = -1;
  const int node = locate(asmb, x, seg);
  const int last = static_cast<int>(asmb.xi.size()) - 1;
  if (node >= 0) seg = std::min(node, last - 1);  // a node: the segment beyond it (the last: before it)
  const double a = asmb.xi[static_cast<std::size_t>(seg)], c = asmb.xi[static_cast<std::size_t>(seg) + 1];
  const Eigen::MatrixXd K = line_segment_stiffness(sys, lambda, a, c);
  Eigen::VectorXd dd(2 * m);
  dd << d.segment(static_cast<Eigen::Index>(seg) * m, m), d.segment(static_cast<Eigen::Index>(seg + 1) * m, m);
  // The segment's end force at a: K d plus the fixed-end reactions of the loads inside it.
  Eigen::VectorXd Fa = -(K.topRows(m) * dd);
  for (const auto& p : loads)
    if (p.xi > a && p.xi < c) Fa += fixed_end(sys, lambda, a, c, p.xi, p.f).first;
  Eigen::VectorXd state(2 * m);
  state << dd.head(m), Fa;
  Eigen::VectorXd out = line_transfer(sys, lambda, a, x) * state;
  for (const auto& p : loads)  // the jump -f carried to x
    if (p.xi > a && p.xi < c && p.xi <= x) out += line_transfer(sys, lambda, p.xi, x).rightCols(m) * (-p.f);
  // At a node the displacements are the solution's own (not carried through rounding).
  if (node >= 0) out.head(m) = d.segment(static_cast<Eigen::Index>(node) * m, m);
  return out;
}

Eigen::VectorXd displacement_at(const LineSystem& sys, const AssembledLine& asmb, double lambda, const Eigen::VectorXd& d,
                                const std::vector<LinePoint>& loads, double x) {
  int seg = -1;
  const int node = locate(asmb, x, seg);
  if (node >= 0) return d.segment(static_cast<Eigen::Index>(node) * sys.m, sys.m);
  return state_at(sys, asmb, lambda, d, loads, x).head(sys.m);
}

LineSpectrum lowest_eigenvalues(const LineSystem& sys, int k, double lambda_hint, SliceStats* stats) {
  LineSpectrum out;
  const double scale = std::abs(lambda_hint);
  const Rigid R = rigid_of(sys);
  // Lines whose held supports leave rigid motions free count through the rigid split below
  // half the scale (where near-rigid modes live and the anchored line is positive definite).
  const bool split = R.info.available && R.info.held_rank < sys.m && sys.polynomial_in_lambda;
  auto N = [&](double lam) {
    if (split && lam < 0.5 * scale) {
      const Split sp = assemble_split(sys, R, line_nodes(sys, lam), lam);
      if (stats) stats->max_unknowns = std::max<long>(stats->max_unknowns, sp.E.free_dofs() + sys.m);
      const int c = split_count(sp);
      if (c >= 0) return c;
    }
    if (stats) stats->max_unknowns = std::max<long>(stats->max_unknowns, static_cast<long>(feature_nodes(sys).size()) * sys.m);
    return count_below(sys, lam);
  };
  const double delta = kRigidThreshold * scale;
  const int below = N(-delta);
  if (below != 0)
    throw std::runtime_error("the system has " + std::to_string(below) +
                             " negative eigenvalue(s) omega^2 < 0: it is unstable, not a vibrating structure");
  double lo = delta;
  if (R.info.available) {
    // Rigid-body modes are exactly the motions no support restrains; every other eigenvalue is
    // resolved down to 1e-250 of the scale.
    lo = 1e-250 * scale;
    const int n_lo = N(lo);
    out.rigid = std::min(n_lo, k);
    out.unresolved = std::max(0, out.rigid - R.info.free_rigid);
  } else {
    out.rigid = std::min(N(delta), k);
    // Without the split, what the count finds below its threshold is rigid only as far as the
    // supports leave rigid motions free (a beam with a disc on soft bearings: near-rigid modes).
    if (const int free = structural_free_rigid(sys); free >= 0) out.unresolved = std::max(0, out.rigid - free);
  }
  out.lambdas.assign(out.rigid, 0.0);
  auto rest = slice_spectrum(N, k - out.rigid, lo, lambda_hint, 1e-13, stats);
  out.lambdas.insert(out.lambdas.end(), rest.begin(), rest.end());
  if (stats) stats->count_evaluations += 2;
  return out;
}

}  // namespace modalbench
