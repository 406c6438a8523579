// The exact back-end's plate responses (plate_responses.hpp).
#include "plate_responses.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "modalbench/exact/plates.hpp"

namespace modalbench::exact::detail {

namespace {

/// The edge reactions, each placed at the edge's middle: its Kirchhoff effective shear plus half of
/// the corner force at each of its ends. A corner force 2 M_xy is the twisting moment M_xy of each
/// edge meeting there, so this is the resultant of each edge as a hard support that holds the
/// twisting moments (the transverse shear Q and M_xy along it), as rfem's edges do; the split of
/// the corner forces alone would be a convention. Given where the series meets the tolerance.
void navier_plate_reactions(const Scene& s, const std::vector<std::array<double, 3>>& forces,
                            const std::vector<PressurePatch>& patches, Result& r) {
  const double a = s.geometry.length, b = s.geometry.width;
  // Exact to 1e-8 of the load at least (the series costs microseconds per term).
  const double tol = std::min(s.request.tolerance, 1e-8);
  const NavierReactions nr = navier_reactions(a, b, s.plate_D(), s.material.nu, forces, patches, tol);
  r.summary.set_diagnostic("reaction_series_terms", nr.terms);
  if (nr.tail_relative > s.request.tolerance) {
    r.summary.warnings.push_back(fmt::format(
        "plate reactions not given: their series at {} terms is uncertain by {:.1e} of the total load, above the "
        "tolerance {:.1e}",
        nr.terms, nr.tail_relative, s.request.tolerance));
    return;
  }
  std::array<Reaction, 4> e = {Reaction{"x0", {0, b / 2}, {0, 0, nr.edge_force[0]}, {nr.edge_first_moment[0], 0, 0}},
                               Reaction{"xL", {a, b / 2}, {0, 0, nr.edge_force[1]}, {nr.edge_first_moment[1], 0, 0}},
                               Reaction{"y0", {a / 2, 0}, {0, 0, nr.edge_force[2]}, {0, -nr.edge_first_moment[2], 0}},
                               Reaction{"yB", {a / 2, b}, {0, 0, nr.edge_force[3]}, {0, -nr.edge_first_moment[3], 0}}};
  const std::array<std::array<double, 2>, 4> corner = {{{0, 0}, {a, 0}, {0, b}, {a, b}}};
  for (int c = 0; c < 4; ++c) {
    const double F = nr.corner[c] / 2;
    for (int k : {corner[c][0] == 0 ? 0 : 1, corner[c][1] == 0 ? 2 : 3}) {
      Reaction& x = e[static_cast<std::size_t>(k)];
      x.force[2] += F;
      x.moment[0] += (corner[c][1] - x.position[1]) * F;
      x.moment[1] -= (corner[c][0] - x.position[0]) * F;
    }
  }
  r.reactions.assign(e.begin(), e.end());
}

}  // namespace

// The tail estimates are checked (FRF: against the static flexibility of the same pair, since |H|
// vanishes at anti-resonances).
namespace {

/// The statics at every probe on one truncation M x N, with the largest deflection tail and the
/// largest |w|.
struct StaticPass {
  std::vector<Deflection> probes;
  std::vector<double> curvature_tail;
  double worst_tail = 0, scale = 0;
};
StaticPass static_pass(const Scene& s, const std::vector<std::array<double, 3>>& forces,
                       const std::vector<PressurePatch>& patches, int M, int N) {
  const double a = s.geometry.length, b = s.geometry.width, D = s.plate_D(), nu = s.material.nu;
  StaticPass out;
  for (const auto& p : s.request.probes) {
    double tail = 0, curvature_tail = 0;
    std::array<double, 3> c{};
    const auto w = navier_static(a, b, D, forces, p[0], p[1], M, N, &tail, patches, &c, &curvature_tail);
    Deflection d;
    d.position = p;
    d.w = w[0];
    d.theta_x = w[2];   // rotation about x: +dw/dy
    d.theta_y = -w[1];  // rotation about y: -dw/dx
    d.forces.mx = D * (c[0] + nu * c[1]);
    d.forces.my = D * (c[1] + nu * c[0]);
    d.forces.mxy = D * (1 - nu) * c[2];
    out.probes.push_back(d);
    out.curvature_tail.push_back(curvature_tail);
    out.worst_tail = std::max(out.worst_tail, tail);
    out.scale = std::max(out.scale, std::abs(w[0]));
  }
  return out;
}

}  // namespace

// The truncation is balanced to the aspect (navier_balanced_terms) and grown (M and N by sqrt 2)
// while the deflections' tail exceeds the tolerance: at most 4 times, 16 times the terms.
void navier_statics(const Scene& s, int terms, Result& r) {
  const double a = s.geometry.length, b = s.geometry.width, D = s.plate_D(), nu = s.material.nu;
  std::vector<std::array<double, 3>> forces;
  for (const auto& p : s.all_point_loads()) forces.push_back({p.x, p.y, p.Fz});
  std::vector<PressurePatch> patches;
  for (const DistributedLoad& q : s.all_distributed_loads())
    patches.push_back({q.from[0], q.to[0], q.from[1], q.to[1], q.qz[0]});
  const auto [M0, N0] = navier_balanced_terms(a, b, terms);
  int M = M0, N = N0;
  StaticPass pass;
  for (int round = 0;; ++round) {
    const double grow = std::pow(std::sqrt(2.0), round);
    M = static_cast<int>(std::lround(M0 * grow));
    N = static_cast<int>(std::lround(N0 * grow));
    pass = static_pass(s, forces, patches, M, N);
    if (!(pass.scale > 0 && pass.worst_tail > s.request.tolerance * pass.scale) || round == 4) break;
  }
  for (std::size_t i = 0; i < pass.probes.size(); ++i) {
    Deflection d = pass.probes[i];
    // The moments (result.hpp) where their series has converged to the tolerance.
    const double m_scale = std::max({std::abs(d.forces.mx), std::abs(d.forces.my), std::abs(d.forces.mxy)});
    const double m_tail = D * (1 + std::abs(nu)) * pass.curvature_tail[i];
    d.has_forces = m_tail <= s.request.tolerance * m_scale;
    if (!d.has_forces) {
      d.forces = {};
      r.summary.warnings.push_back(fmt::format(
          "plate moments at ({:g}, {:g}) m not given: their Navier series at {} x {} terms is uncertain by {:.1e} N*m/m "
          "(under a point force Kirchhoff's moments are infinite)",
          d.position[0], d.position[1], M, N, m_tail));
    }
    r.deflections.push_back(d);
  }
  const double worst_tail = pass.worst_tail, scale = pass.scale;
  r.summary.set_diagnostic("static_series_terms_m", M);
  r.summary.set_diagnostic("static_series_terms_n", N);
  if (scale > 0 && worst_tail > s.request.tolerance * scale)
    r.summary.raise(Status::NotConverged,
                    fmt::format("deflections: the Navier static series truncated at {} x {} terms has an estimated "
                                "relative error {:.1e}, above the tolerance {:.1e} ([request] tolerance): raise "
                                "navier_static_terms",
                                M, N, worst_tail / scale, s.request.tolerance));
  else if (scale > 0 && worst_tail > 1e-5 * scale)
    r.summary.warnings.push_back(fmt::format("Navier static series truncated at {} x {} terms: estimated relative "
                                             "error {:.1e}",
                                             M, N, worst_tail / scale));
  r.summary.set_diagnostic("static_series_tail_relative", scale > 0 ? worst_tail / scale : 0.0);
  navier_plate_reactions(s, forces, patches, r);
}

namespace {

/// The FRF samples on one truncation M x N, with the largest tail over them and the samples left
/// out (exactly on an undamped resonance).
struct FrfPass {
  std::vector<FrfSample> samples;
  double worst = 0;
  int omitted = 0;
};
FrfPass frf_pass(const Scene& s, int M, int N) {
  const double a = s.geometry.length, b = s.geometry.width, D = s.plate_D();
  const double rho_h = s.material.rho * s.geometry.height;
  const auto& f = *s.request.frf;
  FrfPass out;
  for (int i = 0; i < f.points; ++i) {
    const double w = f.omega_min + (f.omega_max - f.omega_min) * i / (f.points - 1);
    double tail = 0;
    const auto rec = navier_receptance(a, b, D, rho_h, s.material.loss_factor, f.excite[0], f.excite[1],
                                       f.observe[0], f.observe[1], w, M, N, &tail);
    if (!std::isfinite(std::abs(rec))) {  // exactly on an undamped resonance
      ++out.omitted;
      continue;
    }
    out.samples.push_back({w, rec});
    out.worst = std::max(out.worst, tail);
  }
  return out;
}

}  // namespace

// The truncation is balanced to the aspect (navier_balanced_terms: about terms^2 terms at one
// wavenumber in both directions) and doubled (M and N by sqrt 2) while the tail exceeds the
// tolerance, at most 6 times (64 times the terms): the tail falls like 1 / terms.
void navier_frf(const Scene& s, int terms, Result& r) {
  const double a = s.geometry.length, b = s.geometry.width, D = s.plate_D();
  const double rho_h = s.material.rho * s.geometry.height;
  const auto& f = *s.request.frf;
  const auto [M0, N0] = navier_balanced_terms(a, b, terms);
  const double flex = std::abs(navier_receptance(a, b, D, rho_h, 0.0, f.excite[0], f.excite[1], f.observe[0],
                                                 f.observe[1], 0.0, M0, N0, nullptr));
  int M = M0, N = N0;
  FrfPass pass;
  for (int round = 0;; ++round) {
    const double grow = std::pow(std::sqrt(2.0), round);
    M = static_cast<int>(std::lround(M0 * grow));
    N = static_cast<int>(std::lround(N0 * grow));
    pass = frf_pass(s, M, N);
    if (!(flex > 0 && pass.worst > s.request.tolerance * flex) || round == 6) break;
  }
  r.frf = std::move(pass.samples);
  const double worst = pass.worst;
  r.summary.set_diagnostic("frf_series_terms_m", M);
  r.summary.set_diagnostic("frf_series_terms_n", N);
  r.summary.set_diagnostic("frf_series_tail_relative_to_flexibility", flex > 0 ? worst / flex : 0.0);
  note_frf_omissions(r.summary, pass.omitted, f.points, "the Navier series is infinite there: an undamped resonance");
  if (flex > 0 && worst > s.request.tolerance * flex)
    r.summary.raise(Status::NotConverged,
                    fmt::format("FRF: the Navier series truncated at {} x {} terms has an estimated error up to {:.1e} "
                                "of the static flexibility, above the tolerance {:.1e}: raise navier_frf_terms",
                                M, N, worst / flex, s.request.tolerance));
  else if (flex > 0 && worst > 1e-3 * flex)
    r.summary.warnings.push_back(fmt::format(
        "Navier FRF series truncated at {} x {} terms: estimated error up to {:.1e} of the static flexibility", M, N,
        worst / flex));
}

}  // namespace modalbench::exact::detail
