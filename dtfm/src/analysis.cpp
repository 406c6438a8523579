#include "modalbench/dtfm/analysis.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace modalbench::dtfm {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

/// One symmetry class of the model as a line problem in scaled coordinates: translations
/// divided by a length (so that K's translation and rotation entries are comparable), energy
/// divided by sigma. q = W q_c, f_c = W^T f / sigma.
struct LineAnalysis::ClassLine {
  int index = 0, mc = 0;
  ModeFamily family = ModeFamily::Unknown;
  Eigen::MatrixXd W, Winv;
  Eigen::MatrixXd St, C, Qt, M;
  double sigma = 1;
  struct End {
    Eigen::MatrixXd B;  // mc x mc orthogonal; the first n_free columns are the admissible motions
    int n_free = 0;
    Eigen::MatrixXd K;  // springs on those coordinates
  } ends[2];
  Eigen::MatrixXd family_motions;  // physical, m x r (beams)
  double re0 = -1, im0 = -1;       // wavenumber bounds at lambda = 0 (cached)

  template <class Scalar>
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> state(Scalar lambda) const {
    using Mat = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
    Mat A(2 * mc, 2 * mc);
    A.topLeftCorner(mc, mc) = (-St).template cast<Scalar>();
    A.topRightCorner(mc, mc) = C.template cast<Scalar>();
    A.bottomLeftCorner(mc, mc) = Qt.template cast<Scalar>() - lambda * M.template cast<Scalar>();
    A.bottomRightCorner(mc, mc) = St.transpose().template cast<Scalar>();
    return A;
  }
};

LineAnalysis::~LineAnalysis() = default;

LineAnalysis::LineAnalysis(const PrismModel& model, SolveControls controls) : model_(model), ctl_(controls) {
  const int m = model.m;
  Eigen::VectorXd s(m);
  for (int k = 0; k < m; ++k) s[k] = model.field_dof[k] < 3 ? model.translation_scale : 1.0;
  const Eigen::VectorXd si = s.cwiseInverse();
  int ci = 0;
  for (const auto& fc : model.classes) {
    auto line = std::make_unique<ClassLine>();
    line->index = ci++;
    line->mc = static_cast<int>(fc.V.cols());
    line->family = fc.family;
    line->family_motions = fc.family_motions;
    line->W = s.asDiagonal() * fc.V;
    line->Winv = fc.V.transpose() * si.asDiagonal();
    const Eigen::MatrixXd& W = line->W;
    const Eigen::MatrixXd Vs = si.asDiagonal() * fc.V;  // strains scale like q'
    Eigen::MatrixXd Mc = W.transpose() * model.M * W;
    double sigma = Mc.norm() * model.lambda_scale;
    if (!(sigma > 0) || !std::isfinite(sigma)) sigma = 1.0;
    line->sigma = sigma;
    const Eigen::MatrixXd Cc = sigma * (Vs.transpose() * model.C * Vs);
    const Eigen::MatrixXd Sc = line->Winv * model.S * W;
    const Eigen::MatrixXd Xc = W.transpose() * model.X * W / sigma;
    const Eigen::MatrixXd Qc = W.transpose() * model.Q1 * W / sigma;
    line->C = 0.5 * (Cc + Cc.transpose());
    line->M = Mc / sigma;
    line->M = 0.5 * (line->M + line->M.transpose());
    line->St = Sc + line->C * Xc;
    line->Qt = Qc - Xc.transpose() * line->C * Xc;
    line->Qt = 0.5 * (line->Qt + line->Qt.transpose());
    for (int e = 0; e < 2; ++e) {
      const auto& end = model.ends[e];
      auto& ce = line->ends[e];
      const int mc = line->mc;
      Eigen::MatrixXd Nc(mc, 0);
      if (end.N.cols() > 0) {
        const Eigen::MatrixXd raw = line->Winv * end.N;
        Eigen::JacobiSVD<Eigen::MatrixXd> svd(raw, Eigen::ComputeThinU);
        const auto& sv = svd.singularValues();
        int r = 0;
        for (Eigen::Index i = 0; i < sv.size(); ++i)
          if (sv[i] > 1e-10 * std::max(sv[0], 1e-300)) ++r;
        Nc = svd.matrixU().leftCols(r);
      }
      ce.n_free = static_cast<int>(Nc.cols());
      ce.B = Eigen::MatrixXd::Identity(mc, mc);
      if (ce.n_free > 0) {
        Eigen::HouseholderQR<Eigen::MatrixXd> qr(Nc);
        const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(mc, mc);
        ce.B.leftCols(ce.n_free) = Nc;
        ce.B.rightCols(mc - ce.n_free) = Q.rightCols(mc - ce.n_free);
        // Springs 1/2 a^T K a with q = N a, a = N^T q = N^T W Nc b.
        const Eigen::MatrixXd G = end.N.transpose() * W * Nc;
        ce.K = G.transpose() * end.K * G / sigma;
        ce.K = 0.5 * (ce.K + ce.K.transpose());
      } else {
        ce.K = Eigen::MatrixXd(0, 0);
      }
    }
    lines_.push_back(std::move(line));
  }
}

