// LineAnalysis natural frequencies: count-driven slicing per class, family labels, reproducibility check
// (the rigid and near-rigid modes below the count's resolution: analysis_near_rigid.cpp).
#include "modalbench/dtfm/analysis.hpp"

#include <fmt/format.h>

#include <Eigen/QR>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <numbers>
#include <optional>
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
  const auto q = to_fields(c, d, mesh.x);
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

/// Where a line is cut into two incommensurate segments (a second discretization): the golden
/// section, 0.618... of the way along.
const double kGoldenCut = 0.5 * (std::sqrt(5.0) - 1.0);

/// A beam's line is one segment: its poles (the segment's clamped-clamped frequencies) are the
/// zeros of a free-free Euler-Bernoulli span exactly, and nearly those of a span on very soft or
/// very stiff springs. At such a root K(lambda) is rounded relative to the pole's size, and the
/// count placed it 1e-8 off (a beam on springs of 1e-12 EI/L^3: mode 4 3.8e-9 off in omega with
/// a bound of 1.5e-12). Each value with a segment pole within kPoleGap of it (the segments' J0
/// differs across that interval) is sliced again there on the line cut at its golden section: two
/// segments of incommensurate lengths, whose poles lie elsewhere (halves would not do: a pinned
/// span's odd modes approach their clamped-clamped ones exponentially). The cut is not used
/// throughout: its shorter segments are stiffer, and a near-rigid mode's count resolves it less
/// well (a rocking on springs of 4e-5 EI/L^3 came out 9e-6 off instead of within 1.4e-6).
void LineAnalysis::repolish_near_poles(ClassLine& c, const Mesh& mesh, double lambda_max, std::vector<double>& vals,
                                       ModeList& out, SliceStats* st) {
  constexpr double kPoleGap = 1e-4;
  Mesh cut;
  for (std::size_t j = 0; j < vals.size(); ++j) {
    const double lo = vals[j] * (1 - kPoleGap), hi = vals[j] * (1 + kPoleGap);
    if (!(lo > 0) || assemble(c, lo, mesh).info.clamped_below == assemble(c, hi, mesh).info.clamped_below) continue;
    if (cut.x.empty()) cut = mesh_for(c, lambda_max, {kGoldenCut * model_.length});
    const auto again = slice_interval_polished([&](double lam) { return count_det(c, lam, cut); }, lo, hi,
                                               ctl_.rel_tol, 0.0, st);
    std::size_t here = 0;
    for (double v : vals) here += v >= lo && v < hi;
    if (again.size() == 1 && here == 1) {
      vals[j] = again[0];
    } else {
      out.count_consistent = false;
      out.count_message += fmt::format(
          "{}mode at {:.6g} rad/s lies within {:g} of a segment's pole and the cut line counts {} value(s) there, "
          "not {}",
          out.count_message.empty() ? "" : "; ", std::sqrt(vals[j]), kPoleGap, again.size(), here);
    }
  }
}

/// modes()' state from one phase to the next (the classes' meshes, near-rigid findings, bracket
/// and modes found so far).
struct LineAnalysis::ModeSearch {
  struct Found {
    double lambda;
    int cls;
    bool near = false;            // a near-rigid mode (below the count's resolution)
    const Mesh* mesh = nullptr;   // the mesh its band was sliced on
  };
  int k = 0;
  std::vector<int> cls;
  double scale = 0, delta = 0;
  std::vector<Mesh> mesh;                // per class: the mesh of the latest refresh
  std::vector<NearRigid> near;           // per class
  int rigid = 0;                         // the chosen classes' count below the rigid threshold
  double hi = 0;                         // the bracket's top
  std::vector<Found> all;
  int true_rigid = 0;
  std::vector<std::vector<Band>> bands;  // per class
};

ModeList LineAnalysis::modes(int k, const std::vector<ModeFamily>& families) {
  ModeList out;
  if (k <= 0) return out;
  const long evals0 = evaluations_;
  ModeSearch s;
  s.k = k;
  s.cls = pick(families);
  if (s.cls.empty()) return out;
  s.scale = model_.lambda_scale;
  s.delta = kRigidThreshold * s.scale;
  s.mesh.resize(lines_.size());
  s.bands.resize(lines_.size());
  const double rigid_below = modes_rigid_threshold(s);
  modes_near_rigid(s, rigid_below, out);
  modes_bracket(s);
  modes_rigid_found(s, out);
  if (s.rigid < k) modes_slice(s, out);
  modes_label(s, out);
  modes_reproducibility(s, out);
  out.evaluations = evaluations_ - evals0;
  return out;
}

