#pragma once
// Private to the exact back-end: mode shapes of its beams, bars and plates (shapes.cpp).

#include <array>
#include <vector>

#include "modalbench/exact/beams.hpp"
#include "modalbench/exact/plates.hpp"

namespace modalbench::exact {

/// A mode of a beam in one plane (disp = w or v, rot = phi) or of a bar (disp = u or the twist)
/// at the points xs, with int mu (disp^2 + r^2 rot^2) dx and int mu disp dx of these values; a
/// beam's bending moment EI phi' (the statics' sign; a rigid mode's is 0) at the points too.
struct LineShape {
  std::vector<double> disp, rot, moment;
  double modal_mass = 0, participation = 0;
};
/// omega = 0: the rigid mode `rigid_index` of `rigid_count` (translation first, then rotation
/// about the centre of mass, point masses included). Point masses enter the modal mass and the
/// participation; rigid modes with point supports are not modelled (std::runtime_error).
LineShape bending_shape(const BeamBending& beam, EndSprings left, EndSprings right, double omega, int rigid_index,
                        int rigid_count, const std::vector<double>& xs, const PointAttachments& points = {});
LineShape bar_shape(const Bar& bar, double k_left, double k_right, double omega, const std::vector<double>& xs,
                    const PointAttachments& points = {});

/// A plate mode at points (x, y): w, theta_x = dw/dy, theta_y = -dw/dx; rho h int w^2 and
/// rho h int w of these values.
struct PlateShape {
  std::vector<double> w, theta_x, theta_y;
  double modal_mass = 0, participation = 0;
};
PlateShape navier_shape(double a, double b, double rho_h, int m, int n, const std::vector<std::array<double, 2>>& pts);
/// A Levy plate's mode at omega: the edges along `a` simply supported; `transposed` when the
/// simply supported edges are y = 0, b (then a is the width and the points' roles swap).
PlateShape levy_shape(double a, double b, double D, double nu, double rho_h, EndSprings y0, EndSprings yb,
                      double omega, const std::vector<std::array<double, 2>>& pts, bool transposed);

}  // namespace modalbench::exact
