// A beam's properties over the cells of its rigid and spring-damping elements (beam_cells.hpp).
#include "beam_cells.hpp"

#include <algorithm>

namespace modalbench::rfem::detail {

namespace {

/// Calls f(lo, hi, piece) for each piece's share [lo, hi] of [a, b].
template <class F>
void over_pieces(const std::vector<Segment>& pieces, double a, double b, F&& f) {
  for (const Segment& p : pieces) {
    const double lo = std::max(a, p.x_from), hi = std::min(b, p.x_to);
    if (hi > lo) f(lo, hi, p);
  }
}

}  // namespace

CellMass cell_mass(const std::vector<Segment>& pieces, double a, double b, double c) {
  CellMass out;
  over_pieces(pieces, a, b, [&](double lo, double hi, const Segment& p) {
    const Section s = p.properties();
    const double rho = p.material.rho, len = hi - lo, u = lo - c, v = hi - c;
    out.mass += rho * s.A * len;
    out.length_inertia += rho * s.A * (v * v * v - u * u * u) / 3.0;
    out.rho_Ip += rho * s.Ip * len;
    out.rho_Iy += rho * s.Iy * len;
    out.rho_Iz += rho * s.Iz * len;
  });
  return out;
}

CellStiffness cell_stiffness(const std::vector<Segment>& pieces, double a, double b) {
  double fEA = 0, fkGA = 0, fGJ = 0, fEIy = 0, fEIz = 0;
  over_pieces(pieces, a, b, [&](double lo, double hi, const Segment& p) {
    const Section s = p.properties();
    const Material& m = p.material;
    const double len = hi - lo;
    fEA += len / (m.E * s.A);
    fkGA += len / (m.kappa * m.G * s.A);
    fGJ += len / (m.G * s.J);
    fEIy += len / (m.E * s.Iy);
    fEIz += len / (m.E * s.Iz);
  });
  return {1.0 / fEA, 1.0 / fkGA, 1.0 / fGJ, 1.0 / fEIy, 1.0 / fEIz};
}

}  // namespace modalbench::rfem::detail
