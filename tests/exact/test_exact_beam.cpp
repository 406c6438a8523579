// Exact beam and bar references against published values and hand-derived formulas.
#define BOOST_TEST_MODULE exact_beam
#include <boost/test/unit_test.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>

#include "modalbench/exact/exact.hpp"

using namespace modalbench;
using namespace modalbench::exact;

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double pi = std::numbers::pi;
const EndSprings kClamped{inf, inf}, kPinned{inf, 0}, kFree{0, 0}, kGuided{0, inf};

// A slender steel-like Euler-Bernoulli beam.
BeamBending eb_beam() { return {2.0e11 * 1e-6, inf, 7850.0 * 1e-2, 0.0, 2.0}; }

// beta_n L from omega_n: (beta L)^4 = omega^2 rhoA L^4 / EI.
double beta_L(const BeamBending& b, double w) { return std::pow(w * w * b.rhoA * std::pow(b.L, 4) / b.EI, 0.25); }

double rel(double a, double b) { return std::abs(a / b - 1.0); }
}  // namespace

BOOST_AUTO_TEST_SUITE(timoshenko)

// Hein, Table 1, "1 prism" column, with G = 8e10 Pa (docs/sources.md, P1); the values to every printed digit.
BOOST_AUTO_TEST_CASE(paper_table1_one_prism) {
  const double E = 2e11, G = 8e10, rho = 8000, b = 0.25, h = 0.25, L = 1.0, kappa = 1.0;
  const double A = b * h, I = b * h * h * h / 12;
  const BeamBending beam{E * I, kappa * G * A, rho * A, rho * I, L};
  const double ref[] = {6211.15, 13848.36, 22763.93, 32186.47, 41982.17, 47172.88};
  const auto f = beam_bending_frequencies(beam, kClamped, kClamped, 6);
  BOOST_REQUIRE(f.omega_rad_s.size() == 6u);
  for (int i = 0; i < 6; ++i) {
    BOOST_TEST_MESSAGE("mode " << i + 1 << ": " << f.omega_rad_s[i] << " vs " << ref[i]);
    BOOST_TEST(rel(f.omega_rad_s[i], ref[i]) < 1e-6);
  }
}

