// The closed-form chain at one Omega: mass-model coefficients, solution roots, end stiffness, characteristic matrix.
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <complex>

#include "chain.hpp"

namespace modalbench::difference_eq::detail {

namespace {
using cd = std::complex<double>;

// Consistent: rhoA a / 420 [[156, 22, 54, -13], [22, 4, 13, -3], [54, 13, 156, -22], [-13, -3, -22, 4]]
// in (w, phi = a psi). Lumped: rhoA a / 2 diag(1, 0, 1, 0).
// Node symbol M(z) = [[m11(x), -gm s], [gm s, m22(x)]] with x = c - 1, s = (z - 1/z)/2;
// Ms = E11 + E12 and Md = E12 - E11 of the element mass blocks (for the end forces).
constexpr MassCoeffs kConsistent{420, 108, 26, 2, -6, {{210, 9}, {35, 1}}, {{-102, -35}, {-9, -7}}, 420};
constexpr MassCoeffs kLumped{2, 0, 0, 0, 0, {{1, 0}, {0, 0}}, {{-1, 0}, {0, 0}}, 2};

// Scaled hyperbolic pair for real mu >= 0: 2 cosh(mu y) e^{-mu T}, 2 sinh(mu y) e^{-mu T}, y in [0, T].
void scaled_hyperbolic(double mu, double y, double T, double& C, double& S) {
  if (mu * T <= 30.0) {
    const double e = std::exp(-mu * T);
    C = 2.0 * std::cosh(mu * y) * e;
    S = 2.0 * std::sinh(mu * y) * e;
  } else {
    const double p = std::exp(mu * (y - T)), m = std::exp(-mu * (y + T));
    C = p + m;
    S = p - m;
  }
}

}  // namespace

const MassCoeffs& coeffs(MassModel m) { return m == MassModel::Consistent ? kConsistent : kLumped; }

void RootData::ch_sh(double y, double T, cd& C, cd& S) const {
  switch (kind) {
    case Kind::Hyper: {
      double c, s;
      scaled_hyperbolic(mur, y, T, c, s);
      C = c;
      S = s;
      return;
    }
    case Kind::Trig:
      C = 2.0 * std::cos(nu * y);
      S = cd(0.0, 2.0 * std::sin(nu * y));
      return;
    case Kind::Alt: {
      // mu = mu' + i pi and y is an integer or a half-integer: cos(pi y), sin(pi y) exact.
      double c, s;
      scaled_hyperbolic(mur, y, T, c, s);
      const long long n = std::llround(2.0 * y);
      if (n % 2 == 0) {
        const double sg = ((n / 2) % 2 == 0) ? 1.0 : -1.0;
        C = c * sg;
        S = s * sg;
      } else {
        const double sg = (((n - 1) / 2) % 2 == 0) ? 1.0 : -1.0;
        C = cd(0.0, s * sg);
        S = cd(0.0, c * sg);
      }
      return;
    }
    case Kind::Complex: {
      const double rho = mu.real();
      if (rho * T <= 30.0) {
        const double e = std::exp(-rho * T);
        C = 2.0 * std::cosh(mu * y) * e;
        S = 2.0 * std::sinh(mu * y) * e;
      } else {
        const cd p = std::exp(mu * y - rho * T), m = std::exp(-mu * y - rho * T);
        C = p + m;
        S = p - m;
      }
      return;
    }
  }
}

Chain::Chain(long R_, const MassCoeffs& m, double Om) : R(R_), T(0.5 * static_cast<double>(R_)), mc(&m), Omega(Om) {
  const double g = 12.0 + Om * m.gm;
  // det H = A x^2 + B x + C, x = cosh(mu) - 1, expanded so that no coefficient cancels.
  const double A = 48.0 + Om * (24.0 * m.m22_1 - 4.0 * m.m11_1 + 24.0 * m.gm) +
                   Om * Om * (m.m11_1 * m.m22_1 + m.gm * m.gm);
  const double B = Om * (24.0 * m.m22_0 - 12.0 * m.m11_1 - 4.0 * m.m11_0 + 48.0 * m.gm) +
                   Om * Om * (m.m11_1 * m.m22_0 + m.m11_0 * m.m22_1 + 2.0 * m.gm * m.gm);
  const double C = -Om * m.m11_0 * (12.0 - Om * m.m22_0);
  const double disc = B * B - 4.0 * A * C;
  cd xs[2];
  bool real_roots = disc >= 0.0;
  if (real_roots) {
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    xs[0] = q / A;
    xs[1] = (q != 0.0) ? C / q : 0.0;
  } else {
    const double re = -B / (2.0 * A), im = std::sqrt(-disc) / (2.0 * A);
    xs[0] = cd(re, im);
    xs[1] = cd(re, -im);
  }
  degenerate = false;
  for (int j = 0; j < 2; ++j) {
    RootData& rd = root[j];
    if (real_roots) {
      const double x = xs[j].real();
      if (x > 0.0) {
        rd.kind = RootData::Kind::Hyper;
        const double sg = std::sqrt(0.5 * x);
        rd.mur = 2.0 * std::asinh(sg);
        rd.sigma = std::sinh(0.5 * rd.mur);
        rd.kappa = std::cosh(0.5 * rd.mur);
        rd.mu = rd.mur;
      } else if (x >= -2.0) {
        rd.kind = RootData::Kind::Trig;
        rd.nu = 2.0 * std::asin(std::min(1.0, std::sqrt(-0.5 * x)));
        rd.sigma = cd(0.0, std::sin(0.5 * rd.nu));
        rd.kappa = std::cos(0.5 * rd.nu);
        rd.mu = cd(0.0, rd.nu);
      } else {
        rd.kind = RootData::Kind::Alt;
        // sinh(mu/2) = i cosh(mu'/2) with cosh^2(mu'/2) = -x/2; sinh(mu'/2) = sqrt(-x/2 - 1).
        rd.mur = 2.0 * std::asinh(std::sqrt(-0.5 * x - 1.0));
        rd.sigma = cd(0.0, std::cosh(0.5 * rd.mur));
        rd.kappa = cd(0.0, std::sinh(0.5 * rd.mur));
        rd.mu = cd(rd.mur, pi);
      }
    } else {
      rd.kind = RootData::Kind::Complex;
      cd mu = 2.0 * std::asinh(std::sqrt(0.5 * xs[j]));
      if (mu.real() < 0) mu = -mu;
      rd.mu = mu;
      rd.sigma = std::sinh(0.5 * mu);
      rd.kappa = std::cosh(0.5 * mu);
    }
    const cd s2 = rd.sigma * rd.sigma, k2 = rd.kappa * rd.kappa;
    const cd x = 2.0 * s2;
    rd.W = 12.0 + 4.0 * x - Om * (m.m22_0 + m.m22_1 * x);
    rd.Phi = 2.0 * g * rd.sigma * rd.kappa;
    // g kappa^2 - h22 = 4 sigma^2 + Omega (gm kappa^2 + m22(x)): the shear of a long wave
    // without the cancellation of the nodal differences.
    const cd gk = 4.0 * s2 + Om * (m.gm * k2 + m.m22_0 + m.m22_1 * x);
    rd.Ge[0] = -Om * rd.kappa * (m.Ms[0][0] * rd.W + 2.0 * g * s2 * m.Md[0][1]);
    rd.Ge[1] = -4.0 * g * s2 * rd.kappa - Om * rd.kappa * (m.Ms[1][0] * rd.W + 2.0 * g * s2 * m.Md[1][1]);
    rd.Go[0] = 24.0 * rd.sigma * gk - Om * rd.sigma * (2.0 * g * k2 * m.Ms[0][1] + m.Md[0][0] * rd.W);
    rd.Go[1] = 12.0 * rd.sigma * gk - Om * rd.sigma * (2.0 * g * k2 * m.Ms[1][1] + m.Md[1][0] * rd.W);

    // Columns, normalised by sigma^a kappa^b so that they are real-analytic in Omega.
    const bool even = (R % 2 == 0);
    cd ns = even ? cd(1.0) : rd.kappa;
    cd na = even ? rd.sigma * rd.kappa : rd.sigma;
    if (j == 1) {
      // The root x2 = C/q passes x = 0 where h22 = 12 - m22_0 Omega vanishes too (consistent mass:
      // Omega = 6) and x = -2 where h22 = 4 - (m22_0 - 2 m22_1) Omega vanishes (Omega = 2/7):
      // there v = (h22, g sinh mu) -> 0 and one column has a simple zero. Dividing by these
      // factors keeps every column non-zero, so det C changes sign only at eigenvalues.
      ns *= (12.0 - Om * m.m22_0) / 12.0;
      (even ? ns : na) *= (4.0 - Om * (m.m22_0 - 2.0 * m.m22_1)) / 4.0;
    }
    if (ns == 0.0 || na == 0.0) degenerate = true;
    norm[0][j] = ns;
    norm[1][j] = na;
    cd CT, ST, Ch, Sh;
    rd.ch_sh(T, T, CT, ST);
    rd.ch_sh(T - 0.5, T, Ch, Sh);
    E[0][j][0] = rd.W * CT / ns;
    E[0][j][1] = -rd.Phi * ST / ns;
    E[1][j][0] = -rd.W * ST / na;
    E[1][j][1] = rd.Phi * CT / na;
    for (int i = 0; i < 2; ++i) {
      F[0][j][i] = (rd.Ge[i] * Ch - rd.Go[i] * Sh) / ns;
      F[1][j][i] = (-rd.Ge[i] * Sh + rd.Go[i] * Ch) / na;
    }
  }
}

Eigen::Matrix4d Chain::end_stiffness() const {
  Eigen::Matrix2d Dp[2];
  for (int p = 0; p < 2; ++p) {
    Eigen::Matrix2cd Em, Fm;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        Em(i, j) = E[p][j][i];
        Fm(i, j) = F[p][j][i];
      }
    const cd det = Em(0, 0) * Em(1, 1) - Em(0, 1) * Em(1, 0);
    Eigen::Matrix2cd inv;
    inv << Em(1, 1), -Em(0, 1), -Em(1, 0), Em(0, 0);
    inv /= det;
    const Eigen::Matrix2cd D = Fm * inv;
    Dp[p] = D.real();
    Dp[p] = 0.5 * (Dp[p] + Dp[p].transpose()).eval();
  }
  // Sym part p = (d0 + J dR)/2, anti part q = (d0 - J dR)/2, J = diag(1, -1):
  // f0 = Ds p + Da q, fR = J (Ds p - Da q).
  Eigen::Matrix2d J = Eigen::Vector2d(1.0, -1.0).asDiagonal();
  Eigen::Matrix4d D;
  D.block<2, 2>(0, 0) = 0.5 * (Dp[0] + Dp[1]);
  D.block<2, 2>(0, 2) = 0.5 * (Dp[0] - Dp[1]) * J;
  D.block<2, 2>(2, 0) = 0.5 * J * (Dp[0] - Dp[1]);
  D.block<2, 2>(2, 2) = 0.5 * J * (Dp[0] + Dp[1]) * J;
  return D;
}

