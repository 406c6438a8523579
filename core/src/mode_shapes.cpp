// Normalization, sign and modal quantities of sampled mode shapes (result.hpp).

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "modalbench/result.hpp"

namespace modalbench {

std::string component_name(int dof) {
  static const char* names[] = {"u", "v", "w", "theta_x", "theta_y", "theta_z"};
  if (dof < 0 || dof > 5) throw std::invalid_argument("component_name: no DOF " + std::to_string(dof));
  return names[dof];
}

void finish_mode_shapes(ModeShapes& s) {
  const std::size_t n = s.values.size();
  if (s.generalized_mass.size() != n || s.participation.size() != n)
    throw std::logic_error("finish_mode_shapes: one generalized mass and participation per mode needed");
  if (!s.moments.empty() && s.moments.size() != n)
    throw std::logic_error("finish_mode_shapes: moments for every mode or none");
  s.effective_mass.assign(n, {0, 0, 0});
  for (std::size_t k = 0; k < n; ++k) {
    auto& mode = s.values[k];
    const double gm = s.generalized_mass[k];
    if (!(gm > 0) || !std::isfinite(gm))
      throw std::runtime_error("mode " + std::to_string(k + 1) + ": generalized mass " + std::to_string(gm) +
                               " is not positive: the shape cannot be mass-normalized");
    double scale = 1.0 / std::sqrt(gm);
    // The sign: the translation sample of largest magnitude positive (rotations if no
    // translation). Ties (an antisymmetric mode's two extremes) go to the first sample within
    // 1e-6 of the largest magnitude, so the sign does not depend on rounding.
    double big = 0;
    for (bool translations : {true, false}) {
      double largest = 0;
      for (std::size_t c = 0; c < mode.size(); ++c)
        if ((s.components[c] < 3) == translations)
          for (double v : mode[c]) largest = std::max(largest, std::abs(v));
      for (std::size_t c = 0; c < mode.size() && big == 0; ++c)
        if ((s.components[c] < 3) == translations)
          for (double v : mode[c])
            if (std::abs(v) >= (1.0 - 1e-6) * largest && largest > 0) {
              big = v;
              break;
            }
      if (big != 0) break;
    }
    if (big < 0) scale = -scale;
    for (auto& comp : mode)
      for (double& v : comp) v *= scale;
    if (k < s.moments.size())
      for (double& v : s.moments[k]) v *= scale;
    s.generalized_mass[k] = 1.0;
    for (int d = 0; d < 3; ++d) {
      s.participation[k][d] *= scale;
      s.effective_mass[k][d] = s.participation[k][d] * s.participation[k][d];
    }
  }
}

}  // namespace modalbench