// Simply supported Timoshenko beam: per half-wave n a 2x2 eigenproblem in (w, phi) gives a
// bending and a shear branch; n = 0 adds the pure shear mode w = 0, phi = const at the
// cut-off sqrt(kGA / rhoI) (it satisfies w = 0 and M = EI phi' = 0 at both ends). Every
// frequency of both spectra, in order, must be found.
BOOST_AUTO_TEST_CASE(pinned_pinned_both_spectra) {
  const double E = 2e11, G = 8e10, rho = 8000, b = 0.25, h = 0.25, L = 1.0, kappa = 5.0 / 6.0;
  const double A = b * h, I = b * h * h * h / 12;
  const BeamBending beam{E * I, kappa * G * A, rho * A, rho * I, L};
  std::vector<double> ref = {std::sqrt(beam.kGA / beam.rhoI)};
  for (int n = 1; n <= 40; ++n) {
    const double k = n * pi / L;
    Eigen::Matrix2d K, M;
    K << beam.kGA * k * k, -beam.kGA * k, -beam.kGA * k, beam.EI * k * k + beam.kGA;
    M << beam.rhoA, 0, 0, beam.rhoI;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(K, M);
    ref.push_back(std::sqrt(es.eigenvalues()[0]));
    ref.push_back(std::sqrt(es.eigenvalues()[1]));
  }
  std::sort(ref.begin(), ref.end());
  const int k = 20;
  const auto f = beam_bending_frequencies(beam, kPinned, kPinned, k);
  for (int i = 0; i < k; ++i) BOOST_TEST(rel(f.omega_rad_s[i], ref[i]) < 1e-10, "mode " << i + 1);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(euler_bernoulli)

// Classical frequency parameters beta L (Blevins, Table 8-1).
BOOST_AUTO_TEST_CASE(classical_beta_L) {
  const BeamBending b = eb_beam();
  struct Case { EndSprings l, r; std::vector<double> betaL; const char* name; };
  const Case cases[] = {
      {kClamped, kClamped, {4.730040745, 7.853204624, 10.995607838}, "clamped-clamped"},
      {kClamped, kFree, {1.875104069, 4.694091133, 7.854757438}, "clamped-free"},
      {kClamped, kPinned, {3.926602312, 7.068582745, 10.210176124}, "clamped-pinned"},
      {kPinned, kPinned, {pi, 2 * pi, 3 * pi}, "pinned-pinned"},
  };
  for (const auto& c : cases) {
    const auto f = beam_bending_frequencies(b, c.l, c.r, 3);
    for (int i = 0; i < 3; ++i)
      BOOST_TEST(std::abs(beta_L(b, f.omega_rad_s[i]) - c.betaL[i]) < 1e-9 * c.betaL[i], c.name << " mode " << i + 1);
  }
}

// Free-free: two rigid modes at exactly zero, then the clamped-clamped parameters.
BOOST_AUTO_TEST_CASE(free_free_rigid_modes) {
  const BeamBending b = eb_beam();
  const auto f = beam_bending_frequencies(b, kFree, kFree, 4);
  BOOST_TEST(f.rigid == 2);
  BOOST_TEST(f.omega_rad_s[0] == 0.0);
  BOOST_TEST(f.omega_rad_s[1] == 0.0);
  BOOST_TEST(std::abs(beta_L(b, f.omega_rad_s[2]) - 4.730040745) < 1e-9 * 4.73);
  BOOST_TEST(std::abs(beta_L(b, f.omega_rad_s[3]) - 7.853204624) < 1e-9 * 7.85);
}

// High modes: the n-th pinned-pinned frequency is (n pi)^2 sqrt(EI / rhoA L^4) up to n = 100.
BOOST_AUTO_TEST_CASE(hundredth_mode_pinned) {
  const BeamBending b = eb_beam();
  const auto f = beam_bending_frequencies(b, kPinned, kPinned, 100);
  BOOST_REQUIRE(f.omega_rad_s.size() == 100u);
  const double c = std::sqrt(b.EI / (b.rhoA * std::pow(b.L, 4)));
  for (int n = 1; n <= 100; ++n) BOOST_TEST(rel(f.omega_rad_s[n - 1], std::pow(n * pi, 2) * c) < 1e-10, "mode " << n);
}

// Springs: 0 and inf are limits. Very soft springs approach free ends, very stiff ones
// clamped ends (dimensionless 1e-6 and 1e12 of EI/L^3, EI/L).
BOOST_AUTO_TEST_CASE(spring_limits) {
  const BeamBending b = eb_beam();
  const double kt = b.EI / std::pow(b.L, 3), kr = b.EI / b.L;
  const auto stiff = beam_bending_frequencies(b, {1e12 * kt, 1e12 * kr}, {1e12 * kt, 1e12 * kr}, 3);
  const auto cc = beam_bending_frequencies(b, kClamped, kClamped, 3);
  for (int i = 0; i < 3; ++i) BOOST_TEST(rel(stiff.omega_rad_s[i], cc.omega_rad_s[i]) < 1e-9);
  // Pinned with a soft rotational spring -> pinned; stiff -> clamped.
  const auto soft_r = beam_bending_frequencies(b, {inf, 1e-6 * kr}, {inf, 1e-6 * kr}, 3);
  const auto pp = beam_bending_frequencies(b, kPinned, kPinned, 3);
  for (int i = 0; i < 3; ++i) BOOST_TEST(rel(soft_r.omega_rad_s[i], pp.omega_rad_s[i]) < 1e-6);
  // Free-free on soft translational springs: two low spring-mass modes, then the elastic ones.
  const auto soft = beam_bending_frequencies(b, {1e-6 * kt, 0}, {1e-6 * kt, 0}, 4);
  BOOST_TEST(soft.rigid == 0);
  const double bounce = std::sqrt(2e-6 * kt / (b.rhoA * b.L));  // rigid bounce on two springs
  BOOST_TEST(rel(soft.omega_rad_s[0], bounce) < 1e-5);
  const auto ff = beam_bending_frequencies(b, kFree, kFree, 4);
  BOOST_TEST(rel(soft.omega_rad_s[2], ff.omega_rad_s[2]) < 1e-6);
  // A midrange spring lies strictly between the limits.
  const auto mid = beam_bending_frequencies(b, {inf, 1.0 * kr}, {inf, 1.0 * kr}, 1);
  BOOST_TEST(mid.omega_rad_s[0] > pp.omega_rad_s[0]);
  BOOST_TEST(mid.omega_rad_s[0] < cc.omega_rad_s[0]);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(statics)

// Hand-derived deflections (Roark): each to rounding.
BOOST_AUTO_TEST_CASE(classical_cases) {
  const BeamBending b = eb_beam();
  const double L = b.L, EI = b.EI, F = -1000.0, M = 250.0;
  // Cantilever, tip force: w(L) = F L^3 / 3EI, theta_y(L) = -w'(L) = -F L^2 / 2EI.
  auto r = beam_static(b, kClamped, kFree, {{L, F, 0}}, {L, L / 2}, -1.0);
  BOOST_TEST(rel(r[0].w, F * L * L * L / (3 * EI)) < 1e-12);
  BOOST_TEST(rel(r[0].theta, -F * L * L / (2 * EI)) < 1e-12);
  BOOST_TEST(rel(r[1].w, F * std::pow(L / 2, 2) * (3 * L - L / 2) / (6 * EI)) < 1e-12);
  // Cantilever, tip moment My: w = -My x^2 / 2EI, theta_y = My x / EI.
  r = beam_static(b, kClamped, kFree, {{L, 0, M}}, {L}, -1.0);
  BOOST_TEST(rel(r[0].w, -M * L * L / (2 * EI)) < 1e-12);
  BOOST_TEST(rel(r[0].theta, M * L / EI) < 1e-12);
  // Simply supported, central force: F L^3 / 48 EI.
  r = beam_static(b, kPinned, kPinned, {{L / 2, F, 0}}, {L / 2}, -1.0);
  BOOST_TEST(rel(r[0].w, F * L * L * L / (48 * EI)) < 1e-12);
  // Clamped-clamped, central force: F L^3 / 192 EI.
  r = beam_static(b, kClamped, kClamped, {{L / 2, F, 0}}, {L / 2}, -1.0);
  BOOST_TEST(rel(r[0].w, F * L * L * L / (192 * EI)) < 1e-11);
  // Propped cantilever (clamped at 0, pinned at L), central force: 7 F L^3 / 768 EI.
  r = beam_static(b, kClamped, kPinned, {{L / 2, F, 0}}, {L / 2}, -1.0);
  BOOST_TEST(rel(r[0].w, 7 * F * L * L * L / (768 * EI)) < 1e-11);
}

BOOST_AUTO_TEST_CASE(elastic_supports) {
  const BeamBending b = eb_beam();
  const double L = b.L, EI = b.EI, F = -1000.0;
  // Two translational springs k, central force: F L^3 / 48EI + F / 2k.
  const double k = 3.0 * EI / (L * L * L);
  auto r = beam_static(b, {k, 0}, {k, 0}, {{L / 2, F, 0}}, {L / 2}, -1.0);
  BOOST_TEST(rel(r[0].w, F * L * L * L / (48 * EI) + F / (2 * k)) < 1e-12);
  // Cantilever with a rotational spring kr at the root, tip force: F L^3/3EI + F L^2 / kr.
  const double kr = 2.0 * EI / L;
  r = beam_static(b, {inf, kr}, kFree, {{L, F, 0}}, {L}, -1.0);
  BOOST_TEST(rel(r[0].w, F * L * L * L / (3 * EI) + F * L * L / kr) < 1e-12);
}

BOOST_AUTO_TEST_CASE(timoshenko_shear_deflection) {
  // Cantilever tip force: F L^3 / 3EI + F L / kGA.
  const BeamBending b{1e6, 2e6, 10.0, 0.1, 1.5};
  auto r = beam_static(b, kClamped, kFree, {{b.L, 100.0, 0}}, {b.L}, -1.0);
  BOOST_TEST(rel(r[0].w, 100.0 * std::pow(b.L, 3) / (3 * b.EI) + 100.0 * b.L / b.kGA) < 1e-12);
}

BOOST_AUTO_TEST_CASE(mechanism_is_refused) {
  const BeamBending b = eb_beam();
  BOOST_CHECK_THROW(beam_static(b, kPinned, kFree, {{1.0, -1.0, 0}}, {1.0}, -1.0), std::runtime_error);
  BOOST_CHECK_THROW(beam_static(b, kGuided, kGuided, {{1.0, -1.0, 0}}, {1.0}, -1.0), std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(bars)

BOOST_AUTO_TEST_CASE(axial_and_torsion) {
  const double E = 2e11, rho = 7850, A = 1e-3, L = 3.0;
  const Bar bar{E * A, rho * A, L};
  const double c = std::sqrt(E / rho) / L;
  auto ff = bar_frequencies(bar, inf, inf, 5);   // fixed-fixed: n pi c
  auto fr = bar_frequencies(bar, inf, 0.0, 5);   // fixed-free: (2n - 1) pi / 2 c
  auto fe = bar_frequencies(bar, 0.0, 0.0, 3);   // free-free: one rigid mode, then n pi c
  for (int n = 1; n <= 5; ++n) {
    BOOST_TEST(rel(ff.omega_rad_s[n - 1], n * pi * c) < 1e-11);
    BOOST_TEST(rel(fr.omega_rad_s[n - 1], (2 * n - 1) * pi / 2 * c) < 1e-11);
  }
  BOOST_TEST(fe.rigid == 1);
  BOOST_TEST(rel(fe.omega_rad_s[1], pi * c) < 1e-11);
  // Torsion of the same form: GJ, rho Ip.
  const double G = 8e10, J = 2e-7, Ip = 3e-7;
  auto ft = bar_frequencies({G * J, rho * Ip, L}, inf, inf, 2);
  BOOST_TEST(rel(ft.omega_rad_s[0], pi * std::sqrt(G * J / (rho * Ip)) / L) < 1e-11);
  // Statics: u(L) = F L / EA for fixed-free; a spring k in series adds F / k.
  auto u = bar_static(bar, inf, 0.0, {{L, 1e4, 0}}, {L});
  BOOST_TEST(rel(u[0], 1e4 * L / (E * A)) < 1e-12);
  const double k = E * A / L;
  u = bar_static(bar, k, 0.0, {{L, 1e4, 0}}, {L});
  BOOST_TEST(rel(u[0], 1e4 * L / (E * A) + 1e4 / k) < 1e-12);
  BOOST_CHECK_THROW(bar_static(bar, 0.0, 0.0, {{L, 1.0, 0}}, {L}), std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()

// Near-rigid modes with point masses: the rigid-motion split carries each spring and mass on its
// own amplitude, also where the line has attachments. Before, an attachment sent the count to
// the plain K(lambda), whose rounding (eps of the stiff spring) was 1e-8 of the soft one's share:
// fuzz seed 7, cases 1589 (rocking on 1.1e-3 N/m about a 6.6e4 N/m end: 1.7e-8 off) and 132
// (a torsion bar with nu near -1 spinning on one 1e4 N*m spring: 4e-9 off), both as success.
BOOST_AUTO_TEST_SUITE(near_rigid_with_masses)

namespace {
/// The lowest root of f in (a, b) by bisection (f changes sign once there).
template <class F>
double bisect(F f, double a, double b) {
  double fa = f(a);
  for (int it = 0; it < 200; ++it) {
    const double c = 0.5 * (a + b), fc = f(c);
    if ((fc > 0) == (fa > 0)) a = c, fa = fc;
    else b = c;
  }
  return 0.5 * (a + b);
}

/// The transfer of (w, w', w'', w''') over x under w'''' = beta^4 w, its Krylov functions from
/// their series (beta x ~ 0.01 here: sinh - sin in closed form would cancel four digits).
Eigen::Matrix4d krylov_transfer(double beta, double x) {
  const double z = std::pow(beta * x, 4);
  double s[4];
  for (int j = 0; j < 4; ++j) {
    double term = std::pow(x, j) / std::tgamma(j + 1.0), sum = 0;
    for (int n = 1; std::abs(term) > 1e-20 * std::abs(sum) || n == 1; ++n) {
      sum += term;
      term *= z / ((4.0 * n + j - 3) * (4.0 * n + j - 2) * (4.0 * n + j - 1) * (4.0 * n + j));
    }
    s[j] = sum;
  }
  Eigen::Matrix4d T;
  T.row(0) << s[0], s[1], s[2], s[3];
  for (int r = 1; r < 4; ++r) T.row(r) << std::pow(beta, 4) * T(r - 1, 3), T(r - 1, 0), T(r - 1, 1), T(r - 1, 2);
  return T;
}
}  // namespace

BOOST_AUTO_TEST_CASE(rocking_about_a_stiff_end_with_a_tip_mass) {
  // Euler-Bernoulli, 1 m, 30 x 50 mm steel; springs k0 at x = 0, kL at x = L; a mass m with
  // rotary inertia J at x = L. Natural conditions: EI w''(0) = 0, EI w'''(0) = -k0 w(0);
  // EI w''(L) = omega^2 J w'(L), EI w'''(L) = (kL - omega^2 m) w(L).
  const double EI = 2.1e11 * 0.03 * std::pow(0.05, 3) / 12, rhoA = 7850 * 0.03 * 0.05, L = 1.0;
  const double k0 = 1.1275874600793106e-3, kL = 65625.0, m = 2.0, J = 5e-4;
  const BeamBending b{EI, inf, rhoA, 0.0, L};
  const auto f = beam_bending_frequencies(b, {k0, 0.0}, {kL, 0.0}, 2, {{L, {0.0, 0.0}, m, J}});
  auto equation = [&](double omega) {
    const double beta = std::pow(rhoA * omega * omega / EI, 0.25);
    Eigen::Matrix<double, 4, 2> s0 = Eigen::Matrix<double, 4, 2>::Zero();
    s0(0, 0) = 1.0;
    s0(1, 1) = 1.0;
    s0(3, 0) = -k0 / EI;
    const Eigen::Matrix<double, 4, 2> sL = krylov_transfer(beta, L) * s0;
    Eigen::Matrix2d R;
    R.row(0) = EI * sL.row(2) - omega * omega * J * sL.row(1);
    R.row(1) = EI * sL.row(3) - (kL - omega * omega * m) * sL.row(0);
    return R.determinant();
  };
  BOOST_REQUIRE(f.omega_rad_s.size() == 2u);
  BOOST_TEST(f.rigid == 0);
  // The rigid rocking about L, sqrt(k0 L^2 / (rhoA L^3 / 3 + J)), bounds it from above.
  const double rigid = std::sqrt(k0 * L * L / (rhoA * L * L * L / 3 + J));
  BOOST_TEST(f.omega_rad_s[0] < rigid);
  BOOST_TEST(rel(f.omega_rad_s[0], bisect(equation, 0.99 * rigid, rigid)) < 1e-10);
}

BOOST_AUTO_TEST_CASE(torsion_bar_spinning_on_one_spring) {
  // GJ theta'' + rho Ip omega^2 theta = 0; free at 0, a spring kt at L, a disc of inertia Jd at
  // L / 2. GJ is 1e7 times kt L: the mode is nearly the rigid sqrt(kt / (rho Ip L + Jd)).
  const double GJ = 1.3e11, mu = 5.2e-3, L = 1.0, kt = 1e4, Jd = 0.06165;
  const auto f = bar_frequencies({GJ, mu, L}, 0.0, kt, 1, {{0.5, {0.0, 0.0}, Jd, 0.0}});
  auto equation = [&](double omega) {
    const double k = omega * std::sqrt(mu / GJ);
    auto transfer = [&](double x) {
      Eigen::Matrix2d T;
      T << std::cos(k * x), std::sin(k * x) / (GJ * k), -GJ * k * std::sin(k * x), std::cos(k * x);
      return T;
    };
    Eigen::Matrix2d jump = Eigen::Matrix2d::Identity();
    jump(1, 0) = -Jd * omega * omega;
    const Eigen::Vector2d s = transfer(L / 2) * jump * transfer(L / 2) * Eigen::Vector2d(1.0, 0.0);
    return s[1] + kt * s[0];
  };
  const double rigid = std::sqrt(kt / (mu * L + Jd));
  BOOST_REQUIRE(f.omega_rad_s.size() == 1u);
  BOOST_TEST(f.omega_rad_s[0] < rigid);
  BOOST_TEST(rel(f.omega_rad_s[0], bisect(equation, 0.999 * rigid, rigid)) < 1e-10);
}

BOOST_AUTO_TEST_SUITE_END()