/// Meshes every chosen class for [0, lam].
void LineAnalysis::modes_refresh(ModeSearch& s, double lam) {
  // The classes are independent line problems: each step of modes() runs them side by side.
  side_by_side(s.cls.size(), [&](std::size_t i) { s.mesh[s.cls[i]] = mesh_for(*lines_[s.cls[i]], lam, {}); });
}

/// The count below lam over the chosen classes, each on its current mesh.
int LineAnalysis::modes_total(ModeSearch& s, double lam) {
  std::vector<int> n(s.cls.size(), 0);
  side_by_side(s.cls.size(), [&](std::size_t i) { n[i] = count_det(*lines_[s.cls[i]], lam, s.mesh[s.cls[i]]).count; });
  int sum = 0;
  for (int v : n) sum += v;
  return sum;
}

/// The meshes for the scale and the threshold below which the count finds only rigid modes (kept
/// in rigid_shift_); throws on a negative eigenvalue.
double LineAnalysis::modes_rigid_threshold(ModeSearch& s) {
  auto total = [&](double lam) { return modes_total(s, lam); };
  modes_refresh(s, s.scale);
  // A plate's rigid-body motions that no edge reaches are exact zeros of the model, but its count
  // places them only within the rounding of K, which can exceed kRigidThreshold (a free plate of
  // 30 strips: three at |omega| ~ 2e-3 rad/s against 10 rad/s for the first elastic mode, some of
  // them negative on coarser strips). The threshold then moves up by decades to where the count
  // finds exactly those, none below minus it, and no other within a further factor of 100 (a gap
  // of two decades to the elastic modes); otherwise it stays, and what the count finds is judged
  // as before.
  double rigid_below = s.delta;
  if (model_.kind == SceneKind::Plate && model_.rigid_body_motions > 0 &&
      (total(s.delta) != model_.rigid_body_motions || total(-s.delta) != 0))
    rigid_below = plate_rigid_threshold(s.delta, s.scale, total);
  rigid_shift_ = rigid_below;
  if (const int neg = total(-rigid_below); neg > 0)
    throw std::runtime_error(fmt::format("the prism model has {} negative eigenvalue(s) omega^2 < 0: unstable", neg));
  return rigid_below;
}

/// Each class's count below the threshold and its rigid and near-rigid modes (s.near, s.rigid);
/// their problems into out's count message.
void LineAnalysis::modes_near_rigid(ModeSearch& s, double rigid_below, ModeList& out) {
  // Each class's count below the threshold and the lowest eigenvalues of classes with rigid
  // motions of their own, rigid (0) and near-rigid, side by side.
  std::vector<int> rigid_c(lines_.size(), 0);
  s.near.resize(lines_.size());
  side_by_side(s.cls.size(), [&](std::size_t i) {
    const int c = s.cls[i];
    rigid_c[c] = count_det(*lines_[c], rigid_below, s.mesh[c]).count;
    s.near[c] = near_rigid(*lines_[c], rigid_c[c]);
  });
  s.rigid = 0;
  for (int c : s.cls) {
    s.rigid += rigid_c[c];
    if (rigid_below > s.delta) {  // a plate's (no rigid split of its own): its rigid modes lie below
      s.near[c].lo = rigid_below;
      s.near[c].below_lo = s.near[c].rigid = rigid_c[c];
    }
    if (!s.near[c].problem.empty()) {
      out.count_consistent = false;
      out.count_message += (out.count_message.empty() ? "" : "; ") + s.near[c].problem;
    }
  }
}

