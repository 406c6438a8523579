// Warnings for numbers that are right for the model but outside what the model means: material
// values far from any engineering material in SI (E = 210 typed for GPa), deflections beyond the
// small-deflection range of linear bending, and modes whose half-wave is shorter than the section
// depth (or plate thickness) under a theory that neglects shear. They never change the status.
#include "solve_internal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace modalbench::detail {

namespace {

/// E and rho far outside engineering materials in SI: the likely unit slip is named.
void material_warnings(const Scene& s, std::vector<std::string>& out) {
  const double E = s.material.E, rho = s.material.rho;
  if (E < 1e6)
    out.push_back(fmt::format("plausibility: material.E = {:g} Pa is below any engineering material (1 MPa and up; "
                              "steel 2.1e11 Pa): modalbench works in SI, was it typed in GPa or MPa?",
                              E));
  else if (E > 1.5e12)
    out.push_back(fmt::format("plausibility: material.E = {:g} Pa is above any engineering material (diamond 1.2e12 "
                              "Pa): modalbench works in SI",
                              E));
  if (rho < 50.0 || rho > 3e4)
    out.push_back(fmt::format("plausibility: material.rho = {:g} kg/m^3 is outside structural materials (foams and "
                              "balsa from about 50, osmium 2.3e4 kg/m^3; steel 7850): was it typed in g/cm^3 or t/m^3?",
                              rho));
}

/// Linear bending holds for small deflections: a plate's |w| well below its thickness, a beam's
/// slopes small.
void deflection_warnings(const Scene& s, const Result& r, std::vector<std::string>& out) {
  double w = 0, slope = 0;
  for (const Deflection& d : r.deflections) {
    w = std::max({w, std::abs(d.w), std::abs(d.v)});
    slope = std::max({slope, std::abs(d.theta_y), std::abs(d.theta_z), s.is_plate() ? std::abs(d.theta_x) : 0.0});
  }
  if (s.is_plate() && w > 0.2 * s.geometry.height)
    out.push_back(fmt::format("plausibility: a deflection of {:.3g} m is {:.3g} times the plate's thickness: beyond "
                              "the small-deflection range of plate bending (|w| < 0.2 h), where membrane action "
                              "stiffens a real plate; the linear result is reported",
                              w, w / s.geometry.height));
  if (slope > 0.1)
    out.push_back(fmt::format("plausibility: a rotation of {:.3g} rad at the probes is beyond the small rotations of "
                              "linear bending (0.1 rad); the linear result is reported",
                              slope));
}

/// Under Euler-Bernoulli or Kirchhoff theory, a mode whose half-wave is shorter than the depth (the
/// thickness) lies where the theory no longer holds: shear and rotary inertia decide it there.
void half_wave_warnings(const Scene& s, const Result& r, std::vector<std::string>& out) {
  if (r.frequencies_rad_s.empty() || !(s.theory == Theory::EulerBernoulli || s.theory == Theory::Kirchhoff)) return;
  if (s.is_frame()) return;  // members of several sections: not judged here yet
  const double omega = r.frequencies_rad_s.back();
  if (!(omega > 0)) return;
  double k4 = 0, depth = s.geometry.height;
  if (s.is_beam()) {
    const Section sec = s.section();
    k4 = omega * omega * s.material.rho * sec.A / (s.material.E * std::min(sec.Iy, sec.Iz));
  } else {
    k4 = omega * omega * s.material.rho * s.geometry.height / s.plate_D();
  }
  const double half_wave = std::numbers::pi / std::pow(k4, 0.25);
  if (half_wave < depth)
    out.push_back(fmt::format("plausibility: mode {} has a bending half-wave of about {:.3g} m, shorter than the {} of "
                              "{:.3g} m: {} theory does not hold there (shear and rotary inertia decide such modes; "
                              "a Timoshenko/Mindlin or 3D model does)",
                              r.frequencies_rad_s.size(), half_wave, s.is_beam() ? "section depth" : "thickness", depth,
                              to_string(s.theory)));
}

}  // namespace

std::vector<std::string> plausibility_warnings(const Scene& scene, const Result& result) {
  std::vector<std::string> out;
  material_warnings(scene, out);
  deflection_warnings(scene, result, out);
  half_wave_warnings(scene, result, out);
  return out;
}

}  // namespace modalbench::detail
