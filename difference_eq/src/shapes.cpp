// Mode shapes of the regular discrete beam: the closed-form nodal shapes (vibration.hpp),
// interpolated along each element with its own Hermite shape functions, normalized in the
// model's own mass matrix (consistent or lumped).

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "attachments.hpp"
#include "modalbench/difference_eq/difference_eq.hpp"

namespace modalbench::difference_eq {

namespace {

constexpr double kConsistent[4][4] = {{156, 22, 54, -13}, {22, 4, 13, -3}, {54, 13, 156, -22}, {-13, -3, -22, 4}};
constexpr double kLumped[4][4] = {{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 0}};
constexpr double kStiffness[4][4] = {{12, 6, -12, 6}, {6, 4, -6, 2}, {-12, -6, 12, -6}, {6, 2, -6, 4}};

/// u' M v over the assembled mass: element by element, u_e = (w_e, a s_e, w_e+1, a s_e+1),
/// M_e = rhoA a / c * table (c = 420 consistent, 2 lumped).
double mass_product(const RegularBeam& b, MassModel mass, const ModeShape& u, const ModeShape& v,
                    const std::vector<NodalAttachment>& at) {
  const double a = b.a(), scale = b.rhoA * a / (mass == MassModel::Consistent ? 420.0 : 2.0);
  const auto& me = mass == MassModel::Consistent ? kConsistent : kLumped;
  double sum = 0;
  for (long e = 0; e < b.R; ++e) {
    const double ue[4] = {u.w[e], a * u.slope[e], u.w[e + 1], a * u.slope[e + 1]};
    const double ve[4] = {v.w[e], a * v.slope[e], v.w[e + 1], a * v.slope[e + 1]};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) sum += ue[i] * me[i][j] * ve[j];
  }
  double points = 0;  // the point masses: m w w' and J (their slope)(slope')
  for (const NodalAttachment& p : at) {
    const auto r = static_cast<std::size_t>(p.node);
    points += p.m * u.w[r] * v.w[r] + p.J * u.slope[r] * v.slope[r];
  }
  return scale * sum + points;
}

/// The bending moment My = EI w'' (sagging positive) of a mode inside element e at xi in [0, 1]:
/// the element's end moments from its nodal displacements, K_e u_e (the element's stiffness forces,
/// exact at the nodes under nodal loads), linear between its ends. Not K_e u_e - omega^2 M_e u_e:
/// summed over the modes with their static weights that would miss the statics by M_e M^-1 f.
double element_moment(const RegularBeam& b, const ModeShape& u, long e, double xi) {
  const double a = b.a(), k = b.EI / (a * a * a);
  const double ue[4] = {u.w[e], a * u.slope[e], u.w[e + 1], a * u.slope[e + 1]};
  double f[4] = {0, 0, 0, 0};  // conjugate to (w, a s): a moment is a times its entry
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) f[i] += k * kStiffness[i][j] * ue[j];
  const double left = -a * f[1], right = a * f[3];
  return left + (right - left) * xi;
}

/// The rigid-body modes the supports leave (rigid_body_modes): translation w = 1 and/or a
/// rotation w = x - x_pivot, slope 1 (about the one end with a translational spring).
std::vector<ModeShape> rigid_shapes(const RegularBeam& b) {
  const long R = b.R;
  const double a = b.a();
  auto translation = [&] {
    ModeShape s;
    s.w.assign(R + 1, 1.0);
    s.slope.assign(R + 1, 0.0);
    return s;
  };
  auto rotation = [&](double pivot) {
    ModeShape s;
    for (long r = 0; r <= R; ++r) {
      s.w.push_back(static_cast<double>(r) * a - pivot);
      s.slope.push_back(1.0);
    }
    return s;
  };
  const int n = rigid_body_modes(b);
  if (n == 2) return {translation(), rotation(0.5 * b.L)};
  if (n == 1) {
    if (b.r0 > 0 || b.rL > 0) return {translation()};
    return {rotation(b.k0 > 0 ? 0.0 : b.L)};
  }
  return {};
}

}  // namespace

