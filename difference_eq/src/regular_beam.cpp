#include "modalbench/difference_eq/regular_beam.hpp"

#include <cmath>
#include <string>

namespace modalbench::difference_eq {

double RegularBeam::dimensionless_spring(int dof) const {
  const double v[4] = {k0, r0, kL, rL};
  const double f = (dof % 2 == 0) ? L * L * L / EI : L / EI;
  return std::isinf(v[dof]) ? kInf : v[dof] * f;
}

void RegularBeam::validate(bool need_mass) const {
  if (!(EI > 0 && std::isfinite(EI))) throw std::invalid_argument("EI must be finite and > 0");
  if (!(L > 0 && std::isfinite(L))) throw std::invalid_argument("L must be finite and > 0");
  if (need_mass && !(rhoA > 0 && std::isfinite(rhoA))) throw std::invalid_argument("rhoA must be finite and > 0");
  if (R < 1 || R > kMaxElements)
    throw std::invalid_argument("R must satisfy 1 <= R <= " + std::to_string(kMaxElements) + " (got " +
                                std::to_string(R) + ")");
  for (double k : {k0, r0, kL, rL})
    if (!(k >= 0)) throw std::invalid_argument("end springs must lie in [0, inf]");
}

int rigid_body_modes(const RegularBeam& b) {
  const bool rot = b.r0 > 0 || b.rL > 0;
  const int trans = (b.k0 > 0) + (b.kL > 0);
  if (rot) return trans > 0 ? 0 : 1;
  return trans == 2 ? 0 : 2 - trans;
}

}  // namespace modalbench::difference_eq
