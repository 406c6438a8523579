#include <fmt/format.h>

#include "modalbench/scene.hpp"
#include "scene_reader.hpp"

namespace modalbench {

using scene_detail::check_range;
using scene_detail::Reader;

void validate(const Scene& s) {
  Reader r(s.source);
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
  } else if (s.theory != Theory::EulerBernoulli && s.theory != Theory::Timoshenko) {
    r.fail("scene.theory", "a beam's theory is euler-bernoulli or timoshenko");
  }
  for (std::size_t i = 0; i < s.loads.size(); ++i) {
    const auto& p = s.loads[i];
    for (double v : {p.x, p.y, p.Fx, p.Fy, p.Fz, p.Mx, p.My, p.Mz})
      if (!std::isfinite(v)) r.fail(fmt::format("loads[{}]", i), "values must be finite");
    check_range(r, fmt::format("loads[{}].x", i), p.x, 0.0, s.geometry.length);
    if (s.is_plate()) check_range(r, fmt::format("loads[{}].y", i), p.y, 0.0, s.geometry.width);
  }
  if (s.request.modes < 0) r.fail("request.modes", "must be >= 0");
}

}  // namespace modalbench
