#pragma once
// The scene's static loads as weights on points, so that a mode's modal force is
// P = sum_i sum_d weight[i][d] phi_d(point_i): point loads at their points, distributed loads by
// Gauss-Legendre quadrature of their intensity against the sampled shape. Not installed.
#include <array>
#include <vector>

#include "modalbench/scene.hpp"

namespace modalbench::detail {

struct LoadPoint {
  std::array<double, 2> at{};
  std::array<double, 6> weight{};  ///< per dofs index (u, v, w, theta_x, theta_y, theta_z): N or N m
};

/// The load points of every static load (gravity included), fine enough for shapes of up to
/// `modes` modes: each distributed load's span (patch) is cut at every point where the structure
/// changes (pieces, supports, masses, point loads) and into pieces no longer than about a quarter
/// of the shortest wave of `modes` modes, each integrated by 6-point Gauss-Legendre.
std::vector<LoadPoint> load_points(const Scene& scene, int modes);

}  // namespace modalbench::detail