Eigen::Matrix4d Chain::characteristic_matrix(const std::array<double, 4>& k) const {
  // Columns (sym root 1, sym root 2, anti root 1, anti root 2); rows (w0, phi0, wR, phiR).
  Eigen::Matrix4d Cm;
  for (int p = 0; p < 2; ++p)
    for (int j = 0; j < 2; ++j) {
      const int col = 2 * p + j;
      for (int i = 0; i < 2; ++i) {
        const double e = E[p][j][i].real(), f = F[p][j][i].real();
        const double left = std::isinf(k[i]) ? e : f + k[i] * e;
        const double right = std::isinf(k[2 + i]) ? e : f + k[2 + i] * e;
        // Mirror: sym solutions have (w, phi)_R = (w, -phi)_0 and forces likewise; anti the opposite.
        const double sgn = (p == 0) ? (i == 0 ? 1.0 : -1.0) : (i == 0 ? -1.0 : 1.0);
        Cm(i, col) = left;
        Cm(2 + i, col) = sgn * right;
      }
    }
  for (int r = 0; r < 4; ++r) {
    const double m = Cm.row(r).cwiseAbs().maxCoeff();
    if (m > 0) Cm.row(r) /= m;
  }
  return Cm;
}

double Chain::pole_closeness() const {
  double m = kInf;
  for (int p = 0; p < 2; ++p) {
    const cd det = E[p][0][0] * E[p][1][1] - E[p][1][0] * E[p][0][1];
    const double n0 = std::hypot(std::abs(E[p][0][0]), std::abs(E[p][0][1]));
    const double n1 = std::hypot(std::abs(E[p][1][0]), std::abs(E[p][1][1]));
    if (n0 > 0 && n1 > 0) m = std::min(m, std::abs(det) / (n0 * n1));
  }
  return m;
}

}  // namespace modalbench::difference_eq::detail
