#pragma once
// Shared references for the difference_eq tests: binary128 scalars, dense FE matrices.

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "modalbench/difference_eq/assembled.hpp"
#include "modalbench/difference_eq/regular_beam.hpp"

namespace deq_test {

// IEEE binary128: the direct FE solves of near-mechanisms need more than double to represent
// the data (a spring of 1e-6 L^3/EI next to element stiffnesses ~ R^3 EI/L^3).
__extension__ typedef __float128 quad;

/// max |x - ref| / max(max |ref|, floor): the floor gives a field that is exactly zero (a slope
/// under pure translation) the scale of its companion field (w / L).
inline double rel_max_error(const std::vector<double>& x, const std::vector<quad>& ref, double floor = 0) {
  double err = 0, scale = floor;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double d = std::abs(x[i] - static_cast<double>(ref[i]));
    err = (std::isnan(d) || d > err) ? d : err;
    scale = std::max(scale, std::abs(static_cast<double>(ref[i])));
  }
  return scale > 0 ? err / scale : err;
}

/// Dense K and M of the FE chain on the free DOFs (element units EI/a^3; mass per (c EI/a^4)).
inline void dense_KM(const modalbench::difference_eq::RegularBeam& b, bool consistent, Eigen::MatrixXd& K,
                     Eigen::MatrixXd& M, std::vector<long>& dofs) {
  using namespace modalbench::difference_eq;
  const long R = b.R, n = 2 * (R + 1);
  Eigen::MatrixXd Kf = Eigen::MatrixXd::Zero(n, n), Mf = Eigen::MatrixXd::Zero(n, n);
  const auto& me = consistent ? assembled::kMassConsistent : assembled::kMassLumped;
  for (long e = 0; e < R; ++e)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        Kf(2 * e + i, 2 * e + j) += assembled::kStiff[i][j];
        Mf(2 * e + i, 2 * e + j) += me[i][j];
      }
  const double a = b.L / static_cast<double>(R);
  const double k[4] = {b.k0 * a * a * a / b.EI, b.r0 * a / b.EI, b.kL * a * a * a / b.EI, b.rL * a / b.EI};
  const long dof[4] = {0, 1, 2 * R, 2 * R + 1};
  dofs.clear();
  for (long i = 0; i < n; ++i) {
    bool held = false;
    for (int j = 0; j < 4; ++j)
      if (dof[j] == i && std::isinf(k[j])) held = true;
    if (!held) dofs.push_back(i);
  }
  for (int j = 0; j < 4; ++j)
    if (!std::isinf(k[j])) Kf(dof[j], dof[j]) += k[j];
  K.resize(dofs.size(), dofs.size());
  M.resize(dofs.size(), dofs.size());
  for (std::size_t i = 0; i < dofs.size(); ++i)
    for (std::size_t j = 0; j < dofs.size(); ++j) {
      K(i, j) = Kf(dofs[i], dofs[j]);
      M(i, j) = Mf(dofs[i], dofs[j]);
    }
}

}  // namespace deq_test
