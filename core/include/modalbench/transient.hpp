#pragma once
// Time histories by modal superposition (`[request.transient]`): each modal coordinate
//   q'' + c q' + omega^2 q = g(t)        (unit modal mass, unit modal force)
// integrated exactly for the load's time function g (piecewise linear, an impulse, or a sine), so
// no time step enters the modal responses: the output step only samples them.
//
// Usage:
//   const LoadFunction g = LoadFunction::of(scene.request.transient.value());
//   const ModalResponse q(omega_n, damping_coefficient(request, omega_n), g);
//   double w = q.q(0.01), v = q.v(0.01);   // at any t >= 0, closed form

#include <string>
#include <vector>

#include "modalbench/scene.hpp"

namespace modalbench {

/// The time function g(t) of a transient request: piecewise linear through (time, factor) knots
/// (a step is the knots (0, 1); after the last knot the last factor holds), a unit impulse at t = 0,
/// or sin(omega t).
struct LoadFunction {
  enum class Kind { PiecewiseLinear, Impulse, Harmonic };
  Kind kind = Kind::PiecewiseLinear;
  std::vector<double> time, factor;  ///< knots, time[0] = 0 (factor[0] = g(0+))
  double omega = 0;                  ///< harmonic, rad/s

  static LoadFunction of(const TransientRequest& rq);
  /// g(t) for t >= 0 (at t = 0 the value just after loading, 0+); 0 for an impulse.
  double value(double t) const;
  /// dg/dt (on a knot, the slope after it).
  double slope(double t) const;
  std::string describe() const;
};

/// The damping coefficient c = 2 zeta omega of a mode of the request (0 without damping).
double damping_coefficient(const TransientRequest& rq, double omega);

/// One modal coordinate's exact response from rest (q(0) = q'(0) = 0; an impulse sets q'(0+) = 1).
/// Underdamped, critically and overdamped modes and rigid ones (omega = 0) alike.
class ModalResponse {
 public:
  ModalResponse(double omega, double c, const LoadFunction& g);
  double q(double t) const;  ///< displacement (per unit modal force)
  double v(double t) const;  ///< velocity
  /// q at t = i dt, i = 0 .. n - 1, stepped exactly between the load's knots (each step the free
  /// response's 2 x 2 transition; re-anchored on the closed form every 256 steps and at knots).
  std::vector<double> sample(double dt, std::size_t n) const;
  double omega() const { return omega_; }

 private:
  struct State {
    double q, v;
  };
  /// The state at t, from the state s at the start t0 of a stretch where g is linear.
  State advance(const State& s, double t0, double t) const;
  State harmonic(double t) const;
  State at(double t) const;

  double omega_, c_;
  LoadFunction g_;
  std::vector<State> knots_;  ///< the state at each knot of a piecewise-linear g
};

}  // namespace modalbench
