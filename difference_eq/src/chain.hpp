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

namespace modalbench::difference_eq::detail {

/// Brent's method on a bracket [a, b] with f(a), f(b) of opposite signs.
template <class F>
double brent(F&& f, double a, double b, double fa, double fb, long& evals) {
  double c = a, fc = fa, d = b - a, e = d;
  for (int it = 0; it < 200; ++it) {
    if ((fb > 0) == (fc > 0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {
      a = b; b = c; c = a;
      fa = fb; fb = fc; fc = fa;
    }
    const double tol = 2.0 * 2.220446049250313e-16 * std::abs(b) + 1e-300;
    const double m = 0.5 * (c - b);
    if (std::abs(m) <= tol || fb == 0.0) return b;
    if (std::abs(e) >= tol && std::abs(fa) > std::abs(fb)) {
      double pp, q, r;
      const double s = fb / fa;
      if (a == c) {
        pp = 2.0 * m * s;
        q = 1.0 - s;
      } else {
        q = fa / fc;
        r = fb / fc;
        pp = s * (2.0 * m * q * (q - r) - (b - a) * (r - 1.0));
        q = (q - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (pp > 0) q = -q;
      else pp = -pp;
      if (2.0 * pp < std::min(3.0 * m * q - std::abs(tol * q), std::abs(e * q))) {
        e = d;
        d = pp / q;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    b += std::abs(d) > tol ? d : (m > 0 ? tol : -tol);
    fb = f(b);
    ++evals;
  }
  return b;
}

}  // namespace modalbench::difference_eq::detail
