// One modal coordinate's exact response (core transient.hpp) against the textbook closed forms of
// a single oscillator, written here independently: step, impulse, ramp, sine (off and at
// resonance), under-, critically and overdamped, and rigid modes; the stepped samples against the
// closed form. Tolerance: each closed form carries rounding of its phase omega t, so the error
// scales with eps * max(1, omega t) times the response's size.
#define BOOST_TEST_MODULE test_transient
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>
#include <limits>

#include "modalbench/transient.hpp"

using namespace modalbench;

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

LoadFunction step() { return LoadFunction::of(TransientRequest{}); }
LoadFunction ramp(double rise) {
  TransientRequest r;
  r.load = TransientRequest::Load::Ramp;
  r.rise = rise;
  return LoadFunction::of(r);
}
LoadFunction impulse() {
  TransientRequest r;
  r.load = TransientRequest::Load::Impulse;
  return LoadFunction::of(r);
}
LoadFunction harmonic(double W) {
  TransientRequest r;
  r.load = TransientRequest::Load::Harmonic;
  r.omega = W;
  return LoadFunction::of(r);
}

/// |q(t) - ref(t)| over [0, tmax] within 64 eps max(1, omega t) scale.
void agrees(const ModalResponse& m, const std::function<double(double)>& ref, double tmax, double scale, double omega) {
  for (int i = 0; i <= 400; ++i) {
    const double t = tmax * i / 400.0;
    const double tol = 64 * kEps * std::max(1.0, omega * t) * scale;
    BOOST_TEST(std::abs(m.q(t) - ref(t)) <= tol, "t = " << t << ": " << m.q(t) << " vs " << ref(t));
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(undamped_step_is_one_minus_cosine) {
  const double w = 37.0;
  const ModalResponse m(w, 0.0, step());
  agrees(
      m, [&](double t) { return (1 - std::cos(w * t)) / (w * w); }, 3.0, 2 / (w * w), w);
  for (double t : {0.1, 0.7, 2.9}) BOOST_TEST(std::abs(m.v(t) - std::sin(w * t) / w) <= 64 * kEps * w * t / w);
}

BOOST_AUTO_TEST_CASE(damped_step_settles_on_the_static_value) {
  const double w = 120.0, z = 0.05, wd = w * std::sqrt(1 - z * z);
  const ModalResponse m(w, 2 * z * w, step());
  agrees(
      m,
      [&](double t) {
        return (1 - std::exp(-z * w * t) * (std::cos(wd * t) + z / std::sqrt(1 - z * z) * std::sin(wd * t))) / (w * w);
      },
      2.0, 2 / (w * w), w);
}

BOOST_AUTO_TEST_CASE(impulse_is_the_decaying_sine) {
  const double w = 8.0, z = 0.3, wd = w * std::sqrt(1 - z * z);
  const ModalResponse m(w, 2 * z * w, impulse());
  agrees(
      m, [&](double t) { return std::exp(-z * w * t) * std::sin(wd * t) / wd; }, 5.0, 1 / w, w);
}

BOOST_AUTO_TEST_CASE(critically_and_overdamped_steps) {
  const double w = 10.0;
  const ModalResponse crit(w, 2 * w, step());
  agrees(
      crit, [&](double t) { return (1 - std::exp(-w * t) * (1 + w * t)) / (w * w); }, 2.0, 1 / (w * w), w);
  const double z = 2.0, r1 = -z * w + w * std::sqrt(z * z - 1), r2 = -z * w - w * std::sqrt(z * z - 1);
  const ModalResponse over(w, 2 * z * w, step());
  agrees(
      over, [&](double t) { return (1 - (r2 * std::exp(r1 * t) - r1 * std::exp(r2 * t)) / (r2 - r1)) / (w * w); }, 4.0,
      1 / (w * w), w);
}

BOOST_AUTO_TEST_CASE(ramp_is_two_ramps_superposed) {
  const double w = 25.0, rise = 0.2;
  auto unit_ramp = [&](double t) { return t <= 0 ? 0.0 : (t - std::sin(w * t) / w) / (w * w * rise); };
  const ModalResponse m(w, 0.0, ramp(rise));
  agrees(
      m, [&](double t) { return unit_ramp(t) - unit_ramp(t - rise); }, 1.0, 2 / (w * w), w);
  // The same as a table, with a hold after the last knot.
  TransientRequest r;
  r.load = TransientRequest::Load::Table;
  r.time = {0.0, rise};
  r.factor = {0.0, 1.0};
  const ModalResponse tab(w, 0.0, LoadFunction::of(r));
  agrees(
      tab, [&](double t) { return unit_ramp(t) - unit_ramp(t - rise); }, 1.0, 2 / (w * w), w);
}

BOOST_AUTO_TEST_CASE(sine_off_and_at_resonance) {
  const double w = 30.0, W = 21.0;
  const ModalResponse off(w, 0.0, harmonic(W));
  agrees(
      off, [&](double t) { return (std::sin(W * t) - W / w * std::sin(w * t)) / (w * w - W * W); }, 3.0,
      2 / (w * w - W * W), w);
  const ModalResponse res(w, 0.0, harmonic(w));
  agrees(
      res, [&](double t) { return (std::sin(w * t) - w * t * std::cos(w * t)) / (2 * w * w); }, 3.0,
      3 * w / (2 * w * w), w);
}

BOOST_AUTO_TEST_CASE(rigid_modes) {
  const ModalResponse free(0.0, 0.0, step());
  agrees(
      free, [](double t) { return t * t / 2; }, 3.0, 4.5, 1.0);
  const double c = 0.7;  // Rayleigh's alpha on a rigid mode: q'' + c q' = 1
  const ModalResponse damped(0.0, c, step());
  agrees(
      damped, [&](double t) { return t / c - (1 - std::exp(-c * t)) / (c * c); }, 3.0, 3.0, 1.0);
  const double W = 4.0;  // q'' = sin(W t) from rest
  const ModalResponse sine(0.0, 0.0, harmonic(W));
  agrees(
      sine, [&](double t) { return t / W - std::sin(W * t) / (W * W); }, 3.0, 1.0, W);
}

BOOST_AUTO_TEST_CASE(stepped_samples_follow_the_closed_form) {
  TransientRequest r;
  r.load = TransientRequest::Load::Table;
  r.time = {0.0, 0.013, 0.05, 0.0501};
  r.factor = {0.5, 1.0, -0.3, 0.0};
  const LoadFunction g = LoadFunction::of(r);
  const double w = 900.0, dt = 1e-5;
  const std::size_t n = 20000;
  for (double c : {0.0, 2 * 0.02 * w, 2 * 3.0 * w}) {
    const ModalResponse m(w, c, g);
    const std::vector<double> q = m.sample(dt, n);
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) worst = std::max(worst, std::abs(q[i] - m.q(static_cast<double>(i) * dt)));
    // 256 steps between re-anchorings, each a few roundings of the response's size.
    BOOST_TEST(worst <= 256 * 8 * kEps * 2 / (w * w), "c = " << c << ": " << worst);
  }
}
