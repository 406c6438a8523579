// One modal coordinate's exact response (transient.hpp): on each stretch where the load is
// linear, the particular solution of the ramp plus the free response that matches the state at
// the stretch's start; a sine load by its complex particular solution.
#include "modalbench/transient.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

namespace modalbench {

std::string to_string(TransientRequest::Load l) {
  switch (l) {
    case TransientRequest::Load::Step:
      return "step";
    case TransientRequest::Load::Impulse:
      return "impulse";
    case TransientRequest::Load::Ramp:
      return "ramp";
    case TransientRequest::Load::Harmonic:
      return "harmonic";
    case TransientRequest::Load::Table:
      return "table";
  }
  return "?";
}

LoadFunction LoadFunction::of(const TransientRequest& rq) {
  LoadFunction g;
  switch (rq.load) {
    case TransientRequest::Load::Step:
      g.time = {0.0}, g.factor = {1.0};
      break;
    case TransientRequest::Load::Ramp:
      g.time = {0.0, rq.rise}, g.factor = {0.0, 1.0};
      break;
    case TransientRequest::Load::Table:
      g.time = rq.time, g.factor = rq.factor;
      break;
    case TransientRequest::Load::Impulse:
      g.kind = Kind::Impulse;
      break;
    case TransientRequest::Load::Harmonic:
      g.kind = Kind::Harmonic, g.omega = rq.omega;
      break;
  }
  return g;
}

namespace {
/// The index of the stretch [time[k], time[k+1]) holding t (the last: from the last knot on).
std::size_t stretch_of(const std::vector<double>& time, double t) {
  const auto it = std::upper_bound(time.begin(), time.end(), t);
  return it == time.begin() ? 0 : static_cast<std::size_t>(it - time.begin()) - 1;
}
double stretch_slope(const LoadFunction& g, std::size_t k) {
  if (k + 1 >= g.time.size()) return 0.0;
  return (g.factor[k + 1] - g.factor[k]) / (g.time[k + 1] - g.time[k]);
}
}  // namespace

double LoadFunction::value(double t) const {
  switch (kind) {
    case Kind::Impulse:
      return 0.0;
    case Kind::Harmonic:
      return std::sin(omega * t);
    case Kind::PiecewiseLinear:
      break;
  }
  const std::size_t k = stretch_of(time, t);
  return factor[k] + stretch_slope(*this, k) * (t - time[k]);
}

double LoadFunction::slope(double t) const {
  switch (kind) {
    case Kind::Impulse:
      return 0.0;
    case Kind::Harmonic:
      return omega * std::cos(omega * t);
    case Kind::PiecewiseLinear:
      break;
  }
  return stretch_slope(*this, stretch_of(time, t));
}

std::string LoadFunction::describe() const {
  switch (kind) {
    case Kind::Impulse:
      return "an impulse at t = 0 (the loads in N s)";
    case Kind::Harmonic:
      return fmt::format("sin({:.6g} t) (rad/s), from rest", omega);
    case Kind::PiecewiseLinear:
      break;
  }
  if (time.size() == 1)
    return factor[0] == 1.0 ? "a step: the loads switched on at t = 0"
                            : fmt::format("a step: {:.6g} times the loads from t = 0", factor[0]);
  return fmt::format("piecewise linear through {} points, {:.6g} after {:.6g} s", time.size(), factor.back(),
                     time.back());
}

double damping_coefficient(const TransientRequest& rq, double omega) {
  switch (rq.damping) {
    case TransientRequest::Damping::None:
      return 0.0;
    case TransientRequest::Damping::Modal:
      return 2.0 * rq.zeta * omega;
    case TransientRequest::Damping::Rayleigh:
      return rq.alpha + rq.beta * omega * omega;
  }
  return 0.0;
}

namespace {
struct Free {
  double q, v;
};
/// The free response of q'' + c q' + omega^2 q = 0 from (x0, v0) after tau:
///   q = e^{-a tau} [x0 C + (v0 + a x0) S],  q' = e^{-a tau} [v0 C - (a v0 + omega^2 x0) S]
/// with a = c / 2 and (C, S) = (cos wd tau, sin(wd tau) / wd), (cosh mu tau, sinh(mu tau) / mu) or
/// (1, tau) as the mode is under-, over- or critically damped.
Free free_response(double omega, double c, double x0, double v0, double tau) {
  const double a = 0.5 * c;
  double eC, eS;
  if (omega > a) {
    const double wd = std::sqrt((omega - a) * (omega + a));
    const double e = std::exp(-a * tau);
    eC = e * std::cos(wd * tau);
    eS = e * std::sin(wd * tau) / wd;
  } else if (omega < a) {
    const double mu = std::sqrt((a - omega) * (a + omega));
    const double e1 = std::exp(-omega * omega / (a + mu) * tau);  // e^{(mu - a) tau}, without cancellation
    eC = 0.5 * e1 * (1.0 + std::exp(-2.0 * mu * tau));
    eS = -0.5 * e1 * std::expm1(-2.0 * mu * tau) / mu;
  } else {
    const double e = std::exp(-a * tau);
    eC = e;
    eS = e * tau;
  }
  return {eC * x0 + eS * (v0 + a * x0), eC * v0 - eS * (a * v0 + omega * omega * x0)};
}
}  // namespace

ModalResponse::ModalResponse(double omega, double c, const LoadFunction& g) : omega_(omega), c_(c), g_(g) {
  if (!(omega >= 0) || !(c >= 0) || !std::isfinite(omega) || !std::isfinite(c))
    throw std::invalid_argument(
        fmt::format("modal response: omega {} and damping {} must be finite and >= 0", omega, c));
  if (g_.kind != LoadFunction::Kind::PiecewiseLinear) return;
  knots_.push_back({0.0, 0.0});
  for (std::size_t k = 0; k + 1 < g_.time.size(); ++k)
    knots_.push_back(advance(knots_.back(), g_.time[k], g_.time[k + 1]));
}

ModalResponse::State ModalResponse::advance(const State& s, double t0, double t) const {
  const double tau = t - t0;
  const std::size_t k = stretch_of(g_.time, t0);
  const double p0 = g_.factor[k] + stretch_slope(g_, k) * (t0 - g_.time[k]);
  const double sl = stretch_slope(g_, k);
  if (omega_ > 0) {
    // Particular solution of the ramp p0 + sl tau: (p0 + sl tau) / w^2 - c sl / w^4.
    const double w2 = omega_ * omega_;
    const double qp0 = p0 / w2 - c_ * sl / (w2 * w2), vp = sl / w2;
    const Free h = free_response(omega_, c_, s.q - qp0, s.v - vp, tau);
    return {h.q + qp0 + sl * tau / w2, h.v + vp};
  }
  if (c_ == 0)
    return {s.q + s.v * tau + p0 * tau * tau / 2 + sl * tau * tau * tau / 6, s.v + p0 * tau + sl * tau * tau / 2};
  // A rigid mode with damping: the velocity u' + c u = p0 + sl tau, then its integral.
  const double u0p = (p0 - sl / c_) / c_;
  const double decay = -std::expm1(-c_ * tau);  // 1 - e^{-c tau}
  return {s.q + u0p * tau + sl * tau * tau / (2 * c_) + (s.v - u0p) * decay / c_,
          u0p + sl * tau / c_ + (s.v - u0p) * (1.0 - decay)};
}

ModalResponse::State ModalResponse::harmonic(double t) const {
  const double W = g_.omega, w2 = omega_ * omega_;
  const std::complex<double> D(w2 - W * W, c_ * W);
  if (D == 0.0) {  // undamped resonance: (sin wt - wt cos wt) / (2 w^2)
    const double st = std::sin(W * t), ct = std::cos(W * t);
    return {(st - W * t * ct) / (2 * w2), t * st / 2};
  }
  const std::complex<double> H = 1.0 / D;
  const double st = std::sin(W * t), ct = std::cos(W * t);
  const double qp = H.real() * st + H.imag() * ct, vp = W * (H.real() * ct - H.imag() * st);
  const Free h = free_response(omega_, c_, -H.imag(), -W * H.real(), t);
  return {h.q + qp, h.v + vp};
}

ModalResponse::State ModalResponse::at(double t) const {
  switch (g_.kind) {
    case LoadFunction::Kind::Impulse: {
      const Free h = free_response(omega_, c_, 0.0, 1.0, t);
      return {h.q, h.v};
    }
    case LoadFunction::Kind::Harmonic:
      return harmonic(t);
    case LoadFunction::Kind::PiecewiseLinear:
      break;
  }
  const std::size_t k = stretch_of(g_.time, t);
  return advance(knots_[k], g_.time[k], t);
}

double ModalResponse::q(double t) const { return at(t).q; }
double ModalResponse::v(double t) const { return at(t).v; }

std::vector<double> ModalResponse::sample(double dt, std::size_t n) const {
  std::vector<double> out(n);
  // Rigid modes and sines: the closed form at each sample (few modes, or no fixed transition).
  if (omega_ == 0 || g_.kind == LoadFunction::Kind::Harmonic) {
    for (std::size_t i = 0; i < n; ++i) out[i] = q(static_cast<double>(i) * dt);
    return out;
  }
  // The deviation from the stretch's particular solution evolves by the free response's transition.
  const Free c1 = free_response(omega_, c_, 1.0, 0.0, dt), c2 = free_response(omega_, c_, 0.0, 1.0, dt);
  const double w2 = omega_ * omega_;
  auto particular = [&](double t, std::size_t k) -> std::pair<double, double> {
    if (g_.kind == LoadFunction::Kind::Impulse) return {0.0, 0.0};
    const double sl = stretch_slope(g_, k);
    return {(g_.factor[k] + sl * (t - g_.time[k])) / w2 - c_ * sl / (w2 * w2), sl / w2};
  };
  auto stretch = [&](double t) { return g_.kind == LoadFunction::Kind::Impulse ? 0 : stretch_of(g_.time, t); };
  double dq = 0, dv = 0;
  std::size_t k_prev = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    const std::size_t k = stretch(t);
    const auto [qp, vp] = particular(t, k);
    if (i == 0 || k != k_prev || i % 256 == 0) {
      const State s = at(t);
      dq = s.q - qp, dv = s.v - vp;
    } else {
      const double nq = c1.q * dq + c2.q * dv, nv = c1.v * dq + c2.v * dv;
      dq = nq, dv = nv;
    }
    out[i] = dq + qp;
    k_prev = k;
  }
  return out;
}

}  // namespace modalbench
