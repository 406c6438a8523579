#pragma once
// Private to the line system (line_system.cpp): its varying pieces (LineVariation in
// line_system.hpp), each segment a Magnus product (varying_transfer.hpp).

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "modalbench/numerics/line_system.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"
#include "modalbench/numerics/varying_transfer.hpp"

namespace modalbench::detail {

/// A gap inside a varying piece has at least this many segments (each a Magnus product), so that
/// a distributed load's Gauss points per segment integrate its smooth fixed-end reactions to
/// rounding at lambda = 0, where the wavenumbers would allow one segment.
inline constexpr int kMinVaryingSegments = 8;

/// The transfer matrix of y' = A(x) y over [x0, x1] (varying_transfer, steps doubled until two
/// agree to 1e-15; throws std::runtime_error where the estimate stays above 1e-12); `d`: a fixed
/// balancing (empty: each step's own).
VaryingTransfer magnus_transfer(const std::function<Eigen::MatrixXd(double)>& A, double x0, double x1,
                                const Eigen::VectorXd& d = {});

/// K(lambda) of the varying segment [x0, x1] with its divided difference (SegmentDivided).
SegmentDivided varying_divided(const LineVariation& v, double lambda, double x0, double x1);

/// Cuts the gap [a, b] of a varying piece into segments each with |p| h <= 1 by its own comparison
/// bound (none then has a clamped frequency below lambda), at least `min_parts` of them; appends
/// the nodes after a (b last).
void cut_varying(const LineVariation& v, double lambda, double a, double b, int min_parts, std::vector<double>& xi,
                 int depth = 0);

}  // namespace modalbench::detail