std::vector<int> LineAnalysis::pick(const std::vector<ModeFamily>& families) const {
  std::vector<int> out;
  for (const auto& l : lines_)
    if (families.empty() || std::find(families.begin(), families.end(), l->family) != families.end())
      out.push_back(l->index);
  return out;
}

namespace {

/// Floating gcd of two lengths (Euclid with a tolerance); 0 if they are incommensurate.
double fgcd(double a, double b, double tol) {
  for (int it = 0; it < 64; ++it) {
    if (a < b) std::swap(a, b);
    if (b <= tol) return a;
    a = std::fmod(a, b);
    if (a <= tol || b - a <= tol) return b;
  }
  return 0.0;
}

}  // namespace

namespace {

void wavenumber_bounds(const Eigen::MatrixXd& A, double& re, double& im) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(balanced(A), false);
  if (es.info() == Eigen::Success) {
    for (Eigen::Index i = 0; i < es.eigenvalues().size(); ++i) {
      re = std::max(re, std::abs(es.eigenvalues()[i].real()));
      im = std::max(im, std::abs(es.eigenvalues()[i].imag()));
    }
  } else {  // |p| <= any induced norm of A
    const double nrm = A.cwiseAbs().rowwise().sum().maxCoeff();
    re = std::max(re, nrm);
    im = std::max(im, nrm);
  }
}
}  // namespace

LineAnalysis::Mesh LineAnalysis::mesh_for(ClassLine& c, double lambda_max, const std::vector<double>& required,
                                          int min_nodes) {
  const double L = model_.length;
  if (c.re0 < 0) {
    c.re0 = c.im0 = 0;
    wavenumber_bounds(c.state(0.0), c.re0, c.im0);
  }
  double re = c.re0, im = c.im0;
  if (lambda_max > 0) wavenumber_bounds(c.state(lambda_max), re, im);
  Mesh mesh;
  mesh.h_im = im > 0 ? ctl_.im_h / im : L;
  mesh.h_re = re > 0 ? ctl_.re_h / re : L;
  mesh.h_base = std::min({L, mesh.h_im, mesh.h_re});
  if (!(mesh.h_base > 0) || !std::isfinite(mesh.h_base)) throw std::runtime_error("dtfm: wavenumber bound is not finite");
  std::vector<double> breaks = {0.0, L};
  for (double x : required) breaks.push_back(std::clamp(x, 0.0, L));
  for (int i = 1; i < min_nodes; ++i) breaks.push_back(L * i / min_nodes);
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> b2;
  for (double x : breaks)
    if (b2.empty() || x - b2.back() > 1e-12 * L) b2.push_back(x);
  b2.back() = L;
  // Equal segments on a common spacing when the breakpoints are commensurate (one long
  // segment matrix per lambda); otherwise one per gap.
  const double tol = 1e-9 * L;
  double unit = b2[1] - b2[0];
  for (std::size_t i = 1; i + 1 < b2.size() && unit > 0; ++i) unit = fgcd(unit, b2[i + 1] - b2[i], tol);
  mesh.x = {0.0};
  for (std::size_t g = 0; g + 1 < b2.size(); ++g) {
    const double len = b2[g + 1] - b2[g];
    const int n = unit > 1e-3 * L ? std::max(1, static_cast<int>(std::lround(len / unit))) : 1;
    for (int j = 1; j < n; ++j) mesh.x.push_back(b2[g] + len * j / n);
    mesh.x.push_back(b2[g + 1]);
  }
  return mesh;
}