/// The bracket's top s.hi above the k lowest eigenvalues, the classes meshed for it.
void LineAnalysis::modes_bracket(ModeSearch& s) {
  const int k = s.k;
  const double scale = s.scale;
  // A plate's bracket starts where its k-th eigenvalue is expected, over-estimated: by Weyl's law
  // (N ~ a b sqrt(lambda rho h / D) / (4 pi), which under-counts a bounded plate's lowest modes)
  // times 4. One count then usually brackets the k lowest: doubling from lambda_scale took 11
  // counts and 11 meshes per class on a 40-strip plate. The growth below still covers an
  // under-estimate, the trimming an over-estimate; the counts decide. A beam's classes (axial,
  // torsion, bending in two planes) spread its spectrum too unevenly for one estimate (the simply
  // supported beam's (k+1)-th cost a 2x2 section 545 counts for 25 modes instead of 453): it
  // doubles from lambda_scale, its first bending mode's order.
  double expected = scale;
  if (model_.kind == SceneKind::Plate) {
    double b = 0;
    for (const auto& p : model_.prisms) b += p.width;
    const double a = model_.length, D_over_mass = scale * std::pow(std::max(a, b) / std::numbers::pi, 4);
    if (b > 0) expected = 4.0 * std::pow(4.0 * std::numbers::pi * k / (a * b), 2) * D_over_mass;
  }
  // Off the grid of dyadic multiples of the scale: the bracket's top and the bands below it (a factor
  // kBand apart) would otherwise fall on the eigenvalues of symmetric structures (a beam pinned at
  // its middle: mode 1 at exactly 16 times the scale), where the two bands' counts disagree by
  // rounding.
  const double off_grid = 1.0 + 1.0 / (10.0 * std::numbers::sqrt2);
  double lo = s.delta, hi = (std::isfinite(expected) ? std::max(scale, expected) : scale) * off_grid;
  int n_hi = s.rigid;
  if (s.rigid < k) {
    modes_refresh(s, hi);
    double meshed_at = hi;
    n_hi = modes_total(s, hi);
    for (int grow = 0; n_hi < k; ++grow) {
      if (grow > 200) throw std::runtime_error("dtfm: could not bracket the requested modes");
      lo = hi;
      hi *= 2.0;
      modes_refresh(s, hi);
      meshed_at = hi;
      n_hi = modes_total(s, hi);
    }
    for (int it = 0; it < 8 && n_hi > k + 1; ++it) {  // fewer modes to polish above the k-th
      const double mid = 0.5 * (lo + hi);
      const int n = modes_total(s, mid);
      if (n >= k) {
        hi = mid;
        n_hi = n;
      } else {
        lo = mid;
      }
    }
    // The mesh for the bracket's top, not for an over-estimate far above it.
    if (hi < 0.5 * meshed_at) modes_refresh(s, hi);
  }
  s.hi = hi;
}

/// The rigid (0) and near-rigid modes into s.all, counted in out.
void LineAnalysis::modes_rigid_found(ModeSearch& s, ModeList& out) {
  for (int c : s.cls) {
    for (int j = 0; j < s.near[c].rigid; ++j) s.all.push_back({0.0, c});
    s.true_rigid += s.near[c].rigid;
    for (double v : s.near[c].lambdas) {
      s.all.push_back({v, c, true});
      ++out.near_rigid;
      out.near_rigid_bound = std::max(out.near_rigid_bound, s.near[c].bound);
    }
  }
}

/// Class c's bands (s.bands[c]) from the bracket's top down to its near-rigid threshold, ascending.
void LineAnalysis::modes_bands(ModeSearch& s, int c) {
  // Each class is sliced in bands of a factor kBand in lambda, each on the mesh its top needs:
  // one mesh for the whole range would cut the low modes into base pieces set by the highest
  // one, whose K(lambda) keeps lambda only to eps / (lambda m h^4 / EI) (mode 1 of a 1000-mode
  // slicing was 9.5e-4 off). Adjacent bands' counts at their common end must agree.
  constexpr double kBand = 16.0;
  // Whether two meshes discretize alike: the same nodes, every segment halved as often.
  auto same_pieces = [](const Mesh& a, const Mesh& b) {
    if (a.x != b.x) return false;
    for (std::size_t i = 0; i + 1 < a.x.size(); ++i) {
      const double h = a.x[i + 1] - a.x[i];
      if (detail::doubling_levels(h, a.h_base) != detail::doubling_levels(h, b.h_base)) return false;
    }
    return true;
  };
  auto& bc = s.bands[c];
  double top = s.hi, bot = s.hi;
  Mesh m = s.mesh[c];
  for (;;) {
    const double next = bot / kBand;
    Mesh mb;
    if (next > s.near[c].lo) mb = mesh_for(*lines_[c], next, {});
    if (!(next > s.near[c].lo) || !(mb.h_base > m.h_base)) {
      bc.push_back({s.near[c].lo, top, m});
      break;
    }
    bot = next;
    // A mesh that cuts every segment into as many base pieces is the same discretization: the
    // band goes on down (a 6x6 spatial beam's bound moved by 1e-4 relative per decade and
    // gave ten bands of one discretization per class, each with its own counts).
    if (same_pieces(mb, m)) continue;
    bc.push_back({bot, top, m});
    top = bot;
    m = mb;
  }
  std::reverse(bc.begin(), bc.end());
}

