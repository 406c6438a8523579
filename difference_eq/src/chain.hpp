#pragma once
// Internal: the closed-form chain at one dimensionless frequency Omega (see vibration.hpp).

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>

#include "modalbench/difference_eq/vibration.hpp"

namespace modalbench::difference_eq::detail {

inline constexpr double pi = std::numbers::pi;

/// Roots of the characteristic functions to full precision: the final bracket is at most
/// 4 eps wide (relative), as the hand-written Brent this replaced.
inline constexpr double kRootRelTol = 4.0 * 2.220446049250313e-16;

/// Node symbol coefficients of a mass model (element units), see chain.cpp.
struct MassCoeffs {
  double m11_0, m11_1, gm, m22_0, m22_1;
  double Ms[2][2], Md[2][2];
  double den;  ///< Omega = omega^2 rhoA a^4 / (den EI)
};

/// One root x of the dispersion quadratic and the quantities of its solution pair.
struct RootData {
  enum class Kind { Hyper, Trig, Alt, Complex } kind = Kind::Hyper;
  std::complex<double> mu, sigma, kappa;  ///< mu; sinh(mu/2); cosh(mu/2)
  double mur = 0;  ///< Hyper: mu; Alt: mu' (mu = mu' + i pi)
  double nu = 0;   ///< Trig: mu = i nu
  std::complex<double> W, Phi, Ge[2], Go[2];
  /// 2 cosh(mu y) e^{-Re(mu) T}, 2 sinh(mu y) e^{-Re(mu) T} for 0 <= y <= T.
  void ch_sh(double y, double T, std::complex<double>& C, std::complex<double>& S) const;
};

struct Chain {
  long R;
  double T;
  const MassCoeffs* mc;
  double Omega;
  RootData root[2];
  std::complex<double> E[2][2][2], F[2][2][2];  ///< [parity: sym, anti][root][dof: w, phi] at r = 0
  std::complex<double> norm[2][2];              ///< column normalisation [parity][root]
  bool degenerate = false;

  Chain(long R, const MassCoeffs& m, double Omega);
  Eigen::Matrix4d end_stiffness() const;
  Eigen::Matrix4d characteristic_matrix(const std::array<double, 4>& k) const;
  /// |sin| of the angle between the two end-displacement columns of each parity (0 at a pole of D).
  double pole_closeness() const;
};

const MassCoeffs& coeffs(MassModel m);
int negative_eigenvalues(const Eigen::MatrixXd& A);
long pinned_pinned_count(long R, const MassCoeffs& m, double Omega);
double acoustic_estimate(long R, const MassCoeffs& m, long k);

}  // namespace modalbench::difference_eq::detail
