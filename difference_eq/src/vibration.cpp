#include "modalbench/difference_eq/vibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "chain.hpp"

namespace modalbench::difference_eq {

MassModel mass_model_from_string(const std::string& s) {
  if (s == "consistent") return MassModel::Consistent;
  if (s == "lumped") return MassModel::Lumped;
  throw std::invalid_argument("mass model must be consistent or lumped (got '" + s + "')");
}

std::string to_string(MassModel m) { return m == MassModel::Consistent ? "consistent" : "lumped"; }

namespace detail {

namespace {
constexpr double pi = std::numbers::pi;
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

int negative_eigenvalues(const Eigen::MatrixXd& A) {
  const Eigen::Index n = A.rows();
  if (n == 0) return 0;
  // Congruence with s_i = 1/sqrt(max_j |A_ij|) keeps the inertia and bounds every entry by 1
  // (|A_ij| <= min(r_i, r_j)); scaling by the diagonal alone fails when a diagonal entry
  // passes through zero.
  Eigen::VectorXd s(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double r = A.row(i).cwiseAbs().maxCoeff();
    s[i] = r > 0 ? 1.0 / std::sqrt(r) : 1.0;
  }
  const Eigen::MatrixXd As = s.asDiagonal() * A * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(As, Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) throw std::runtime_error("difference_eq: small eigenproblem failed");
  int neg = 0;
  for (Eigen::Index i = 0; i < n; ++i) neg += es.eigenvalues()[i] < 0.0;
  return neg;
}

long pinned_pinned_count(long R, const MassCoeffs& m, double Om) {
  const double A = 48.0 + Om * (24.0 * m.m22_1 - 4.0 * m.m11_1 + 24.0 * m.gm) +
                   Om * Om * (m.m11_1 * m.m22_1 + m.gm * m.gm);
  const double B = Om * (24.0 * m.m22_0 - 12.0 * m.m11_1 - 4.0 * m.m11_0 + 48.0 * m.gm) +
                   Om * Om * (m.m11_1 * m.m22_0 + m.m11_0 * m.m22_1 + 2.0 * m.gm * m.gm);
  const double C = -Om * m.m11_0 * (12.0 - Om * m.m22_0);
  auto Q = [&](double x) { return (A * x + B) * x + C; };
  auto trace = [&](double x) {
    return (12.0 - Om * (m.m11_0 + m.m22_0)) + x * (-20.0 - Om * (m.m11_1 + m.m22_1));
  };
  auto theta_of = [](double x) { return 2.0 * std::asin(std::min(1.0, std::sqrt(std::max(0.0, -0.5 * x)))); };
  std::vector<double> th = {0.0, pi};
  const double disc = B * B - 4.0 * A * C;
  if (disc >= 0) {
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    for (double x : {q / A, q != 0.0 ? C / q : 0.0})
      if (x > -2.0 && x < 0.0) th.push_back(theta_of(x));
  }
  const double tden = 20.0 + Om * (m.m11_1 + m.m22_1);
  if (tden != 0) {
    const double xt = (12.0 - Om * (m.m11_0 + m.m22_0)) / tden;
    if (xt > -2.0 && xt < 0.0) th.push_back(theta_of(xt));
  }
  std::sort(th.begin(), th.end());
  long count = 0;
  const double Rd = static_cast<double>(R);
  for (std::size_t i = 0; i + 1 < th.size(); ++i) {
    const double a = th[i], b = th[i + 1];
    long klo = std::max<long>(1, static_cast<long>(std::ceil(a * Rd / pi)));
    long khi = std::min<long>(R - 1, static_cast<long>(std::ceil(b * Rd / pi)) - 1);
    if (khi < klo) continue;
    const double tm = 0.5 * (a + b);
    const double sh = std::sin(0.5 * tm);
    const double x = -2.0 * sh * sh;
    const double det = Q(x), tr = trace(x);
    const int neg = det < 0 ? 1 : (tr < 0 ? 2 : 0);
    count += neg * (khi - klo + 1);
  }
  // k = 0 (phi = 1) and k = R (phi = (-1)^r): rotation only.
  if (12.0 - Om * m.m22_0 < 0) ++count;
  if (4.0 - Om * (m.m22_0 - 2.0 * m.m22_1) < 0) ++count;
  return count;
}

double acoustic_estimate(long R, const MassCoeffs& m, long k) {
  const double th = pi * static_cast<double>(k) / static_cast<double>(R);
  const double sh = std::sin(0.5 * th);
  const double x = -2.0 * sh * sh, s2 = -x * (2.0 + x);
  const double k11 = -24.0 * x, k22 = 12.0 + 4.0 * x;
  const double m11 = m.m11_0 + m.m11_1 * x, m22 = m.m22_0 + m.m22_1 * x;
  const double a = m11 * m22 - m.gm * m.gm * s2;
  const double b = -(k11 * m22 + k22 * m11) - 24.0 * m.gm * s2;
  const double c = 48.0 * x * x;
  if (a == 0.0) return -c / b;
  const double d = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
  return 2.0 * c / (-b + d);
}

}  // namespace detail

namespace {

using detail::Chain;
using detail::MassCoeffs;

struct Problem {
  long R;
  const MassCoeffs* mc;
  std::array<double, 4> k;  // element units, inf = held
  double lam_to_Omega;      // Omega = lambda * this
};

Problem make_problem(const RegularBeam& b, MassModel mass) {
  b.validate(true);
  Problem p;
  p.R = b.R;
  p.mc = &detail::coeffs(mass);
  const double a = b.a();
  auto sc = [](double v, double f) { return std::isinf(v) ? kInf : v * f; };
  p.k = {sc(b.k0, a * a * a / b.EI), sc(b.r0, a / b.EI), sc(b.kL, a * a * a / b.EI), sc(b.rL, a / b.EI)};
  p.lam_to_Omega = b.rhoA * a * a * a * a / (p.mc->den * b.EI);
  return p;
}

Chain chain_at(const Problem& p, double Om) {
  Chain c(p.R, *p.mc, Om);
  // A root exactly at a band edge (sigma or kappa = 0) makes the column normalisation 0/0;
  // the functions are smooth there, so step off by one ulp.
  for (int i = 0; c.degenerate && i < 4; ++i) {
    Om = std::nextafter(Om, kInf);
    c = Chain(p.R, *p.mc, Om);
  }
  return c;
}

long count_omega(const Problem& p, double Om) {
  // At a pinned-pinned eigenvalue N_pp jumps exactly while an eigenvalue of D_phiphi crosses zero
  // with a rounding-sized sign: the two jumps cancel in exact arithmetic but not within ~1e-15
  // of the crossing. The count is piecewise constant, so evaluate it just above such a point
  // (1e-10 relative); Brent on the pole-free det C then places the root exactly.
  for (double shift = 1e-10; shift < 1e-3; shift *= 10.0) {
    const long lo = detail::pinned_pinned_count(p.R, *p.mc, Om * (1.0 - 1e-12));
    const long hi = detail::pinned_pinned_count(p.R, *p.mc, Om * (1.0 + 1e-12));
    if (lo == hi) break;
    Om *= 1.0 + shift;
  }
  Chain c = chain_at(p, Om);
  // Likewise at a clamped-clamped eigenvalue (a pole of D): there D is a huge rank-one term
  // whose rounding hides the signs of the rest. Step off until the pole no longer dominates.
  for (double shift = 1e-12; c.pole_closeness() < 1e-11 && shift < 1e-3; shift *= 10.0)
    c = chain_at(p, Om * (1.0 + shift));
  const Eigen::Matrix4d D = c.end_stiffness();
  Eigen::Matrix2d Dpp;
  Dpp << D(1, 1), D(1, 3), D(3, 1), D(3, 3);
  std::vector<int> fr;
  for (int i = 0; i < 4; ++i)
    if (!std::isinf(p.k[i])) fr.push_back(i);
  Eigen::MatrixXd Df(fr.size(), fr.size());
  for (std::size_t i = 0; i < fr.size(); ++i)
    for (std::size_t j = 0; j < fr.size(); ++j) Df(i, j) = D(fr[i], fr[j]) + (i == j ? p.k[fr[i]] : 0.0);
  return detail::pinned_pinned_count(p.R, *p.mc, c.Omega) - detail::negative_eigenvalues(Dpp) +
         detail::negative_eigenvalues(Df);
}

double char_omega(const Problem& p, double Om) {
  const Chain c = chain_at(p, Om);
  return c.characteristic_matrix(p.k).partialPivLu().determinant();
}

}  // namespace

long count_below(const RegularBeam& beam, MassModel mass, double lambda) {
  const Problem p = make_problem(beam, mass);
  if (!(lambda > 0)) return 0;
  return count_omega(p, lambda * p.lam_to_Omega);
}

double characteristic_function(const RegularBeam& beam, MassModel mass, double lambda) {
  const Problem p = make_problem(beam, mass);
  return char_omega(p, lambda * p.lam_to_Omega);
}

std::vector<double> end_dynamic_stiffness(const RegularBeam& beam, MassModel mass, double lambda) {
  const Problem p = make_problem(beam, mass);
  const Eigen::Matrix4d D = chain_at(p, lambda * p.lam_to_Omega).end_stiffness();
  std::vector<double> out(16);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[4 * i + j] = D(i, j);
  return out;
}

Spectrum natural_frequencies(const RegularBeam& beam, MassModel mass, int k) {
  const Problem p = make_problem(beam, mass);
  if (k < 0) throw std::invalid_argument("number of modes must be >= 0");
  Spectrum out;
  const long R = beam.R;
  const int held_t = std::isinf(p.k[0]) + std::isinf(p.k[2]);
  const int held_r = std::isinf(p.k[1]) + std::isinf(p.k[3]);
  out.available = mass == MassModel::Consistent ? 2 * (R + 1) - held_t - held_r : (R + 1) - held_t;
  const long want = std::min<long>(k, out.available);
  out.rigid = static_cast<int>(std::min<long>(rigid_body_modes(beam), want));
  out.omega_rad_s.assign(out.rigid, 0.0);

  auto N = [&](double Om) {
    ++out.count_evaluations;
    return count_omega(p, Om);
  };
  auto f = [&](double Om) { return char_omega(p, Om); };

  double lo = 0.0;
  long nlo = rigid_body_modes(beam);
  double hi_prev = 0.0;
  for (long j = nlo + 1; j <= want;) {
    // Bracket from the structure: mode j lies below the (j+2)-th pinned-pinned frequency,
    // whose acoustic branch is closed-form; the exact count confirms or the bracket grows.
    double hi = 0;
    if (j + 2 <= R - 1) hi = detail::acoustic_estimate(R, *p.mc, j + 2) * (1.0 + 1e-9);
    if (!(hi > lo)) hi = std::max(2.0 * lo, hi_prev > lo ? hi_prev : 1.0);
    long nhi = N(hi);
    for (int grow = 0; nhi < j; ++grow) {
      if (grow > 200) throw std::runtime_error("difference_eq: could not bracket mode " + std::to_string(j));
      lo = hi;
      nlo = nhi;
      hi *= 2.0;
      nhi = N(hi);
    }
    // Isolate: N(lo) = j - 1, N(hi) = j.
    while (!(nlo == j - 1 && nhi == j)) {
      if (hi - lo <= 4e-16 * hi) break;
      const double mid = 0.5 * (lo + hi);
      const long nm = N(mid);
      if (nm < nlo || nm > nhi)
        throw std::runtime_error("difference_eq: the mode count is not monotonic (numerical breakdown)");
      if (nm >= j) {
        hi = mid;
        nhi = nm;
      } else {
        lo = mid;
        nlo = nm;
      }
    }
    double root;
    long mult = 1;
    if (nlo == j - 1 && nhi == j && lo == 0.0) {
      // Omega = 0 is the double root x = 0 where the solution basis degenerates: never
      // evaluate there; move lo up by halving (the count keeps the bracket honest).
      double t = 0.5 * hi;
      for (int h = 0; h < 2000; ++h, t *= 0.5) {
        if (N(t) < j) break;
        hi = t;
      }
      lo = t;
    }
    if (nlo == j - 1 && nhi == j) {
      const double flo = f(lo), fhi = f(hi);
      out.determinant_evaluations += 2;
      if (flo == 0.0) root = lo;
      else if (fhi == 0.0) root = hi;
      else if ((flo > 0) != (fhi > 0)) root = detail::brent(f, lo, hi, flo, fhi, out.determinant_evaluations);
      else {
        // No sign change seen (should not happen for a simple root): bisect on the count.
        while (hi - lo > 4e-16 * hi) {
          const double mid = 0.5 * (lo + hi);
          if (N(mid) >= j) hi = mid;
          else lo = mid;
        }
        root = 0.5 * (lo + hi);
      }
      out.max_bracket = std::max(out.max_bracket, 4.0 * std::numeric_limits<double>::epsilon());
    } else {
      // A cluster narrower than rounding: a repeated frequency.
      root = 0.5 * (lo + hi);
      mult = nhi - (j - 1);
      out.max_bracket = std::max(out.max_bracket, (hi - lo) / hi);
    }
    for (long m = 0; m < mult && j <= want; ++m, ++j) out.omega_rad_s.push_back(std::sqrt(root / p.lam_to_Omega));
    hi_prev = 2.0 * hi;
    lo = hi;
    nlo = nhi;
  }
  return out;
}

ModeShape mode_shape(const RegularBeam& beam, MassModel mass, double omega) {
  const Problem p = make_problem(beam, mass);
  const Chain c = chain_at(p, omega * omega * p.lam_to_Omega);
  const Eigen::Matrix4d Cm = c.characteristic_matrix(p.k);
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(Cm, Eigen::ComputeFullV);
  const Eigen::Vector4d amp = svd.matrixV().col(3);
  const long R = beam.R;
  ModeShape u;
  u.w.assign(R + 1, 0.0);
  u.slope.assign(R + 1, 0.0);
  std::vector<double> phi(R + 1, 0.0);
  for (long r = 0; r <= R; ++r) {
    const double t = static_cast<double>(r) - c.T;
    const double sg = t < 0 ? -1.0 : 1.0;
    std::complex<double> w = 0, ph = 0;
    for (int j = 0; j < 2; ++j) {
      std::complex<double> C, S;
      c.root[j].ch_sh(std::abs(t), c.T, C, S);
      S *= sg;
      w += amp[j] * (c.root[j].W * C / c.norm[0][j]) + amp[2 + j] * (c.root[j].W * S / c.norm[1][j]);
      ph += amp[j] * (c.root[j].Phi * S / c.norm[0][j]) + amp[2 + j] * (c.root[j].Phi * C / c.norm[1][j]);
    }
    u.w[r] = w.real();
    phi[r] = ph.real();
  }
  double scale = 0;
  for (long r = 0; r <= R; ++r) scale = std::max({scale, std::abs(u.w[r]), std::abs(phi[r])});
  const double a = beam.a();
  for (long r = 0; r <= R; ++r) {
    u.w[r] /= scale;
    u.slope[r] = phi[r] / scale / a;
  }
  return u;
}

double eigen_residual(const RegularBeam& beam, MassModel mass, double omega, const ModeShape& u) {
  const Problem p = make_problem(beam, mass);
  const long R = beam.R;
  const double a = beam.a(), Om = omega * omega * p.lam_to_Omega;
  static const double ke[4][4] = {{12, 6, -12, 6}, {6, 4, -6, 2}, {-12, -6, 12, -6}, {6, 2, -6, 4}};
  static const double mc[4][4] = {{156, 22, 54, -13}, {22, 4, 13, -3}, {54, 13, 156, -22}, {-13, -3, -22, 4}};
  static const double ml[4][4] = {{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 0}};
  const auto& me = mass == MassModel::Consistent ? mc : ml;
  std::vector<double> Ku(2 * (R + 1), 0.0), Mu(2 * (R + 1), 0.0);
  for (long e = 0; e < R; ++e) {
    const double ue[4] = {u.w[e], a * u.slope[e], u.w[e + 1], a * u.slope[e + 1]};
    for (int i = 0; i < 4; ++i) {
      double ks = 0, ms = 0;
      for (int j = 0; j < 4; ++j) {
        ks += ke[i][j] * ue[j];
        ms += me[i][j] * ue[j];
      }
      Ku[2 * e + i] += ks;
      Mu[2 * e + i] += ms;
    }
  }
  const long end_dof[4] = {0, 1, 2 * R, 2 * R + 1};
  double held = 0;
  for (int i = 0; i < 4; ++i) {
    const long d = end_dof[i];
    const double v = (d % 2 == 0) ? u.w[d / 2] : a * u.slope[d / 2];
    if (std::isinf(p.k[i])) {
      held = std::max(held, std::abs(v));
      Ku[d] = Mu[d] = 0;  // the reaction takes this row
    } else {
      Ku[d] += p.k[i] * v;
    }
  }
  // Normwise backward error: ||r|| / ((||K|| + Omega ||M||) ||u||) (infinity norms, element units).
  double res = 0, umax = 0;
  for (std::size_t i = 0; i < Ku.size(); ++i) res = std::max(res, std::abs(Ku[i] - Om * Mu[i]));
  for (long r = 0; r <= R; ++r) umax = std::max({umax, std::abs(u.w[r]), std::abs(a * u.slope[r])});
  double knorm = 60.0, mnorm = mass == MassModel::Consistent ? 446.0 : 2.0;
  for (int i = 0; i < 4; ++i)
    if (!std::isinf(p.k[i])) knorm = std::max(knorm, 60.0 + p.k[i]);
  const double den = (knorm + Om * mnorm) * umax;
  return std::max(den > 0 ? res / den : res, umax > 0 ? held / umax : held);
}

}  // namespace modalbench::difference_eq
