// Supports that share a rigid element of a beam mesh (shared_supports.hpp).
#include "shared_supports.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace modalbench::rfem::detail {

std::string supports_sharing_an_element(const Scene& s, int n) {
  if (!s.is_beam() || s.theory != Theory::Timoshenko || n < 1) return "";
  struct Held {
    std::string name;
    double x;
    int element;
  };
  const double L = s.geometry.length, d = L / n;
  std::vector<Held> held;
  if (s.x0.translational > 0) held.push_back({"x0", 0.0, 0});
  for (std::size_t i = 0; i < s.point_supports.size(); ++i) {
    const PointSupport& p = s.point_supports[i];
    // The element the builder attaches it to (beam_builder.cpp: the nearest centre).
    if (p.support.translational > 0)
      held.push_back({fmt::format("points[{}]", i), p.x, std::clamp(static_cast<int>(std::lround(p.x / d)), 0, n)});
  }
  if (s.xL.translational > 0) held.push_back({"xL", L, n});
  for (std::size_t i = 0; i + 1 < held.size(); ++i)
    for (std::size_t j = i + 1; j < held.size(); ++j)
      if (held[i].element == held[j].element)
        return fmt::format(
            "supports {} and {} ({:.3g} m apart) act on one rigid element of mesh {}: it holds the section's rotation "
            "between them (a clamp), where a Timoshenko beam turns at a shear stiffness kappa G A times their "
            "distance; every mesh of the family does the same, so the error estimate cannot see it: the frequencies "
            "are those of a clamp there, not of the scene's beam",
            held[i].name, held[j].name, std::abs(held[j].x - held[i].x), n);
  return "";
}

}  // namespace modalbench::rfem::detail
