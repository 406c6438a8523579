#include "modalbench/rfem/model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace modalbench::rfem {

std::string dof_symbol(int d) {
  switch (d) {
    case dofs::Ux: return "u";
    case dofs::Uy: return "v";
    case dofs::Uz: return "w";
    case dofs::Rx: return "theta_x";
    case dofs::Ry: return "theta_y";
    case dofs::Rz: return "theta_z";
    default: return "?";
  }
}

int Model::local_index(int d) const {
  for (std::size_t k = 0; k < active.size(); ++k)
    if (active[k] == d) return static_cast<int>(k);
  return -1;
}

std::string Model::dof_name(long i) const {
  const long na = dofs_per_element();
  const long e = i / na;
  const int d = active[static_cast<std::size_t>(i % na)];
  const std::string& lab = elements[static_cast<std::size_t>(e)].label;
  return fmt::format("{}[{}]", dof_symbol(d), lab.empty() ? fmt::format("rfe {}", e) : lab);
}

void Model::check() const {
  if (active.empty()) throw std::invalid_argument("rfem model: no active DOFs");
  for (int d : active)
    if (d < 0 || d > 5) throw std::invalid_argument("rfem model: active DOF index outside 0..5");
  if (elements.empty()) throw std::invalid_argument("rfem model: no rigid elements");
  const int ne = static_cast<int>(elements.size());
  for (int e = 0; e < ne; ++e) {
    const auto& r = elements[static_cast<std::size_t>(e)];
    if (!(r.mass > 0) || !std::isfinite(r.mass))
      throw std::invalid_argument(fmt::format("rfem model: element {} has mass {} (must be finite, > 0)", e, r.mass));
    for (int d : active)
      if (d >= 3 && !(r.inertia[d - 3] > 0 && std::isfinite(r.inertia[d - 3])))
        throw std::invalid_argument(
            fmt::format("rfem model: element {} has moment of inertia {} about axis {} (must be > 0)", e,
                        r.inertia[d - 3], d - 3));
  }
  for (std::size_t s = 0; s < sdes.size(); ++s) {
    const Sde& sd = sdes[s];
    if (sd.a < 0 || sd.a >= ne || sd.b < kGround || sd.b >= ne || sd.a == sd.b)
      throw std::invalid_argument(fmt::format("rfem model: SDE {} joins invalid elements {} and {}", s, sd.a, sd.b));
    for (int c = 0; c < 6; ++c) {
      if (std::isnan(sd.stiffness[c]) || sd.stiffness[c] < 0)
        throw std::invalid_argument(fmt::format("rfem model: SDE {} stiffness k{} = {} (must be >= 0)", s, c + 1,
                                                sd.stiffness[c]));
      if (!std::isfinite(sd.damping[c]) || sd.damping[c] < 0)
        throw std::invalid_argument(fmt::format("rfem model: SDE {} damping c{} = {} (must be finite, >= 0)", s,
                                                c + 1, sd.damping[c]));
    }
  }
  for (std::size_t c = 0; c < couplings.size(); ++c) {
    const auto& cp = couplings[c];
    const auto n = static_cast<Eigen::Index>(6 * cp.elements.size());
    if (!cp.stiffness || cp.stiffness->rows() != n || cp.stiffness->cols() != n)
      throw std::invalid_argument(fmt::format("rfem model: coupling {} needs a {}x{} matrix for {} elements", c, n, n,
                                              cp.elements.size()));
    for (int e : cp.elements)
      if (e < 0 || e >= ne) throw std::invalid_argument(fmt::format("rfem model: coupling {} names element {}", c, e));
  }
  if (basis.size() > 0 || basis.cols() > 0) {
    if (basis.rows() != body_dofs())
      throw std::invalid_argument("rfem model: basis rows must equal the number of body DOFs");
    if (static_cast<Eigen::Index>(basis_names.size()) != basis.cols())
      throw std::invalid_argument("rfem model: one name per basis column required");
  }
  if (dof_family.size() != active.size())
    throw std::invalid_argument("rfem model: dof_family must parallel the active DOFs");
}

}  // namespace modalbench::rfem
