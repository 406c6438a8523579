#include "modalbench/numerics/line_mode.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "modalbench/numerics/balancing.hpp"
#include "modalbench/numerics/quadrature.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

namespace modalbench {

LineMode::LineMode(const LineSystem& sys, double lambda) : m_(sys.m), sys_(sys), lambda_(lambda) {
  if (!(lambda > 0)) throw std::invalid_argument("LineMode: lambda must be > 0 (rigid modes are the caller's)");
  const double sigma = lambda * (1.0 + 1e-11);
  // One set of nodes for both assemblies: the segment lengths follow the wavenumbers at lambda.
  LineSystem fixed = sys;
  const double p = sys.max_wavenumber(lambda);
  fixed.max_wavenumber = [p](double) { return p; };
  for (LinePiece& piece : fixed.steps) {
    const double q = piece.max_wavenumber(lambda);
    piece.max_wavenumber = [q](double) { return q; };
  }
  // A varying piece's cuts likewise, by its bound at lambda.
  auto fix = [lambda](LineVariation& v) {
    if (v) v.wavenumber_over = [bound = v.wavenumber_over, lambda](double, double a, double b) { return bound(lambda, a, b); };
  };
  fix(fixed.variation);
  for (LinePiece& piece : fixed.steps) fix(piece.variation);
  const AssembledLine shifted = assemble(fixed, sigma);
  const long n = static_cast<long>(shifted.xi.size()) * m_;
  // A deterministic start with every component present.
  Eigen::VectorXd v(n);
  for (long i = 0; i < n; ++i) v[i] = 1.0 + 0.5 * std::sin(1.7 * static_cast<double>(i) + 0.3);
  for (int step = 0; step < 2; ++step) {
    v = shifted.K.solve(v, 0.0);
    const double nv = v.cwiseAbs().maxCoeff();
    if (!(nv > 0) || !std::isfinite(nv)) throw std::runtime_error("LineMode: inverse iteration broke down");
    v /= nv;
  }
  // The fields at lambda itself, from the nodal displacements (same nodes: one discretization).
  xi_ = shifted.xi;
  const std::size_t nodes = xi_.size();
  y_.assign(nodes, Eigen::VectorXd::Zero(2 * m_));
  for (std::size_t i = 0; i + 1 < nodes; ++i) {
    const double h = xi_[i + 1] - xi_[i];
    A_.push_back(sys.state_matrix_at(lambda, 0.5 * (xi_[i] + xi_[i + 1])));
    const Eigen::MatrixXd K = sys.variation_at(0.5 * (xi_[i] + xi_[i + 1])) ? line_segment_stiffness(sys, lambda, xi_[i], xi_[i + 1])
                                                                         : segment_dynamic_stiffness(A_.back(), h);
    Eigen::VectorXd dd(2 * m_);
    dd << v.segment(static_cast<long>(i) * m_, m_), v.segment(static_cast<long>(i + 1) * m_, m_);
    const Eigen::VectorXd fk = K * dd;  // [-f(0); f(h)]
    y_[i].head(m_) = dd.head(m_);
    y_[i].tail(m_) = -fk.head(m_);
    if (i + 2 == nodes) {
      y_[i + 1].head(m_) = dd.tail(m_);
      y_[i + 1].tail(m_) = fk.tail(m_);
    }
  }
}

Eigen::MatrixXd LineMode::transfer(std::size_t segment, double s) const {
  if (sys_.variation_at(0.5 * (xi_[segment] + xi_[segment + 1])))
    return line_transfer(sys_, lambda_, xi_[segment], xi_[segment] + s);
  Eigen::MatrixXd B = A_[segment] * s;
  const Eigen::VectorXd scale = balance_in_place(B, 20);
  return scale.asDiagonal() * Eigen::MatrixXd(B.exp()) * scale.cwiseInverse().asDiagonal();
}

Eigen::VectorXd LineMode::state(double xi) const {
  if (xi <= xi_.front()) return y_.front();
  if (xi >= xi_.back()) return y_.back();
  const auto it = std::upper_bound(xi_.begin(), xi_.end(), xi);
  const std::size_t i = static_cast<std::size_t>(it - xi_.begin()) - 1;
  if (xi == xi_[i]) return y_[i];
  return transfer(i, xi - xi_[i]) * y_[i];
}

double LineMode::integrate(const std::function<double(const Eigen::VectorXd& d, double xi)>& g, double zero_scale) const {
  // Each segment to 1e-12 relative, or absolutely to 1e-13 of |g| h at its ends and middle (a
  // segment whose integrand cancels cannot reach a relative tolerance); the accumulated error
  // estimate must stay below 1e-9 of the total.
  double total = 0, error = 0, scale = 0;
  for (std::size_t i = 0; i + 1 < xi_.size(); ++i) {
    const Eigen::VectorXd y0 = y_[i];
    const double x0 = xi_[i], x1 = xi_[i + 1];
    auto f = [&](double x) { return g((transfer(i, x - x0) * y0).head(m_), x); };
    // |g| sampled off the segment's symmetry points: an antisymmetric mode's integrand vanishes at
    // the ends and the middle of a pinned beam, and a zero scale asked 1e-12 of an integral that
    // rounds to 1e-17 (GSL ran out of subintervals on the deep beam's seventh mode).
    double gmax = std::max(std::abs(f(x0)), std::abs(f(x1)));
    for (int k = 0; k < 9; ++k) gmax = std::max(gmax, std::abs(f(x0 + (x1 - x0) * (k + 0.381966) / 9.0)));
    const double size = (x1 - x0) * gmax;
    const Integral part = modalbench::integrate(f, x0, x1, 1e-12, 1e-13 * (size + zero_scale * (x1 - x0)) + 1e-300);
    total += part.value;
    error += part.abs_error;
    scale += std::abs(part.value);
  }
  if (error > 1e-9 * std::max({std::abs(total), scale, zero_scale}) + 1e-300)
    throw std::runtime_error("LineMode: the modal integral is accurate only to " + std::to_string(error) + " of " +
                             std::to_string(total));
  return total;
}

}  // namespace modalbench
