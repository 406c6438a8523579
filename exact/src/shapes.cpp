// Exact mode shapes: beams and bars from the null vector of the exact dynamic stiffness and the
// transfer matrix between nodes (numerics/line_mode.hpp), Navier plates in closed form, Levy
// plates from their strip's line mode; modal masses and participations by GSL quadrature of the
// exact fields where no closed form is used.

#include "exact_shapes.hpp"

#include <functional>
#include <stdexcept>
#include <utility>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "line_models.hpp"
#include "modalbench/gauss_legendre.hpp"
#include "modalbench/numerics/line_mode.hpp"

namespace modalbench::exact {

namespace {
constexpr double pi = std::numbers::pi;
}  // namespace

namespace {

/// The point masses' share of a mode: sum m disp^2 + J rot^2 into the modal mass, sum m disp into
/// the participation (disp, rot: the mode at each attachment).
void add_point_masses(const PointAttachments& points, const std::function<std::pair<double, double>(double)>& at,
                      LineShape& out) {
  for (const PointAttachment& p : points) {
    if (p.mass == 0 && p.inertia == 0) continue;
    const auto [disp, rot] = at(p.x);
    out.modal_mass += p.mass * disp * disp + p.inertia * rot * rot;
    out.participation += p.mass * disp;
  }
}

/// The integral over the beam of density(x, properties at x): piece by piece, a uniform piece's by
/// its closed form f(x1, x2, piece), a tapered one's by 8-point Gauss-Legendre on 16 parts (its
/// properties are polynomials of degree <= 8 in x or exponentials: to rounding).
double over_pieces(const BeamBending& beam, const std::function<double(double, double, const BeamBending&)>& f,
                   const std::function<double(double, const BeamBending&)>& density) {
  std::vector<double> ends = {0.0};
  std::vector<bool> varies = {static_cast<bool>(beam.varies)};
  for (const BendingStep& s : beam.steps) {
    ends.push_back(s.x_from);
    varies.push_back(static_cast<bool>(s.varies));
  }
  ends.push_back(beam.L);
  double sum = 0;
  for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
    if (!varies[i]) {
      sum += f(ends[i], ends[i + 1], beam.at(ends[i]));
      continue;
    }
    sum += gauss_legendre8::integrate([&](double x) { return density(x, beam.at(x)); }, ends[i], ends[i + 1], 16);
  }
  return sum;
}

/// A bar's inertia per length as a beam's rhoA, piece by piece (for over_pieces).
BeamBending bar_as_beam(const Bar& bar) {
  const auto variation = [](const BarVariation& v) {
    if (!v) return BendingVariation{};
    return BendingVariation{[v](double x) { return BendingProps{1.0, 1.0, v.at(x).mu, 0.0}; },
                            [v](double x0, double x1) { return BendingProps{1.0, 1.0, v.bound(x0, x1).mu, 0.0}; }};
  };
  BeamBending b{1.0, 1.0, bar.mu, 0.0, bar.L, {}, variation(bar.varies)};
  for (const BarStep& st : bar.steps) b.steps.push_back({st.x_from, 1.0, 1.0, st.mu, 0.0, variation(st.varies)});
  return b;
}

bool any_spring(const PointAttachments& points) {
  for (const PointAttachment& p : points)
    if (p.springs.translational > 0 || p.springs.rotational > 0) return true;
  return false;
}

}  // namespace