/// Every class sliced band by band (side by side), its values merged into s.all in class order
/// (a near-rigid enclosure correcting the lowest).
void LineAnalysis::modes_slice(ModeSearch& s, ModeList& out) {
  struct Sliced {
    SliceStats st;
    std::vector<double> vals;
    std::vector<const Band*> band_of;
    ModeList notes;  // count_consistent, count_message of the class's bands and re-polish
  };
  std::vector<Sliced> sliced(s.cls.size());
  side_by_side(s.cls.size(), [&](std::size_t i) {
    const int c = s.cls[i];
    Sliced& sl = sliced[i];
    modes_bands(s, c);
    const auto& bc = s.bands[c];
    for (std::size_t b = 0; b + 1 < bc.size(); ++b) {
      const int below = count_det(*lines_[c], bc[b].hi, bc[b].mesh).count;
      const int above = count_det(*lines_[c], bc[b].hi, bc[b + 1].mesh).count;
      if (below != above) {
        sl.notes.count_consistent = false;
        sl.notes.count_message += fmt::format("{}the counts at {:.6g} rad/s on two meshes differ ({} and {})",
                                              sl.notes.count_message.empty() ? "" : "; ", std::sqrt(bc[b].hi),
                                              below, above);
      }
    }
    for (const Band& band : s.bands[c]) {
      auto v = slice_interval_polished([&](double lam) { return count_det(*lines_[c], lam, band.mesh); }, band.lo,
                                       band.hi, ctl_.rel_tol, 1e-14 * s.scale, &sl.st);
      if (model_.kind == SceneKind::Beam) repolish_near_poles(*lines_[c], band.mesh, band.hi, v, sl.notes, &sl.st);
      sl.vals.insert(sl.vals.end(), v.begin(), v.end());
      sl.band_of.insert(sl.band_of.end(), v.size(), &band);
    }
  });
  for (std::size_t ci = 0; ci < s.cls.size(); ++ci) {
    const int c = s.cls[ci];
    const SliceStats& st = sliced[ci].st;
    const std::vector<double>& vals = sliced[ci].vals;
    const std::vector<const Band*>& band_of = sliced[ci].band_of;
    if (!sliced[ci].notes.count_consistent) {
      out.count_consistent = false;
      out.count_message += (out.count_message.empty() ? "" : "; ") + sliced[ci].notes.count_message;
    }
    out.polish_floor_width = std::max(out.polish_floor_width, st.polish_floor_width);
    for (std::size_t j = 0; j < vals.size(); ++j) {
      if (j < s.near[c].enclosures.size()) {
        // Inside its enclosure a sliced value is known to b as well (the count that placed it is
        // the one in doubt here), so b is its bound either way. One outside it is moved to the
        // enclosure's nearer end: a torsion on one spring beside G = 1e17 Pa was sliced 3e-8
        // below the lower end, the Ritz value (the upper end) 1.3e-7 above the truth.
        const auto [ritz, b] = s.near[c].enclosures[j];
        out.near_rigid_bound = std::max(out.near_rigid_bound, b);
        ++out.near_rigid;
        if (vals[j] < ritz / (1.0 + b) || vals[j] > ritz * (1.0 + 1e-12)) {
          s.all.push_back({std::clamp(vals[j], ritz / (1.0 + b), ritz), c, true});
          continue;
        }
      }
      s.all.push_back({vals[j], c, false, &band_of[j]->mesh});
    }
  }
}

