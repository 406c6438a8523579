#pragma once
// Private to the beam builder: a beam's properties integrated over the parts of it that one rigid
// element (its mass, rotary inertia) or one spring-damping element (its compliances, in series)
// stands for. Exact for a stepped beam ([[segments]]) wherever its steps fall; over a tapered
// piece, integrated to rounding by Gauss-Legendre quadrature (beam_cells.cpp).

#include <vector>

#include "modalbench/scene.hpp"

namespace modalbench::rfem::detail {

/// The mass properties of [a, b] about x = c: int rho A dx, int rho A (x - c)^2 dx, and the
/// section's rotary inertia int rho (Ip, Iy, Iz) dx (kg, kg m^2).
struct CellMass {
  double mass = 0, length_inertia = 0, rho_Ip = 0, rho_Iy = 0, rho_Iz = 0;
};
CellMass cell_mass(const std::vector<Segment>& pieces, double a, double b, double c);

/// The stiffnesses of [a, b] as springs in series, 1 / int dx / S(x), for S = EA, kGA, GJ, EIy, EIz
/// (N, N, N m^2, N m^2, N m^2 per the length: N/m and N m/rad).
struct CellStiffness {
  double EA = 0, kGA = 0, GJ = 0, EIy = 0, EIz = 0;
};
CellStiffness cell_stiffness(const std::vector<Segment>& pieces, double a, double b);

}  // namespace modalbench::rfem::detail