LineAnalysis::Mesh LineAnalysis::refined(const Mesh& mesh) {
  Mesh out = mesh;
  out.x = {mesh.x.front()};
  for (std::size_t i = 0; i + 1 < mesh.x.size(); ++i) {
    out.x.push_back(0.5 * (mesh.x[i] + mesh.x[i + 1]));
    out.x.push_back(mesh.x[i + 1]);
  }
  return out;
}

namespace {

template <class Mat>
void transform_end(Mat& k, const Eigen::MatrixXd& B, int mc, bool left) {
  using Scalar = typename Mat::Scalar;
  const Mat Bs = B.template cast<Scalar>();
  if (left) {
    k.topLeftCorner(mc, mc) = (Bs.transpose() * k.topLeftCorner(mc, mc) * Bs).eval();
    k.topRightCorner(mc, mc) = (Bs.transpose() * k.topRightCorner(mc, mc)).eval();
    k.bottomLeftCorner(mc, mc) = (k.bottomLeftCorner(mc, mc) * Bs).eval();
  } else {
    k.bottomRightCorner(mc, mc) = (Bs.transpose() * k.bottomRightCorner(mc, mc) * Bs).eval();
    k.bottomLeftCorner(mc, mc) = (Bs.transpose() * k.bottomLeftCorner(mc, mc)).eval();
    k.topRightCorner(mc, mc) = (k.topRightCorner(mc, mc) * Bs).eval();
  }
}

/// Long-segment stiffness by doubling, real or complex (the pieces the base length allows).
LongSegment long_segment(const Eigen::MatrixXd& A, double h, int levels) {
  return long_segment_dynamic_stiffness(A, h, levels);
}
LongSegmentC long_segment(const Eigen::MatrixXcd& A, double h, int levels) {
  return long_segment_dynamic_stiffness(A, h, levels);
}
int clamped_of(const LongSegment& s) { return s.clamped_below; }
int clamped_of(const LongSegmentC&) { return 0; }
double log_tdf_of(const LongSegment& s) { return s.log_abs_det_tdf; }
double log_tdf_of(const LongSegmentC&) { return 0.0; }

struct AssemblyInfo {
  int clamped_below = 0;   // sum of the segments' J0
  double log_poles = 0;    // sum of the segments' log |det Tdf|
  double min_pivot_rel = 1;
};

template <class Tri, class Mat, class Scalar>
AssemblyInfo assemble_into(Tri& K, const LineAnalysis::ClassLine& c, const Mat& A, const std::vector<double>& x,
                           double h_base, double& max_asym) {
  const int nn = static_cast<int>(x.size()), mc = c.mc;
  using Seg = decltype(long_segment(A, 1.0, 0));
  std::vector<std::pair<double, Seg>> cache;
  AssemblyInfo info;
  for (int i = 0; i + 1 < nn; ++i) {
    const double h = x[i + 1] - x[i];
    const Seg* hit = nullptr;
    for (const auto& e : cache)
      if (std::abs(h - e.first) <= 1e-9 * h) hit = &e.second;
    if (!hit) {
      const int levels = std::max(0, static_cast<int>(std::ceil(std::log2(h / h_base) - 1e-9)));
      cache.emplace_back(h, long_segment(A, h, levels));
      hit = &cache.back().second;
      max_asym = std::isfinite(hit->asymmetry) ? std::max(max_asym, hit->asymmetry) : kInf;
      info.min_pivot_rel = std::min(info.min_pivot_rel, hit->min_pivot_rel);
    }
    info.clamped_below += clamped_of(*hit);
    info.log_poles += log_tdf_of(*hit);
    if (i == 0 || i + 2 == nn) {
      Mat k = hit->K;
      if (i == 0) transform_end(k, c.ends[0].B, mc, true);
      if (i + 2 == nn) transform_end(k, c.ends[1].B, mc, false);
      K.add_segment(i, k);
    } else {
      K.add_segment(i, hit->K);
    }
  }
  for (int e = 0; e < 2; ++e) {
    const auto& ce = c.ends[e];
    const int node = e == 0 ? 0 : nn - 1;
    if (ce.n_free > 0 && ce.K.norm() > 0) {
      Mat pad = Mat::Zero(2 * mc, 2 * mc);
      if (e == 0) pad.topLeftCorner(ce.n_free, ce.n_free) = ce.K.template cast<Scalar>();
      else pad.block(mc, mc, ce.n_free, ce.n_free) = ce.K.template cast<Scalar>();
      K.add_segment(e == 0 ? 0 : nn - 2, pad);
    }
    for (int j = ce.n_free; j < mc; ++j) K.hold(node, j);
  }
  return info;
}

}  // namespace

