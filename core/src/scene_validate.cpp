#include <fmt/format.h>

#include "modalbench/scene.hpp"
#include "scene_reader.hpp"

namespace modalbench {

using scene_detail::check_range;
using scene_detail::Reader;

namespace {

/// A stepped beam's pieces: contiguous from 0 to the length, each with a valid section and material.
void validate_segments(const Reader& r, const Scene& s) {
  if (s.segments.empty()) return;
  if (s.is_plate()) r.fail("segments", "a plate has no segments (a stepped beam's pieces)");
  double x = 0;
  for (std::size_t i = 0; i < s.segments.size(); ++i) {
    const Segment& seg = s.segments[i];
    const std::string key = fmt::format("segments[{}]", i);
    if (!(seg.x_from == x && seg.x_to > seg.x_from && std::isfinite(seg.x_to)))
      r.fail(key + ".length", "pieces must follow each other from x = 0 with positive lengths");
    x = seg.x_to;
    // A tapered piece at both ends (its dimensions are monotone between them).
    for (double at : {seg.x_from, seg.x_to}) {
      const Section p = seg.properties_at(at);
      for (double v : {p.A, p.Iy, p.Iz, p.J, seg.width, seg.height})
        if (!(std::isfinite(v) && v > 0)) r.fail(key + ".section", "its properties must be finite and > 0");
    }
    const Material& m = seg.material;
    for (double v : {m.E, m.G, m.rho, m.kappa})
      if (!(std::isfinite(v) && v > 0)) r.fail(key + ".material", "E, G, rho and kappa must be finite and > 0");
    if (!(m.nu > -1.0 && m.nu < 0.5)) r.fail(key + ".material.nu", "must lie in (-1, 0.5)");
  }
  if (x != s.geometry.length)
    r.fail("segments", fmt::format("the pieces end at {} m, not at geometry.length = {} m", x, s.geometry.length));
}

/// A plate R times longer than wide has its first modes sin(pi x / a) sin(n pi y / b), n = 1, 2,
/// ..., a relative 3 / R^2 apart: beyond R = 1e7 that is below the rounding of any eigen solver
/// (a few 1e-14 at best), so no back-end can separate them, and each would spend its whole time
/// limit trying (a plate 3e67 m wide ran past 60 s in rfem and dtfm).
void validate_plate_aspect(const Reader& r, const Geometry& g) {
  constexpr double kMaxAspect = 1e7;
  if (!(g.length > 0 && g.width > 0)) return;  // reported as such above
  const bool long_x = g.length > g.width;
  const double aspect = long_x ? g.length / g.width : g.width / g.length;
  if (aspect > kMaxAspect)
    r.fail(long_x ? "geometry.length" : "geometry.width",
           fmt::format("the plate is {:.3g} times longer than wide (length {:g} m, width {:g} m): its first modes "
                       "along the long side lie 3 / {:.3g}^2 = {:.2g} apart in frequency, below what double precision "
                       "resolves, so no back-end can solve it (limit {:g}); a plate this slender is a strip: write it "
                       "as a beam (in cylindrical bending across the short side, with E / (1 - nu^2))",
                       aspect, g.length, g.width, aspect, 3.0 / (aspect * aspect), kMaxAspect));
}

/// [request.transient]: the grid, the time function, the damping, and what it needs of the scene.
void validate_transient(const Reader& r, const Scene& s) {
  if (!s.request.transient) return;
  const TransientRequest& t = *s.request.transient;
  const std::string w = "request.transient";
  auto positive = [&](const std::string& key, double v) {
    if (!(std::isfinite(v) && v > 0)) r.fail(w + "." + key, fmt::format("must be finite and > 0 (got {})", v));
  };
  positive("duration", t.duration);
  positive("step", t.step);
  if (t.step > t.duration) r.fail(w + ".step", fmt::format("must not exceed the duration ({} s)", t.duration));
  if (t.duration / t.step > 1e6)
    r.fail(w + ".step", fmt::format("gives {:.3g} output times; at most 1e6 are written", t.duration / t.step));
  if (t.load == TransientRequest::Load::Ramp) positive("rise", t.rise);
  if (t.load == TransientRequest::Load::Harmonic) positive("omega", t.omega);
  if (t.load == TransientRequest::Load::Table) {
    if (t.time.size() != t.factor.size())
      r.fail(w + ".load", fmt::format("time and factor must have the same length ({} and {})", t.time.size(), t.factor.size()));
    for (std::size_t i = 0; i < t.time.size(); ++i) {
      if (!std::isfinite(t.time[i]) || !std::isfinite(t.factor[i])) r.fail(w + ".load", "values must be finite");
      if (i == 0 && t.time[0] != 0) r.fail(w + ".load.time", "must start at 0 (the response starts at rest at t = 0)");
      if (i > 0 && !(t.time[i] > t.time[i - 1])) r.fail(w + ".load.time", "must be strictly ascending");
    }
  }
  if (t.damping == TransientRequest::Damping::Modal && !(t.zeta >= 0 && t.zeta <= 100))
    r.fail(w + ".damping.modal", fmt::format("the damping ratio must lie in [0, 100] (got {})", t.zeta));
  if (t.damping == TransientRequest::Damping::Rayleigh && !(t.alpha >= 0 && t.beta >= 0 && std::isfinite(t.alpha + t.beta)))
    r.fail(w + ".damping.rayleigh", "alpha (1/s) and beta (s) must be finite and >= 0");
  if (t.damping == TransientRequest::Damping::None && s.material.loss_factor > 0)
    r.fail(w + ".damping",
           "missing: material.loss_factor (the FRFs' structural damping) has no causal form in time; give { modal = "
           "zeta } (zeta = eta / 2 matches it at resonance) or { rayleigh = [alpha, beta] }");
  if (s.request.probes.empty()) r.fail(w, "needs request.probes: the histories are given at the probes");
  if (s.all_point_loads().empty() && s.all_distributed_loads().empty())
    r.fail(w, "the scene has no loads: the transient applies the static loads ([[loads]], line loads, pressures, gravity) "
              "times its time function");
}

}  // namespace

void validate(const Scene& s) {
  Reader r(s.source);
  if (s.is_frame()) {
    scene_detail::validate_frame(r, s);
    return;
  }
  auto finite_pos = [&](const std::string& key, double v) {
    if (!(std::isfinite(v) && v > 0)) r.fail(key, fmt::format("must be finite and > 0 (got {})", v));
  };
  finite_pos("geometry.length", s.geometry.length);
  finite_pos("geometry.width", s.geometry.width);
  finite_pos("geometry.height", s.geometry.height);
  const SectionSpec& sec = s.cross_section;
  if (s.is_plate() && sec.shape != SectionShape::Rectangle)
    r.fail("geometry.section", "a plate has no cross-section: give its width and thickness (height)");
  if (sec.shape == SectionShape::Circle || sec.shape == SectionShape::Tube)
    finite_pos("geometry.section.diameter", sec.diameter);
  if (sec.shape == SectionShape::Tube && !(sec.inner_diameter > 0 && sec.inner_diameter < sec.diameter))
    r.fail("geometry.section.inner_diameter", fmt::format("must lie in (0, outer_diameter = {} m) (got {} m)",
                                                          sec.diameter, sec.inner_diameter));
  if (sec.shape == SectionShape::General) {
    finite_pos("geometry.section.area", sec.A);
    finite_pos("geometry.section.Iy", sec.Iy);
    finite_pos("geometry.section.Iz", sec.Iz);
    finite_pos("geometry.section.J", sec.J);
  }
  finite_pos("material.E", s.material.E);
  finite_pos("material.G", s.material.G);
  finite_pos("material.rho", s.material.rho);
  finite_pos("material.kappa", s.material.kappa);
  if (!(s.material.nu > -1.0 && s.material.nu < 0.5)) r.fail("material.nu", "must lie in (-1, 0.5)");
  if (!(std::isfinite(s.material.loss_factor) && s.material.loss_factor >= 0))
    r.fail("material.loss_factor", "must be finite and >= 0");
  auto check_support = [&](const std::string& key, const Support& sp) {
    for (double v : {sp.translational, sp.rotational, sp.axial, sp.torsional})
      if (std::isnan(v) || v < 0) r.fail("supports." + key, "spring stiffness must be >= 0 (NaN given or negative)");
  };
  check_support("x0", s.x0);
  check_support("xL", s.xL);
  if (s.is_plate()) {
    check_support("y0", s.y0);
    check_support("yB", s.yB);
    if (s.physics != Physics::Bending) r.fail("scene.physics", "a plate has physics 'bending'");
    if (s.theory != Theory::Kirchhoff && s.theory != Theory::Mindlin)
      r.fail("scene.theory", "a plate's theory is kirchhoff or mindlin");
    validate_plate_aspect(r, s.geometry);
  } else if (s.theory != Theory::EulerBernoulli && s.theory != Theory::Timoshenko) {
    r.fail("scene.theory", "a beam's theory is euler-bernoulli or timoshenko");
  }
  validate_segments(r, s);
  for (std::size_t i = 0; i < s.point_supports.size(); ++i) {
    const std::string key = fmt::format("supports.points[{}]", i);
    const double x = s.point_supports[i].x, y = s.point_supports[i].y;
    if (!(x > 0 && x < s.geometry.length)) r.fail(key + ".x", fmt::format("must lie in (0, {}) m", s.geometry.length));
    if (s.is_plate() && !(y > 0 && y < s.geometry.width))
      r.fail(key + ".y", fmt::format("must lie in (0, {}) m", s.geometry.width));
    if (s.is_beam() && y != 0) r.fail(key + ".y", "a beam's supports lie on its axis (y = 0)");
    if (s.is_beam() && i > 0 && !(x > s.point_supports[i - 1].x))
      r.fail(key + ".x", "point supports must be distinct and in ascending x");
    check_support(fmt::format("points[{}]", i), s.point_supports[i].support);
  }
  for (std::size_t i = 0; i < s.masses.size(); ++i) {
    const std::string key = fmt::format("masses[{}]", i);
    const PointMass& pm = s.masses[i];
    check_range(r, key + ".x", pm.x, 0.0, s.geometry.length);
    if (s.is_plate()) check_range(r, key + ".y", pm.y, 0.0, s.geometry.width);
    if (s.is_beam() && pm.y != 0) r.fail(key + ".y", "a beam's masses lie on its axis (y = 0)");
    for (double v : {pm.mass, pm.Jx, pm.Jy, pm.Jz})
      if (!(std::isfinite(v) && v >= 0)) r.fail(key, "mass and rotary inertias must be finite and >= 0");
    if (s.is_beam() && i > 0 && pm.x < s.masses[i - 1].x) r.fail(key + ".x", "masses must be in ascending x");
  }
  const std::vector<DistributedLoad>& dist = s.is_beam() ? s.line_loads : s.pressures;
  const std::string dist_key = s.is_beam() ? "line_loads" : "pressures";
  if (!(s.is_beam() ? s.pressures : s.line_loads).empty())
    r.fail(s.is_beam() ? "pressures" : "line_loads", "beams take line loads, plates pressures");
  for (std::size_t i = 0; i < dist.size(); ++i) {
    const DistributedLoad& q = dist[i];
    const std::string key = fmt::format("{}[{}]", dist_key, i);
    for (double v : {q.qx[0], q.qx[1], q.qy[0], q.qy[1], q.qz[0], q.qz[1], q.from[0], q.from[1], q.to[0], q.to[1]})
      if (!std::isfinite(v)) r.fail(key, "values must be finite");
    if (!(q.from[0] >= 0 && q.from[0] < q.to[0] && q.to[0] <= s.geometry.length))
      r.fail(key, fmt::format("its x range must lie in [0, {}] m with from < to", s.geometry.length));
    if (s.is_plate() && !(q.from[1] >= 0 && q.from[1] < q.to[1] && q.to[1] <= s.geometry.width))
      r.fail(key, fmt::format("its y range must lie in [0, {}] m with from < to", s.geometry.width));
  }
  if (s.gravity)
    for (double g : *s.gravity)
      if (!std::isfinite(g)) r.fail("gravity.g", "values must be finite");
  for (std::size_t i = 0; i < s.loads.size(); ++i) {
    const auto& p = s.loads[i];
    for (double v : {p.x, p.y, p.Fx, p.Fy, p.Fz, p.Mx, p.My, p.Mz})
      if (!std::isfinite(v)) r.fail(fmt::format("loads[{}]", i), "values must be finite");
    check_range(r, fmt::format("loads[{}].x", i), p.x, 0.0, s.geometry.length);
    if (s.is_plate()) check_range(r, fmt::format("loads[{}].y", i), p.y, 0.0, s.geometry.width);
    if (s.is_plate() && (p.Fx != 0 || p.Fy != 0 || p.Mz != 0))
      r.fail(fmt::format("loads[{}]", i), "a plate in bending takes Fz, Mx and My (no in-plane Fx, Fy, Mz)");
    if (s.is_beam() && s.physics == Physics::Lateral && (p.Fx != 0 || p.Mx != 0))
      r.fail(fmt::format("loads[{}]", i), "a lateral (rotor) model carries no axial force or torque (no Fx, Mx)");
  }
  if (s.request.modes < 0) r.fail("request.modes", "must be >= 0");
  validate_transient(r, s);
  scene_detail::validate_rotor(r, s);
}

}  // namespace modalbench