LineShape bending_shape(const BeamBending& beam, EndSprings left, EndSprings right, double omega, int rigid_index,
                        int rigid_count, const std::vector<double>& xs, const PointAttachments& points) {
  LineShape out;
  const double L = beam.L;
  if (omega == 0.0) {
    if (any_spring(points))
      throw std::runtime_error("exact: rigid-body mode shapes of a beam with point supports are not modelled");
    // Rigid-body modes of the free beam: a translation and/or a rotation (w' = phi: no shear),
    // the free pair's rotation about the centre of mass (M-orthogonal to the translation).
    const bool rotation_restrained = left.rotational > 0 || right.rotational > 0;
    bool rotation = false;
    double total = over_pieces(beam, [](double a, double b, const BeamBending& p) { return p.rhoA * (b - a); },
                               [](double, const BeamBending& p) { return p.rhoA; });
    double moment = over_pieces(beam, [](double a, double b, const BeamBending& p) { return p.rhoA * (b * b - a * a) / 2; },
                                [](double x, const BeamBending& p) { return p.rhoA * x; });
    for (const PointAttachment& p : points) {
      total += p.mass;
      moment += p.mass * p.x;
    }
    double pivot = moment / total;
    if (rigid_count == 2) {
      rotation = rigid_index == 1;
    } else if (!rotation_restrained) {
      rotation = true;
      pivot = left.translational > 0 ? 0.0 : L;
    }
    for (double x : xs) {
      out.disp.push_back(rotation ? x - pivot : 1.0);
      out.rot.push_back(rotation ? 1.0 : 0.0);
      out.moment.push_back(0.0);
    }
    if (rotation) {
      out.modal_mass = over_pieces(beam, [pivot](double a, double b, const BeamBending& p) {
        const double c0 = a - pivot, c1 = b - pivot;  // int (x - pivot)^2 dx over the piece
        return p.rhoA * (c1 * c1 * c1 - c0 * c0 * c0) / 3.0 + p.rhoI * (b - a);
      }, [pivot](double x, const BeamBending& p) { return p.rhoA * (x - pivot) * (x - pivot) + p.rhoI; });
      out.participation = over_pieces(beam, [pivot](double a, double b, const BeamBending& p) {
        return p.rhoA * 0.5 * ((b - pivot) * (b - pivot) - (a - pivot) * (a - pivot));
      }, [pivot](double x, const BeamBending& p) { return p.rhoA * (x - pivot); });
    } else {
      out.modal_mass = out.participation = over_pieces(beam, [](double a, double b, const BeamBending& p) {
        return p.rhoA * (b - a);
      }, [](double, const BeamBending& p) { return p.rhoA; });
    }
    add_point_masses(points, [&](double x) { return std::pair{rotation ? x - pivot : 1.0, rotation ? 1.0 : 0.0}; }, out);
    return out;
  }
  detail::BendingLine line(beam, left, right, points);
  for (double x : xs) line.sys.nodes_at.push_back(x / L);
  const LineMode mode(line.sys, omega * omega);
  for (double x : xs) {
    // The state [w_bar, phi, Q, M] (line_models.hpp), forces scaled by EI / L^2 and EI / L.
    const Eigen::VectorXd y = mode.state(x / L);
    out.disp.push_back(y[0] * L);  // w_bar = w / L
    out.rot.push_back(y[1]);
    out.moment.push_back(y[3] * beam.EI / L);
  }
  out.modal_mass = L * mode.integrate([&](const Eigen::VectorXd& d, double xi) {
    const BeamBending p = beam.at(xi * L);
    return p.rhoA * d[0] * d[0] * L * L + p.rhoI * d[1] * d[1];
  });
  // |rhoA w L| <= sqrt(rhoA m(x)), m the modal mass's integrand: of the mode's size on average.
  double rhoA_max = beam.rhoA;
  for (const BendingStep& p : beam.steps) rhoA_max = std::max(rhoA_max, p.rhoA);
  for (int k = 0; k <= 64 && beam.tapered(); ++k) rhoA_max = std::max(rhoA_max, beam.at(L * k / 64.0).rhoA);
  out.participation = L * mode.integrate([&](const Eigen::VectorXd& d, double xi) { return beam.at(xi * L).rhoA * d[0] * L; },
                                         std::sqrt(rhoA_max * out.modal_mass / L));
  add_point_masses(points, [&](double x) {
    const Eigen::VectorXd d = mode.displacement(x / L);
    return std::pair{d[0] * L, d[1]};
  }, out);
  return out;
}

