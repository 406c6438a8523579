// The exact rotor (rotor.hpp): whirl frequencies per spin and critical speeds, solved for.
//
// Axisymmetric shaft: each whirl direction is a planar line (whirl_line.hpp) whose frequencies the
// Wittrick-Williams count brackets exactly. The rotating frame of such a shaft sees the forward
// whirl at omega_F - Omega and the backward at omega_B + Omega. An asymmetric uniform
// Euler-Bernoulli shaft with the same end conditions in both planes (free, pinned, clamped or
// guided: the two planes share their mode shapes) couples mode n of one plane with mode n of the
// other only; in the rotating frame, with a = omega_zn^2 - Omega^2 and b = omega_yn^2 - Omega^2,
//   (lambda^2 + a) (lambda^2 + b) + 4 Omega^2 lambda^2 = 0,
// i.e. x = -lambda^2 solves x^2 - (a + b + 4 Omega^2) x + a b = 0.
#include "rotor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "modalbench/exact/beams.hpp"
#include "modalbench/numerics/line_system.hpp"
#include "modalbench/rotor_scene.hpp"
#include "modalbench/whirl.hpp"
#include "whirl_line.hpp"

namespace modalbench::exact::detail {

namespace {

/// The lowest k frequencies of one whirl line (rad/s) and, at `xs` (if any), each one's planar shape.
WhirlBranch branch(const Scene& s, const Whirling& w, int k, Summary& sum, const std::vector<double>& xs = {}) {
  const BendingLine line = whirl_line(s, w);
  SliceStats st;
  const LineSpectrum spec = lowest_eigenvalues(line.sys, k, 1.0 / line.lam_to_Omega2, &st);
  sum.set_diagnostic("count_evaluations",
                     std::max(0.0, sum.diagnostic("count_evaluations")) + static_cast<double>(st.count_evaluations));
  WhirlBranch out;
  for (double lam : spec.lambdas) out.omega.push_back(std::sqrt(std::max(lam, 0.0)));
  if (!xs.empty())
    for (double omega : out.omega) out.shape.push_back(whirl_shape(s, w, omega, xs));
  return out;
}

int count_below(const Scene& s, const Whirling& w, double omega) {
  return modalbench::count_below(whirl_line(s, w).sys, omega * omega);
}

/// The whirl roots of an axisymmetric shaft at `spin`, in the scene's frame, with their orbits at
/// `xs` (if any).
std::vector<WhirlRoot> axisymmetric_roots(const Scene& s, double spin, int k, Summary& sum,
                                          const std::vector<double>& xs) {
  return axisymmetric_whirl(
      spin, s.rotor->frame == Rotor::Frame::Rotating, k,
      [&](int sense, int n) { return branch(s, {sense, spin, false}, n, sum, xs); },
      [&](double omega) { return count_below(s, {+1, spin, false}, omega); });
}

/// The k lowest roots of the asymmetric shaft (rotating frame) at `spin`.
std::vector<WhirlRoot> asymmetric_roots(const Scene& s, double spin, int k, Summary& sum) {
  const EndSprings l{s.x0.translational, s.x0.rotational}, r{s.xL.translational, s.xL.rotational};
  for (int kk = k;; kk *= 2) {
    const Frequencies fz = beam_bending_frequencies(bending_xz(s), l, r, kk), fy = beam_bending_frequencies(bending_xy(s), l, r, kk);
    sum.set_diagnostic("count_evaluations", std::max(0.0, sum.diagnostic("count_evaluations")) +
                                                static_cast<double>(fz.count_evaluations + fy.count_evaluations));
    std::vector<WhirlRoot> out;
    for (int n = 0; n < kk; ++n)
      for (const WhirlRoot& w : rotating_frame_roots(fy.omega_rad_s[n], fz.omega_rad_s[n], spin)) out.push_back(w);
    std::sort(out.begin(), out.end(), [](const WhirlRoot& a, const WhirlRoot& b) { return a.omega < b.omega; });
    // Mode n's roots are at least min(omega_n) - spin: beyond the k-th root, no later mode reaches.
    const double next = std::min(fz.omega_rad_s.back(), fy.omega_rad_s.back());
    if (next - spin > out[static_cast<std::size_t>(k - 1)].omega || kk >= (1 << 16)) return out;
  }
}

/// Critical speeds of one whirl direction of an axisymmetric shaft: every one up to `top` and the
/// next above (where the direction has one: a forward whirl's may be finitely many).
std::vector<double> synchronous(const Scene& s, int sense, double top, double scale, Summary& sum) {
  const Whirling w{sense, 0.0, true};
  const int below = count_below(s, w, top);
  const int far = count_below(s, w, 100.0 * std::max(top, scale));
  const int n = std::min(far, below + 1);
  return n > 0 ? branch(s, w, n, sum).omega : std::vector<double>{};
}

}  // namespace

std::string rotor_refusal(const Scene& s) {
  if (!rotor_held(s))
    return "exact solves rotors on supports that hold them (a free rotor's rigid whirl is not solved yet)";
  if (axisymmetric_shaft(s)) return "";
  if (s.theory == Theory::EulerBernoulli && !s.is_stepped() && !s.has_tapered_pieces() && s.masses.empty() &&
      s.point_supports.empty() && classical_ends(s))
    return "";
  return "exact solves an asymmetric shaft (Iy != Iz) only as a uniform (neither stepped nor tapered) Euler-Bernoulli shaft without discs or "
         "supports between the ends, each end free, pinned, clamped or guided (the planes then share their mode "
         "shapes and each mode pair has a closed form); rfem models the others";
}

Campbell rotor_campbell(const Scene& s, Summary& sum) {
  Campbell c;
  const int k = s.request.modes;
  const bool sym = axisymmetric_shaft(s);
  c.frame = to_string(s.rotor->frame);
  // Orbits where [request.shapes] asks: an axisymmetric shaft's whirl is a circle of its line's shape.
  std::vector<double> xs;
  if (s.request.shapes) {
    for (const auto& pt : s.shape_points()) xs.push_back(pt[0]);
    if (sym) {
      c.orbit_points_m = xs;
      c.orbit_note = "circles (w = -+ i v) of each whirl line's mode shape at its frequency, by the beam's transfer "
                     "matrices";
    } else {
      c.orbit_note = "not given: the asymmetric shaft's elliptic orbits are not computed by exact yet";
    }
  }
  for (double spin : s.rotor->spin) {
    bool unstable = false;
    c.points.push_back(campbell_point(
        spin, sym ? axisymmetric_roots(s, spin, k, sum, c.orbit_points_m) : asymmetric_roots(s, spin, k, sum), k,
        unstable));
    if (unstable) c.unstable_spins.push_back(spin);
  }
  const double top = s.rotor->spin.back();
  if (sym) {
    const double scale = branch(s, {+1, 0.0, false}, 1, sum).omega.at(0);
    c.forward_criticals = synchronous(s, +1, top, scale, sum);
    c.backward_criticals = synchronous(s, -1, top, scale, sum);
    c.criticals_note = "synchronous whirl per direction (rotary inertias rho I -+ rho I_p, J_t -+ J_p), bisected on "
                       "the Wittrick-Williams count: every critical speed up to the highest spin and the next above";
    c.note = fmt::format("exact {} shaft: per whirl direction a planar line with rotary inertia rho I - s rho I_p "
                         "Omega / omega (discs J_t - s J_p Omega / omega), its frequencies bracketed by the "
                         "Wittrick-Williams count{}; undamped (material.loss_factor is not applied): growth rates 0",
                         to_string(s.theory),
                         s.rotor->frame == Rotor::Frame::Rotating ? "; rotating frame: omega_F - Omega, omega_B + Omega"
                                                                  : "");
  } else {
    const EndSprings l{s.x0.translational, s.x0.rotational}, r{s.xL.translational, s.xL.rotational};
    for (int kk = std::max(k, 4);; kk *= 2) {
      const std::vector<double> z = beam_bending_frequencies(bending_xz(s), l, r, kk).omega_rad_s;
      const std::vector<double> y = beam_bending_frequencies(bending_xy(s), l, r, kk).omega_rad_s;
      std::vector<double> all = z;
      all.insert(all.end(), y.begin(), y.end());
      std::sort(all.begin(), all.end());
      const auto above = std::upper_bound(all.begin(), all.end(), top);
      // Complete up to the lower of the two planes' last frequencies (both above the top: the
      // next critical above it is among them).
      if (std::min(z.back(), y.back()) > top || kk >= (1 << 16)) {
        c.forward_criticals.assign(all.begin(), above == all.end() ? above : above + 1);
        break;
      }
    }
    c.criticals_note = "forward: where a rotating-frame frequency is 0 (Omega = either plane's frequency of a mode, "
                       "the ends of its unstable range); backward critical speeds of an asymmetric shaft are not given";
    c.note = "exact asymmetric Euler-Bernoulli shaft in the rotating frame: per mode n, (lambda^2 + omega_zn^2 - "
             "Omega^2)(lambda^2 + omega_yn^2 - Omega^2) + 4 Omega^2 lambda^2 = 0 (Coriolis and spin softening of the "
             "shared mode shape); growth rate: Re lambda of the growing root of each pair";
  }
  return c;
}

}  // namespace modalbench::exact::detail