struct LineAnalysis::Assembled {
  BlockTridiagonal K;
  AssemblyInfo info;
};

LineAnalysis::Assembled LineAnalysis::assemble(const ClassLine& c, double lambda, const Mesh& mesh) {
  Assembled out{BlockTridiagonal(static_cast<int>(mesh.x.size()), c.mc), {}};
  out.info = assemble_into<BlockTridiagonal, Eigen::MatrixXd, double>(out.K, c, c.state(lambda), mesh.x,
                                                                      mesh.h_base, max_asymmetry_);
  return out;
}

ComplexBlockTridiagonal LineAnalysis::assemble(const ClassLine& c, std::complex<double> lambda, const Mesh& mesh) {
  ComplexBlockTridiagonal K(static_cast<int>(mesh.x.size()), c.mc);
  assemble_into<ComplexBlockTridiagonal, Eigen::MatrixXcd, std::complex<double>>(K, c, c.state(lambda), mesh.x,
                                                                                 mesh.h_base, max_asymmetry_);
  return K;
}

CountDet LineAnalysis::count_det(const ClassLine& c, double lambda, const Mesh& mesh) {
  ++evaluations_;
  // A segment whose condensed middle block is nearly singular (lambda close to a clamped
  // frequency of a sub-piece) is split at its middle: the global LDL^T then pivots across it.
  Mesh use = mesh;
  for (int attempt = 0;; ++attempt) {
    const Assembled a = assemble(c, lambda, use);
    if (a.info.min_pivot_rel < 1e-10 && attempt < 4) {
      use = refined(use);
      continue;
    }
    const auto in = a.K.inertia();
    // Wittrick-Williams: J = J0 (segments) + s{K}; det K * prod det Tdf has no poles.
    return {in.negative + a.info.clamped_below, in.log_abs_det + a.info.log_poles};
  }
}

int LineAnalysis::count_below(double lambda, const std::vector<ModeFamily>& families) {
  int n = 0;
  for (int c : pick(families)) {
    const Mesh mesh = mesh_for(*lines_[c], std::max(lambda, 0.0), {});
    n += count_det(*lines_[c], lambda, mesh).count;
  }
  return n;
}

