// Whirl of a mode shared by both bending planes (whirl.hpp).
#include "modalbench/whirl.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

namespace modalbench {

std::array<WhirlRoot, 2> rotating_frame_roots(double omega_v, double omega_w, double spin) {
  using C = std::complex<double>;
  const double O2 = spin * spin, a = omega_w * omega_w - O2, b = omega_v * omega_v - O2;
  const double p = a + b + 4 * O2;
  const C disc = std::sqrt(C(p * p - 4 * a * b));
  std::array<WhirlRoot, 2> out;
  int i = 0;
  for (const C x : {(p + disc) / 2.0, (p - disc) / 2.0}) {  // x = -lambda^2
    const C lambda = std::sqrt(-x);                          // Re >= 0: the growing root of +-lambda
    WhirlRoot r{std::abs(lambda.imag()), std::max(0.0, lambda.real()), spin > 0 ? Whirl::None : Whirl::Planar, {}};
    if (r.omega > 1e-13 * std::sqrt(std::abs(x)) && spin > 0) {
      // v'' - 2 Omega w' + b v = 0: W / V = (lambda^2 + b) / (2 Omega lambda); the orbit turns in the
      // spin's sense (v to w) where Im(V conj W) > 0, i.e. Im(W / V) < 0 (lambda with Im > 0).
      const C l(lambda.real(), std::abs(lambda.imag()));
      r.whirl = ((l * l + b) / (2.0 * spin * l)).imag() < 0 ? Whirl::Forward : Whirl::Backward;
    }
    out[static_cast<std::size_t>(i++)] = r;
  }
  return out;
}

CampbellPoint campbell_point(double spin, std::vector<WhirlRoot> roots, int k, bool& unstable) {
  std::stable_sort(roots.begin(), roots.end(), [](const WhirlRoot& a, const WhirlRoot& b) { return a.omega < b.omega; });
  if (static_cast<int>(roots.size()) > k) roots.resize(static_cast<std::size_t>(k));
  CampbellPoint p;
  p.spin_rad_s = spin;
  unstable = false;
  const bool orbits = std::any_of(roots.begin(), roots.end(), [](const WhirlRoot& r) { return !r.orbit.v.empty(); });
  for (const WhirlRoot& r : roots) {
    p.frequencies_rad_s.push_back(r.omega);
    p.whirl.push_back(r.whirl);
    p.growth_rates_1_s.push_back(r.growth);
    if (orbits) p.orbits.push_back(r.orbit);
    unstable = unstable || r.growth > 0;
  }
  return p;
}

void normalize(Orbit& o) {
  // The point of the largest orbit (the first such); there v, or w where v is negligible, is made
  // real and positive.
  double top = 0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < o.v.size(); ++i)
    if (const double a = std::norm(o.v[i]) + std::norm(o.w[i]); a > top * (1 + 1e-9)) {
      top = a;
      at = i;
    }
  if (!(top > 0)) return;
  const std::complex<double> big = std::norm(o.v[at]) >= 1e-6 * top ? o.v[at] : o.w[at];
  const std::complex<double> f = std::conj(big) / std::abs(big) / std::sqrt(top);
  for (auto& c : o.v) c *= f;
  for (auto& c : o.w) c *= f;
}

Orbit circular_orbit(const std::vector<double>& phi, Whirl sense) {
  const std::complex<double> turn(0.0, sense == Whirl::Forward ? -1.0 : 1.0);
  Orbit o;
  for (double p : phi) {
    o.v.push_back(p);
    o.w.push_back(turn * p);
  }
  normalize(o);
  return o;
}

std::vector<WhirlRoot> axisymmetric_whirl(double spin, bool rotating, int k,
                                          const std::function<WhirlBranch(int sense, int n)>& branch,
                                          const std::function<int(double omega)>& forward_below) {
  WhirlBranch fw = branch(+1, k);
  const WhirlBranch bw = branch(-1, k);
  auto orbit = [](const WhirlBranch& b, std::size_t i, Whirl sense) {
    return i < b.shape.size() ? circular_orbit(b.shape[i], sense) : Orbit{};
  };
  std::vector<WhirlRoot> out;
  auto collect = [&] {
    out.clear();
    for (std::size_t i = 0; i < bw.omega.size(); ++i)
      out.push_back({rotating ? bw.omega[i] + spin : bw.omega[i], 0.0, Whirl::Backward, orbit(bw, i, Whirl::Backward)});
    for (std::size_t i = 0; i < fw.omega.size(); ++i) {
      const double f = fw.omega[i], d = rotating ? f - spin : f;
      const Whirl sense = std::abs(d) <= 1e-13 * f ? Whirl::None : d > 0 ? Whirl::Forward : Whirl::Backward;
      out.push_back({std::abs(d), 0.0, sense, orbit(fw, i, sense == Whirl::None ? Whirl::Forward : sense)});
    }
    std::stable_sort(out.begin(), out.end(), [](const WhirlRoot& a, const WhirlRoot& b) { return a.omega < b.omega; });
  };
  collect();
  if (rotating && static_cast<int>(out.size()) >= k) {
    // A forward frequency near the spin is a low one in the rotating frame.
    const int n = forward_below(spin + out[static_cast<std::size_t>(k - 1)].omega);
    if (n > static_cast<int>(fw.omega.size())) {
      fw = branch(+1, n);
      collect();
    }
  }
  return out;
}

}  // namespace modalbench