LineShape bar_shape(const Bar& bar, double k_left, double k_right, double omega, const std::vector<double>& xs,
                    const PointAttachments& points) {
  LineShape out;
  const double L = bar.L;
  if (omega == 0.0) {
    out.disp.assign(xs.size(), 1.0);
    out.rot.assign(xs.size(), 0.0);
    // The bar's mass, piece by piece (a tapered one's as over_pieces).
    const BeamBending as_beam = bar_as_beam(bar);
    out.modal_mass = out.participation = over_pieces(as_beam, [](double a, double b, const BeamBending& p) {
      return p.rhoA * (b - a);
    }, [](double, const BeamBending& p) { return p.rhoA; });
    add_point_masses(points, [](double) { return std::pair{1.0, 0.0}; }, out);
    return out;
  }
  detail::BarLine line(bar, k_left, k_right, points);
  for (double x : xs) line.sys.nodes_at.push_back(x / L);
  const LineMode mode(line.sys, omega * omega);
  for (double x : xs) {
    out.disp.push_back(mode.displacement(x / L)[0]);
    out.rot.push_back(0.0);
  }
  out.modal_mass = L * mode.integrate([&](const Eigen::VectorXd& d, double xi) { return bar.at(xi * L).mu * d[0] * d[0]; });
  out.participation = L * mode.integrate([&](const Eigen::VectorXd& d, double xi) { return bar.at(xi * L).mu * d[0]; });
  add_point_masses(points, [&](double x) { return std::pair{mode.displacement(x / L)[0], 0.0}; }, out);
  return out;
}

PlateShape navier_shape(double a, double b, double rho_h, int m, int n, const std::vector<std::array<double, 2>>& pts) {
  PlateShape out;
  for (const auto& p : pts) {
    const double sx = std::sin(m * pi * p[0] / a), cx = std::cos(m * pi * p[0] / a);
    const double sy = std::sin(n * pi * p[1] / b), cy = std::cos(n * pi * p[1] / b);
    out.w.push_back(sx * sy);
    out.theta_x.push_back(sx * cy * n * pi / b);   // +dw/dy
    out.theta_y.push_back(-cx * sy * m * pi / a);  // -dw/dx
  }
  out.modal_mass = rho_h * a * b / 4.0;
  out.participation = rho_h * (a / (m * pi)) * (1 - std::cos(m * pi)) * (b / (n * pi)) * (1 - std::cos(n * pi));
  return out;
}

PlateShape levy_shape(double a, double b, double D, double nu, double rho_h, EndSprings y0, EndSprings yb,
                      double omega, const std::vector<std::array<double, 2>>& pts, bool transposed) {
  // The strip whose count jumps at omega^2 carries the mode.
  const double lambda = omega * omega;
  int strip = 0;
  for (int m = 1; m <= levy_strip_count(a, D, nu, rho_h, lambda * (1 + 1e-8)) && strip == 0; ++m) {
    const LineSystem sys = levy_strip(a, b, D, nu, rho_h, y0, yb, m);
    if (count_below(sys, lambda * (1 + 1e-8)) > count_below(sys, lambda * (1 - 1e-8))) strip = m;
  }
  if (strip == 0) throw std::runtime_error("Levy plate: no strip has a mode at this frequency");
  LineSystem sys = levy_strip(a, b, D, nu, rho_h, y0, yb, strip);
  // In the strip's own axes: along = the simply supported direction (length a), across = y.
  auto along = [&](const std::array<double, 2>& p) { return transposed ? p[1] : p[0]; };
  auto across = [&](const std::array<double, 2>& p) { return transposed ? p[0] : p[1]; };
  for (const auto& p : pts) sys.nodes_at.push_back(across(p) / b);
  const LineMode mode(sys, lambda);
  const double k = strip * pi / a;
  PlateShape out;
  for (const auto& p : pts) {
    const Eigen::VectorXd d = mode.displacement(across(p) / b);  // [W / b, dW/dy]
    const double W = d[0] * b, dW = d[1], s = std::sin(k * along(p)), c = std::cos(k * along(p));
    const double d_along = W * k * c, d_across = dW * s;  // derivatives of w = W(across) sin(k along)
    const double dwdx = transposed ? d_across : d_along, dwdy = transposed ? d_along : d_across;
    out.w.push_back(W * s);
    out.theta_x.push_back(dwdy);
    out.theta_y.push_back(-dwdx);
  }
  // rho h int sin^2 (a / 2) int W^2 dy, W = b W_bar, dy = b dy_bar.
  out.modal_mass = rho_h * (a / 2.0) * b * b * b * mode.integrate([](const Eigen::VectorXd& d, double) { return d[0] * d[0]; });
  out.participation = rho_h * (1 - std::cos(strip * pi)) / k * b * b *
                      mode.integrate([](const Eigen::VectorXd& d, double) { return d[0]; });
  return out;
}

}  // namespace modalbench::exact