ModeShapes DifferenceEqSolver::shapes(const Scene& s, const RegularBeam& beam, MassModel mass,
                                      const std::vector<double>& omega, int rigid) {
  ModeShapes out;
  out.points = s.shape_points();
  out.components = s.shape_components();  // bending x-z: w, theta_y (others stay 0: not modelled)
  out.directions = {false, false, true};
  const std::vector<NodalAttachment> at = attachments_of(s, beam.R);
  out.total_mass = beam.rhoA * beam.L;
  for (const NodalAttachment& p : at) out.total_mass += p.m;
  auto mprod = [&](const ModeShape& u, const ModeShape& v) { return mass_product(beam, mass, u, v, at); };
  const double a = beam.a();
  ModeShape ones;
  ones.w.assign(beam.R + 1, 1.0);
  ones.slope.assign(beam.R + 1, 0.0);
  // Rigid modes first (omega = 0 exactly), M-orthonormalized among themselves (Gram-Schmidt).
  std::vector<ModeShape> nodal = at.empty() ? rigid_shapes(beam) : rigid_shapes_attached(beam, at);
  nodal.resize(std::min<std::size_t>(nodal.size(), static_cast<std::size_t>(rigid)));
  for (std::size_t i = 1; i < nodal.size(); ++i) {
    const double c = mprod(nodal[i], nodal[0]) / mprod(nodal[0], nodal[0]);
    for (long r = 0; r <= beam.R; ++r) {
      nodal[i].w[r] -= c * nodal[0].w[r];
      nodal[i].slope[r] -= c * nodal[0].slope[r];
    }
  }
  for (std::size_t k = static_cast<std::size_t>(rigid); k < omega.size(); ++k) {
    if (at.empty()) {
      nodal.push_back(mode_shape(beam, mass, omega[k]));
    } else {
      double backward_error = 0;
      nodal.push_back(mode_shape_attached(beam, mass, at, omega[k], backward_error));
    }
  }
  const bool moments = s.request.shapes && s.request.shapes->moments;
  for (const ModeShape& u : nodal) {
    std::vector<std::vector<double>> mode(out.components.size(), std::vector<double>(out.points.size(), 0.0));
    std::vector<double> moment(moments ? out.points.size() : 0);
    for (std::size_t p = 0; p < out.points.size(); ++p) {
      const double x = out.points[p][0];
      const long e = std::min<long>(beam.R - 1, static_cast<long>(std::floor(x / a)));
      const double xi = std::clamp((x - static_cast<double>(e) * a) / a, 0.0, 1.0);
      // Hermite cubics on (w_e, s_e, w_e+1, s_e+1) and their derivatives (per x).
      const double N[4] = {1 - 3 * xi * xi + 2 * xi * xi * xi, a * (xi - 2 * xi * xi + xi * xi * xi),
                           3 * xi * xi - 2 * xi * xi * xi, a * (-xi * xi + xi * xi * xi)};
      const double dN[4] = {(-6 * xi + 6 * xi * xi) / a, 1 - 4 * xi + 3 * xi * xi, (6 * xi - 6 * xi * xi) / a,
                            -2 * xi + 3 * xi * xi};
      const double nod[4] = {u.w[e], u.slope[e], u.w[e + 1], u.slope[e + 1]};
      double w = 0, slope = 0;
      for (int i = 0; i < 4; ++i) {
        w += N[i] * nod[i];
        slope += dN[i] * nod[i];
      }
      for (std::size_t c = 0; c < out.components.size(); ++c) {
        if (out.components[c] == 2) mode[c][p] = w;
        if (out.components[c] == 4) mode[c][p] = -slope;  // theta_y = -dw/dx
      }
      if (moments) moment[p] = element_moment(beam, u, e, xi);
    }
    out.values.push_back(std::move(mode));
    if (moments) out.moments.push_back(std::move(moment));
    out.generalized_mass.push_back(mprod(u, u));
    out.participation.push_back({0.0, 0.0, mprod(u, ones)});
  }
  out.note = std::string(at.empty() ? "closed-form nodal shapes (null vector of the characteristic matrix; "
                                     : "nodal shapes by inverse iteration on the assembled model with the point "
                                       "supports and masses (") +
             "rigid modes M-orthonormalized), "
             "interpolated with the elements' Hermite cubics, normalized in the model's " + to_string(mass) +
             " mass matrix; bending in x-z only" +
             (moments ? "; moments My from each element's stiffness end forces, linear between its nodes" : "");
  finish_mode_shapes(out);
  return out;
}

}  // namespace modalbench::difference_eq