namespace {
/// Field values (physical) at every node from a class solution d (nodes x mc, end nodes in B coordinates).
template <class Vec>
std::vector<Vec> to_fields(const LineAnalysis::ClassLine& c, const Vec& d, int nn) {
  using Scalar = typename Vec::Scalar;
  std::vector<Vec> q(nn);
  for (int i = 0; i < nn; ++i) {
    Vec dc = d.segment(static_cast<Eigen::Index>(i) * c.mc, c.mc);
    if (i == 0) dc = c.ends[0].B.template cast<Scalar>() * dc;
    if (i == nn - 1) dc = c.ends[1].B.template cast<Scalar>() * dc;
    q[i] = c.W.template cast<Scalar>() * dc;
  }
  return q;
}
}  // namespace

double LineAnalysis::family_share(ClassLine& c, double lambda) {
  if (c.family_motions.cols() == 0) return 1.0;
  // The mode shape by one inverse-iteration solve just off the eigenvalue, on 32 segments.
  const Mesh mesh = mesh_for(c, lambda, {}, 32);
  const int nn = static_cast<int>(mesh.x.size());
  Eigen::VectorXd f(static_cast<Eigen::Index>(nn) * c.mc);
  for (Eigen::Index i = 0; i < f.size(); ++i) f[i] = std::sin(1.0 + 2.3 * static_cast<double>(i));  // deterministic
  // Just off the eigenvalue; further off if the solve meets the rounding floor (a very stiff
  // support makes the largest pivot huge): the contamination by other modes stays ~ shift / gap.
  Eigen::VectorXd d;
  for (double shift : {1e-7, 1e-5, 1e-3}) {
    try {
      d = assemble(c, lambda * (1.0 + shift) + 1e-12 * model_.lambda_scale, mesh).K.solve(f);
      break;
    } catch (const std::runtime_error&) {
      d.resize(0);
    }
  }
  if (d.size() == 0) return std::numeric_limits<double>::quiet_NaN();
  const auto q = to_fields(c, d, nn);
  const Eigen::MatrixXd& T = c.family_motions;
  const Eigen::MatrixXd TM = T.transpose() * model_.M;
  const Eigen::MatrixXd H = TM * T;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(H);
  double rigid = 0, total = 0;
  for (int i = 0; i < nn; ++i) {
    const double w = (i > 0 ? mesh.x[i] - mesh.x[i - 1] : 0.0) + (i + 1 < nn ? mesh.x[i + 1] - mesh.x[i] : 0.0);
    const Eigen::VectorXd r = cod.solve(Eigen::VectorXd(TM * q[i]));
    rigid += w * r.dot(H * r);
    total += w * q[i].dot(model_.M * q[i]);
  }
  return total > 0 ? rigid / total : 0.0;
}

