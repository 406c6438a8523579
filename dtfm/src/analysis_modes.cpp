// LineAnalysis natural frequencies: count-driven slicing per class, family labels, reproducibility check.
#include "modalbench/dtfm/analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis_detail.hpp"
#include "modalbench/numerics/line_system.hpp"

namespace modalbench::dtfm {

namespace {
using detail::to_fields;
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
      const auto vals = detail::slice_class(
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

}  // namespace modalbench::dtfm
