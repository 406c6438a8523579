// Rotor scenes' predicates and the comparison of Campbell diagrams (rotor_scene.hpp).
#include "modalbench/rotor_scene.hpp"

#include <algorithm>
#include <cmath>

namespace modalbench {

bool axisymmetric_shaft(const Scene& s) {
  for (const Segment& p : s.beam_pieces())
    for (double x : {p.x_from, 0.5 * (p.x_from + p.x_to), p.x_to}) {  // a tapered piece at its ends and middle
      const Section sec = p.properties_at(x);
      if (std::abs(sec.Iy - sec.Iz) > 1e-12 * std::max(sec.Iy, sec.Iz)) return false;
    }
  return true;
}

bool classical_ends(const Scene& s) {
  for (const Support* e : {&s.x0, &s.xL})
    for (double k : {e->translational, e->rotational})
      if (!(k == 0.0 || std::isinf(k))) return false;
  return true;
}

bool rotor_held(const Scene& s) {
  int held = (s.x0.translational > 0) + (s.xL.translational > 0), turned = (s.x0.rotational > 0) + (s.xL.rotational > 0);
  for (const PointSupport& p : s.point_supports) {
    held += p.support.translational > 0;
    turned += p.support.rotational > 0;
  }
  return held >= 2 || (held >= 1 && turned >= 1);
}

double campbell_difference(const Campbell& a, const Campbell& b) {
  if (a.points.size() != b.points.size() || a.points.empty()) return kNotMeasured;
  double worst = 0;
  for (std::size_t p = 0; p < a.points.size(); ++p) {
    const auto &f = a.points[p].frequencies_rad_s, &g = b.points[p].frequencies_rad_s;
    if (f.size() != g.size() || a.points[p].spin_rad_s != b.points[p].spin_rad_s) return kNotMeasured;
    for (std::size_t i = 0; i < f.size(); ++i)
      worst = std::max(worst, std::abs(f[i] - g[i]) / (std::abs(g[i]) + a.points[p].spin_rad_s));
  }
  return worst;
}

}  // namespace modalbench