ModeList LineAnalysis::modes(int k, const std::vector<ModeFamily>& families) {
  ModeList out;
  if (k <= 0) return out;
  const long evals0 = evaluations_;
  const std::vector<int> cls = pick(families);
  if (cls.empty()) return out;
  const double scale = model_.lambda_scale;
  const double delta = kRigidThreshold * scale;
  std::vector<Mesh> mesh(lines_.size());
  auto refresh = [&](double lam) {
    for (int c : cls) mesh[c] = mesh_for(*lines_[c], lam, {});
  };
  auto total = [&](double lam) {
    int n = 0;
    for (int c : cls) n += count_det(*lines_[c], lam, mesh[c]).count;
    return n;
  };
  refresh(scale);
  if (const int neg = total(-delta); neg > 0)
    throw std::runtime_error(fmt::format("the prism model has {} negative eigenvalue(s) omega^2 < 0: unstable", neg));
  std::vector<int> rigid_c(lines_.size(), 0);
  int rigid = 0;
  for (int c : cls) rigid += rigid_c[c] = count_det(*lines_[c], delta, mesh[c]).count;
  double lo = delta, hi = scale;
  int n_hi = rigid;
  if (rigid < k) {
    refresh(hi);
    n_hi = total(hi);
    for (int grow = 0; n_hi < k; ++grow) {
      if (grow > 200) throw std::runtime_error("dtfm: could not bracket the requested modes");
      lo = hi;
      hi *= 2.0;
      refresh(hi);
      n_hi = total(hi);
    }
    for (int it = 0; it < 8 && n_hi > k + 1; ++it) {  // fewer modes to polish above the k-th
      const double mid = 0.5 * (lo + hi);
      const int n = total(mid);
      if (n >= k) {
        hi = mid;
        n_hi = n;
      } else {
        lo = mid;
      }
    }
  }
  struct Found {
    double lambda;
    int cls;
  };
  std::vector<Found> all;
  for (int c : cls)
    for (int j = 0; j < rigid_c[c]; ++j) all.push_back({0.0, c});
  if (rigid < k) {
    for (int c : cls) {
      SliceStats st;
      const auto vals = slice_interval_polished(
          [&](double lam) { return count_det(*lines_[c], lam, mesh[c]); }, delta, hi, ctl_.rel_tol, 1e-14 * scale, &st);
      for (double v : vals) all.push_back({v, c});
    }
  }
  std::stable_sort(all.begin(), all.end(), [](const Found& a, const Found& b) { return a.lambda < b.lambda; });
  if (static_cast<int>(all.size()) > k) all.resize(k);
  out.rigid = std::min(rigid, k);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto& f = all[i];
    out.omega_rad_s.push_back(std::sqrt(std::max(f.lambda, 0.0)));
    out.cls.push_back(f.cls);
    auto& line = *lines_[f.cls];
    if (static_cast<int>(i) < out.rigid) {
      out.family.push_back(ModeFamily::Rigid);
      out.family_share.push_back(1.0);
      continue;
    }
    const double share = family_share(line, f.lambda);
    out.family_share.push_back(share);
    out.family.push_back(share >= ctl_.family_threshold ? line.family : ModeFamily::Unknown);
  }
  // Reproducibility: each mode's class is counted just below and above it (lambda (1 -+ tau))
  // on a second discretization (segments split in two, base pieces half as long: other J0,
  // other pivots, other rounding). A mode whose count does not come out as expected is below
  // the model's rounding floor (stiff layers or very slender spans against soft supports).
  constexpr double tau = 1e-4;
  std::vector<Mesh> alt(lines_.size());
  for (int c : cls) {
    alt[c] = refined(mesh[c]);
    // Longer base pieces where the evanescent bound sets them (fewer doublings), else shorter.
    const double longer = std::min({model_.length, mesh[c].h_im, 2.0 * mesh[c].h_re});
    alt[c].h_base = longer > 1.5 * mesh[c].h_base ? longer : 0.5 * mesh[c].h_base;
  }
  int failures = 0;
  for (std::size_t i = static_cast<std::size_t>(out.rigid); i < all.size(); ++i) {
    const int c = all[i].cls;
    const double lam = all[i].lambda;
    int below = rigid_c[c], upto = rigid_c[c];
    for (const auto& f : all)
      if (f.cls == c && f.lambda > 0) {
        below += f.lambda < lam * (1 - tau);
        upto += f.lambda <= lam * (1 + tau);
      }
    const int got_lo = count_det(*lines_[c], lam * (1 - tau), alt[c]).count;
    const int got_hi = count_det(*lines_[c], lam * (1 + tau), alt[c]).count;
    const bool ok = got_lo == below && got_hi >= upto;
    out.reproducible.push_back(ok);
    if (!ok) {
      out.count_consistent = false;
      if (++failures > 4) continue;
      out.count_message += fmt::format(
          "{}mode {} ({:.6g} rad/s) not reproduced to {:g} on a second discretization (counts {} / {} around it, "
          "expected {} / {})",
          out.count_message.empty() ? "" : "; ", i + 1, std::sqrt(lam), tau / 2, got_lo, got_hi, below, upto);
    }
  }
  if (failures > 4) out.count_message += fmt::format("; {} more", failures - 4);
  out.evaluations = evaluations_ - evals0;
  return out;
}