/// The k lowest of s.all into out, ascending, with their families and family shares.
void LineAnalysis::modes_label(ModeSearch& s, ModeList& out) {
  auto& all = s.all;
  std::stable_sort(all.begin(), all.end(),
                   [](const ModeSearch::Found& a, const ModeSearch::Found& b) { return a.lambda < b.lambda; });
  if (static_cast<int>(all.size()) > s.k) all.resize(s.k);
  out.rigid = std::min(s.true_rigid, s.k);
  // One prism cannot deform in its section: every mode of a class is of its family (the share's
  // inverse iteration loses its digits next to springs of 1e12 EI / L^3 and mislabelled them).
  // Otherwise each mode's share from its own inverse iteration, side by side.
  const bool one_prism = model_.kind == SceneKind::Beam && model_.prisms.size() == 1;
  std::vector<double> shares(all.size(), 1.0);
  side_by_side(all.size(), [&](std::size_t i) {
    if (static_cast<int>(i) < out.rigid || all[i].near || one_prism) return;
    shares[i] = family_share(*lines_[all[i].cls], all[i].lambda);
  });
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
    if (f.near) {  // a rigid motion of its class on soft springs, by construction
      out.family.push_back(line.family);
      out.family_share.push_back(1.0);
      continue;
    }
    const double share = shares[i];
    out.family_share.push_back(share);
    out.family.push_back(share >= ctl_.family_threshold ? line.family : ModeFamily::Unknown);
  }
}

/// Each mode's count just below and above it on a second discretization: out.reproducible, and a
/// message for those that do not reproduce.
void LineAnalysis::modes_reproducibility(ModeSearch& s, ModeList& out) {
  const auto& all = s.all;
  // Reproducibility: each mode's class is counted just below and above it (lambda (1 -+ tau))
  // on a second discretization: each segment cut in three equal pieces, base pieces within the
  // same bounds (other J0, other pivots, other rounding, the same accuracy; 2/3 of the first's
  // length, not a power of two of it). Equal pieces share one long-segment matrix: the golden
  // section used before gave two of different lengths, twice the work. A mode whose count
  // does not come out as expected is below the model's rounding floor (stiff layers or very
  // slender spans against soft supports). Base pieces longer or shorter than the bounds would
  // test a worse discretization instead: twice the evanescent bound loses digits in exp(A h), half
  // of it one more doubling (a free plate of 180 strips and a cantilever of 64 were flagged so).
  constexpr double tau = 1e-4;
  auto alt_of = [&](const Mesh& m) {
    Mesh a = m;
    a.x = {m.x.front()};
    for (std::size_t i = 0; i + 1 < m.x.size(); ++i) {
      const double d = m.x[i + 1] - m.x[i];
      a.x.push_back(m.x[i] + d / 3.0);
      a.x.push_back(m.x[i] + 2.0 * d / 3.0);
      a.x.push_back(m.x[i + 1]);
    }
    return a;
  };
  std::deque<std::pair<const Mesh*, Mesh>> alt;  // per band's mesh
  auto alt_for = [&](const Mesh* m) -> const Mesh& {
    for (const auto& [key, a] : alt)
      if (key == m) return a;
    alt.emplace_back(m, alt_of(*m));
    return alt.back().second;
  };
  // The second discretizations first (one per band, shared by its modes), then every mode's two
  // counts side by side (count_det reads its class and mesh only), then the verdicts in order.
  const std::size_t first = static_cast<std::size_t>(out.rigid);
  std::vector<const Mesh*> alt_mesh(all.size(), nullptr);
  for (std::size_t i = first; i < all.size(); ++i)
    if (!all[i].near) alt_mesh[i] = &alt_for(all[i].mesh ? all[i].mesh : &s.mesh[all[i].cls]);
  std::vector<std::array<int, 2>> got(all.size(), {0, 0});
  side_by_side(all.size() - first, [&](std::size_t j) {
    const std::size_t i = first + j;
    if (!alt_mesh[i]) return;
    got[i][0] = count_det(*lines_[all[i].cls], all[i].lambda * (1 - tau), *alt_mesh[i]).count;
    got[i][1] = count_det(*lines_[all[i].cls], all[i].lambda * (1 + tau), *alt_mesh[i]).count;
  });
  int failures = 0;
  for (std::size_t i = first; i < all.size(); ++i) {
    if (all[i].near) {  // below the count's resolution: checked by its own bound instead
      out.reproducible.push_back(true);
      continue;
    }
    const int c = all[i].cls;
    const double lam = all[i].lambda;
    int below = s.near[c].below_lo, upto = s.near[c].below_lo;
    for (const auto& f : all)
      if (f.cls == c && f.lambda >= s.delta) {  // those below it are in below_lo
        below += f.lambda < lam * (1 - tau);
        upto += f.lambda <= lam * (1 + tau);
      }
    const int got_lo = got[i][0], got_hi = got[i][1];
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
}

}  // namespace modalbench::dtfm
