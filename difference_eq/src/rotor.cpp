// A spinning shaft on the regular Euler-Bernoulli chain (rotor.hpp).
#include "rotor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "modalbench/difference_eq/difference_eq.hpp"
#include "modalbench/rotor_scene.hpp"
#include "modalbench/whirl.hpp"

namespace modalbench::difference_eq {

namespace {

/// The chain in x-y (EI_z): the x-z chain's springs, its own stiffness.
RegularBeam beam_xy(const Scene& s, long R) {
  RegularBeam b = beam_of(s, R);
  b.EI = s.material.E * s.section().Iz;
  return b;
}

/// The planes' k lowest frequencies (x-y, x-z), as many as both give.
std::pair<std::vector<double>, std::vector<double>> planes(const Scene& s, long R, MassModel mass, int k, Summary& sum) {
  const Spectrum w = natural_frequencies(beam_of(s, R), mass, k), v = natural_frequencies(beam_xy(s, R), mass, k);
  sum.set_diagnostic("count_evaluations", std::max(0.0, sum.diagnostic("count_evaluations")) +
                                              static_cast<double>(w.count_evaluations + v.count_evaluations));
  const std::size_t n = std::min(w.omega_rad_s.size(), v.omega_rad_s.size());
  return {std::vector<double>(v.omega_rad_s.begin(), v.omega_rad_s.begin() + static_cast<long>(n)),
          std::vector<double>(w.omega_rad_s.begin(), w.omega_rad_s.begin() + static_cast<long>(n))};
}

/// The k lowest roots at `spin`: modes are added until the next mode's roots (at least its lower
/// plane frequency minus the spin) cannot be among them, or the chain has no more.
std::vector<WhirlRoot> roots_at(const Scene& s, long R, MassModel mass, double spin, int k, Summary& sum) {
  const bool rotating = s.rotor->frame == Rotor::Frame::Rotating;
  for (int kk = k;; kk *= 2) {
    const auto [v, w] = planes(s, R, mass, kk, sum);
    std::vector<WhirlRoot> out;
    for (std::size_t n = 0; n < v.size(); ++n) {
      if (rotating) {
        for (const WhirlRoot& r : rotating_frame_roots(v[n], w[n], spin)) out.push_back(r);
      } else {
        out.push_back({w[n], 0.0, Whirl::Backward, {}});
        out.push_back({w[n], 0.0, Whirl::Forward, {}});
      }
    }
    std::vector<double> sorted;
    for (const WhirlRoot& r : out) sorted.push_back(r.omega);
    std::sort(sorted.begin(), sorted.end());
    const bool more = static_cast<int>(v.size()) == kk;  // the chain may have more modes
    if (!more || !rotating || static_cast<int>(sorted.size()) < k ||
        std::min(v.back(), w.back()) - spin > sorted[static_cast<std::size_t>(k - 1)])
      return out;
  }
}

/// Every value up to `top` and the next above, from an ascending list that reaches past top
/// (or is all there is).
std::vector<double> up_to(const std::vector<double>& all, double top) {
  auto above = std::upper_bound(all.begin(), all.end(), top);
  if (above != all.end()) ++above;
  return {all.begin(), above};
}

}  // namespace

std::string rotor_refusal(const Scene& s) {
  if (!s.point_supports.empty() || !s.masses.empty())
    return "difference_eq's rotor is the appendix's A3 chain without supports or discs between the ends (a disc's "
           "gyroscopic moment is not in it)";
  if (!rotor_held(s))
    return "difference_eq solves rotors on end supports that hold them (a free rotor's rigid whirl is not solved yet)";
  if (!axisymmetric_shaft(s) && !classical_ends(s))
    return "difference_eq's asymmetric shaft needs ends free, pinned, clamped or guided (its planes then share "
           "their mode shapes): an end spring of an asymmetric shaft couples them otherwise";
  return "";
}

Campbell rotor_campbell(const Scene& s, long R, MassModel mass, Summary& sum) {
  const bool rotating = s.rotor->frame == Rotor::Frame::Rotating;
  const int k = s.request.modes;
  Campbell c;
  c.frame = to_string(s.rotor->frame);
  for (double spin : s.rotor->spin) {
    bool unstable = false;
    c.points.push_back(campbell_point(spin, roots_at(s, R, mass, spin, k, sum), k, unstable));
    if (unstable) c.unstable_spins.push_back(spin);
  }
  // Critical speeds: the chain's frequencies (flat whirl seen from the ground: each crosses the 1x
  // line at itself, forward and backward); an asymmetric shaft's, the planes' (a rotating-frame
  // root reaches 0 there, the ends of its unstable range).
  const double top = s.rotor->spin.back();
  for (int kk = std::max(k, 4);; kk *= 2) {
    const auto [v, w] = planes(s, R, mass, kk, sum);
    std::vector<double> all = w;
    if (!axisymmetric_shaft(s)) all.insert(all.end(), v.begin(), v.end());
    std::sort(all.begin(), all.end());
    if (static_cast<int>(v.size()) < kk || std::min(v.back(), w.back()) > top) {
      c.forward_criticals = up_to(all, top);
      if (axisymmetric_shaft(s)) c.backward_criticals = c.forward_criticals;
      break;
    }
  }
  c.criticals_note = axisymmetric_shaft(s) ? "the chain's bending frequencies: no gyroscopic moment, so each whirl crosses "
                                       "whirl = spin at its own frequency, forward and backward"
                                     : "forward: where a rotating-frame frequency is 0 (either plane's frequency of a "
                                       "mode); backward critical speeds of an asymmetric shaft are not given";
  if (s.request.shapes) c.orbit_note = "not given: difference_eq does not compute the chain's whirl orbits yet";
  c.note = fmt::format("regular chain of {} Hermite Euler-Bernoulli elements ({} mass){}: per mode shared by both "
                       "planes, (lambda^2 + omega_v^2 - Omega^2)(lambda^2 + omega_w^2 - Omega^2) + 4 Omega^2 lambda^2 = "
                       "0 in the rotating frame (the appendix's A3: 2 L_e and -K_e, the consistent translational "
                       "mass turned); seen from the ground no gyroscopic moment (no rotary inertia); undamped",
                       R, to_string(mass), rotating ? ", rotating frame" : ", stationary frame");
  return c;
}

}  // namespace modalbench::difference_eq
