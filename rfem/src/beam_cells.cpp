// A beam's properties over the cells of its rigid and spring-damping elements (beam_cells.hpp).
#include "beam_cells.hpp"

#include <Eigen/Core>

#include <algorithm>

#include "modalbench/gauss_legendre.hpp"

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

/// The integrands of a tapered piece at x = c + u: rho (A, A u^2, Ip, Iy, Iz) and the compliances
/// per length 1 / (EA, kGA, GJ, EIy, EIz). (u is given, not x - c: its rounding would be that of x.)
using Integrands = Eigen::Matrix<double, 10, 1>;
Integrands integrands(const Segment& p, double c, double u) {
  const double x = c + u;
  const Section s = p.properties_at(x);
  const Material& m = p.material;
  const double rho = m.rho;
  Integrands f;
  f << rho * s.A, rho * s.A * u * u, rho * s.Ip, rho * s.Iy, rho * s.Iz, 1.0 / (m.E * s.A),
      1.0 / (p.kappa_at(x) * m.G * s.A), 1.0 / (m.G * s.J), 1.0 / (m.E * s.Iy), 1.0 / (m.E * s.Iz);
  return f;
}

/// 8-point Gauss-Legendre on [c + ua, c + ub], in u = x - c.
Integrands gauss8(const Segment& p, double c, double ua, double ub) {
  using gauss_legendre8::node, gauss_legendre8::weight;
  const double mid = 0.5 * (ua + ub), half = 0.5 * (ub - ua);
  Integrands sum = Integrands::Zero();
  for (std::size_t i = 0; i < node.size(); ++i)
    sum += weight[i] * (integrands(p, c, mid - half * node[i]) + integrands(p, c, mid + half * node[i]));
  return half * sum;
}

/// The integrals over [c + ua, c + ub] of a tapered piece to rounding: the 8-point rule, halved
/// (in u, so that u^2 keeps its digits near c) until the halves agree with the whole to 1e-14 in
/// each component. The integrands are smooth (polynomials of degree <= 4 and their reciprocals, or
/// exponentials): a level or two. At most 10 levels: a rectangle's torsion constant, a series, is
/// smooth only to its truncation (1e-12) where the sides cross, and there 1e-14 cannot be met.
Integrands integrate(const Segment& p, double c, double ua, double ub, const Integrands& whole, int depth = 0) {
  const double um = 0.5 * (ua + ub);
  const Integrands left = gauss8(p, c, ua, um), right = gauss8(p, c, um, ub), both = left + right;
  const bool agreed = ((both - whole).array().abs() <= 1e-14 * both.array().abs()).all();
  if (agreed || depth >= 10) return both;
  return integrate(p, c, ua, um, left, depth + 1) + integrate(p, c, um, ub, right, depth + 1);
}

Integrands tapered(const Segment& p, double a, double b, double c) {
  return integrate(p, c, a - c, b - c, gauss8(p, c, a - c, b - c));
}

}  // namespace

CellMass cell_mass(const std::vector<Segment>& pieces, double a, double b, double c) {
  CellMass out;
  over_pieces(pieces, a, b, [&](double lo, double hi, const Segment& p) {
    if (p.tapered()) {
      const Integrands f = tapered(p, lo, hi, c);
      out.mass += f[0];
      out.length_inertia += f[1];
      out.rho_Ip += f[2];
      out.rho_Iy += f[3];
      out.rho_Iz += f[4];
      return;
    }
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
    if (p.tapered()) {
      const Integrands f = tapered(p, lo, hi, 0.5 * (lo + hi));
      fEA += f[5];
      fkGA += f[6];
      fGJ += f[7];
      fEIy += f[8];
      fEIz += f[9];
      return;
    }
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