std::vector<Deflection> LineAnalysis::statics(const std::vector<PointLoad>& loads,
                                              const std::vector<std::array<double, 2>>& probes) {
  std::vector<double> required;
  for (const auto& p : loads) required.push_back(p.x);
  for (const auto& p : probes) required.push_back(p[0]);
  const int m = model_.m;
  std::vector<Eigen::VectorXd> qp(probes.size(), Eigen::VectorXd::Zero(m));
  for (const auto& line : lines_) {
    ClassLine& c = *line;
    const Mesh mesh = mesh_for(c, 0.0, required);
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
    if (f.norm() == 0.0) continue;
    const Assembled a = assemble(c, 0.0, mesh);
    Eigen::VectorXd d;
    try {
      d = a.K.solve(f);
    } catch (const std::runtime_error&) {
      throw std::runtime_error(fmt::format(
          "mechanism: the supports do not restrain the loaded motions ({} / {})", model_.ends[0].text,
          model_.ends[1].text));
    }
    const auto q = to_fields(c, d, nn);
    for (std::size_t j = 0; j < probes.size(); ++j) qp[j] += q[node(std::clamp(probes[j][0], 0.0, model_.length))];
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
                                                           int* skipped) {
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
  for (const auto& line : lines_) {
    ClassLine& c = *line;
    const Eigen::VectorXd fc0 = c.W.transpose() * f_full / c.sigma;
    const Eigen::RowVectorXd oc = o_full * c.W;
    if (fc0.norm() == 0.0 || oc.norm() == 0.0) continue;
    const Mesh mesh = mesh_for(c, w_max * w_max, {excite[0], observe[0]});
    const auto& x = mesh.x;
    const int nn = static_cast<int>(x.size());
    auto node = [&](double xx) {
      for (int i = 0; i < nn; ++i)
        if (std::abs(x[i] - xx) <= 1e-12 * model_.length) return i;
      return 0;
    };
    const int ie = node(std::clamp(excite[0], 0.0, model_.length));
    const int io = node(std::clamp(observe[0], 0.0, model_.length));
    Eigen::VectorXd fc = fc0;
    if (ie == 0) fc = c.ends[0].B.transpose() * fc;
    if (ie == nn - 1) fc = c.ends[1].B.transpose() * fc;
    auto observe_at = [&](auto dnode) {
      using V = std::decay_t<decltype(dnode)>;
      V d = dnode;
      if (io == 0) d = c.ends[0].B.template cast<typename V::Scalar>() * d;
      if (io == nn - 1) d = c.ends[1].B.template cast<typename V::Scalar>() * d;
      return (oc.template cast<typename V::Scalar>() * d)(0);
    };
    for (std::size_t s = 0; s < omegas.size(); ++s) {
      const double lam = omegas[s] * omegas[s];
      if (eta == 0.0) {
        Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nn) * c.mc);
        f.segment(static_cast<Eigen::Index>(ie) * c.mc, c.mc) = fc;
        try {
          const Eigen::VectorXd d = assemble(c, lam, mesh).K.solve(f);
          H[s] += observe_at(Eigen::VectorXd(d.segment(static_cast<Eigen::Index>(io) * c.mc, c.mc)));
        } catch (const std::runtime_error&) {
          bad[s] = 1;
        }
      } else {
        Eigen::VectorXcd f = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(nn) * c.mc);
        f.segment(static_cast<Eigen::Index>(ie) * c.mc, c.mc) = fc.cast<std::complex<double>>() / cdamp;
        try {
          const Eigen::VectorXcd d = assemble(c, std::complex<double>(lam) / cdamp, mesh).solve(f);
          H[s] += observe_at(Eigen::VectorXcd(d.segment(static_cast<Eigen::Index>(io) * c.mc, c.mc)));
        } catch (const std::runtime_error&) {
          bad[s] = 1;
        }
      }
    }
  }
  for (std::size_t s = 0; s < omegas.size(); ++s) {
    if (bad[s]) {
      H[s] = std::numeric_limits<double>::quiet_NaN();
      if (skipped) ++*skipped;
    }
  }
  return H;
}

}  // namespace modalbench::dtfm
