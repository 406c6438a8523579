// Exact plate references against published values: the prism paper's Table 2 (docs/sources.md, P2),
// Leissa (1973) "The free vibration of rectangular plates", J. Sound Vib. 31(3), Tables for
// a/b = 1, nu = 0.3, and Mindlin's thick plate (Srinivas et al. 1970: 0.0930).
#define BOOST_TEST_MODULE exact_plate
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "modalbench/exact/exact.hpp"

using namespace modalbench::exact;

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
const EndSprings kSS{inf, 0}, kC{inf, inf}, kF{0, 0};
constexpr double E = 2e11, nu = 0.3, rho = 8000;
double D_of(double h) { return E * h * h * h / (12 * (1 - nu * nu)); }
}  // namespace

// Table 2, "Exact frequency (57)": nu = 0.3, rho = 8000 (P2). The printed integers are
// the computed values truncated (5425.80 is printed 5425, 9009.81 is printed 9009).
BOOST_AUTO_TEST_CASE(paper_table2_exact_column) {
  const double h = 0.03;
  const double printed[] = {1692, 3036, 5276, 5425, 6769, 8412, 9009, 11648};
  const auto w = navier_frequencies(1.0, 0.6, D_of(h), rho * h, 8);
  for (int i = 0; i < 8; ++i) {
    BOOST_TEST_MESSAGE("mode " << i + 1 << ": " << w[i] << " rad/s, printed " << printed[i]);
    BOOST_TEST((w[i] >= printed[i] && w[i] < printed[i] + 1), "mode " << i + 1 << ": " << w[i]);
  }
}

// Levy plates (x-edges simply supported), square, lambda = omega a^2 sqrt(rho h / D).
BOOST_AUTO_TEST_CASE(levy_against_leissa) {
  const double a = 1.0, h = 0.01, D = D_of(h), rh = rho * h;
  struct Case { const char* name; EndSprings y0, yb; std::vector<double> lambda; };
  const Case cases[] = {
      {"SCSC", kC, kC, {28.951, 54.743, 69.327, 94.585, 102.22, 129.10}},
      {"SFSF", kF, kF, {9.6314, 16.135, 36.726, 38.945, 46.738, 70.740}},
      {"SCSS", kC, kSS, {23.646, 51.674, 58.646, 86.135, 100.27, 113.23}},
      {"SCSF", kC, kF, {12.687, 33.065, 41.702, 63.015, 72.398, 90.612}},
      {"SSSF", kSS, kF, {11.684, 27.756, 41.197, 59.066, 61.861, 90.294}},
  };
  for (const auto& c : cases) {
    const auto f = levy_frequencies(a, a, D, nu, rh, c.y0, c.yb, 6);
    for (int i = 0; i < 6; ++i) {
      const double lam = f.omega_rad_s[i] * a * a * std::sqrt(rh / D);
      // Leissa prints 5 significant digits.
      BOOST_TEST(std::abs(lam - c.lambda[i]) <= 0.6e-4 * c.lambda[i], c.name << " mode " << i + 1 << ": " << lam);
    }
  }
}

// The Levy path with simply supported y-edges is the Navier plate, repeated roots included.
BOOST_AUTO_TEST_CASE(levy_equals_navier_when_all_simply_supported) {
  const double h = 0.02, D = D_of(h), rh = rho * h;
  for (double b : {0.6, 1.0}) {
    const auto levy = levy_frequencies(1.0, b, D, nu, rh, kSS, kSS, 12);
    const auto nav = navier_frequencies(1.0, b, D, rh, 12);
    for (int i = 0; i < 12; ++i)
      BOOST_TEST(std::abs(levy.omega_rad_s[i] / nav[i] - 1) < 1e-10, "b = " << b << " mode " << i + 1);
  }
}

// Mindlin, simply supported square plate, h/a = 0.1, kappa = pi^2/12: the fundamental
// omega h sqrt(rho/G) = 0.0930; a very thin plate approaches Kirchhoff.
BOOST_AUTO_TEST_CASE(mindlin_thick_and_thin) {
  const double G = E / (2 * (1 + nu)), kappa = std::numbers::pi * std::numbers::pi / 12;
  auto thick = mindlin_ss_frequencies(1, 1, 0.1, E, nu, G, kappa, rho, 3);
  BOOST_TEST(std::abs(thick[0] * 0.1 * std::sqrt(rho / G) - 0.0930) < 0.00005);
  BOOST_TEST(thick[1] == thick[2], boost::test_tools::tolerance(1e-12));  // (1,2) and (2,1)
  const double h = 1e-3;
  auto thin = mindlin_ss_frequencies(1, 0.6, h, E, nu, G, 5.0 / 6.0, rho, 8);
  auto kir = navier_frequencies(1, 0.6, D_of(h), rho * h, 8);
  for (int i = 0; i < 8; ++i) {
    BOOST_TEST(thin[i] < kir[i]);  // shear and rotary inertia only soften
    BOOST_TEST(thin[i] / kir[i] - 1 > -1e-4);
  }
}

// A very thick plate: its thickness-shear modes (w = 0) enter the list in order. Below the
// lowest pure-shear frequency sqrt((kGh + D (1-nu)/2 (pi/a)^2) / (rho h^3/12)) every mode is
// a flexural-branch mode; the list stays sorted and includes that shear mode.
BOOST_AUTO_TEST_CASE(mindlin_thickness_shear_modes_listed) {
  const double G = E / (2 * (1 + nu)), kappa = 5.0 / 6.0, h = 0.5, a = 1.0;
  const auto w = mindlin_ss_frequencies(a, a, h, E, nu, G, kappa, rho, 30);
  const double D = D_of(h), shear = std::sqrt((kappa * G * h + D * (1 - nu) / 2 * std::pow(std::numbers::pi / a, 2)) /
                                              (rho * h * h * h / 12));
  BOOST_TEST(std::is_sorted(w.begin(), w.end()));
  int found = 0;
  for (double x : w) found += std::abs(x / shear - 1) < 1e-12;
  BOOST_TEST(found == 2);  // (m, n) = (0, 1) and (1, 0) on a square plate
}

// A simply supported plate with a central force P deflects w = alpha P a^2 / D at the centre
// (a the shorter side). Square: alpha = 0.01160 (Timoshenko & Woinowsky-Krieger, Table 23).
// Rectangles: the independent Levy single series (TWK Eq. 146),
//   alpha = 1 / (2 pi^3) sum_{m odd} (tanh b_m - b_m / cosh^2 b_m) / m^3,  b_m = m pi b / (2 a).
BOOST_AUTO_TEST_CASE(navier_static_central_force) {
  const double D = D_of(0.01), P = -1000.0, pi = std::numbers::pi;
  auto levy_alpha = [&](double ratio) {
    double sum = 0;
    for (int m = 1; m < 20000; m += 2) {
      const double bm = m * pi * ratio / 2;
      sum += (bm < 300 ? std::tanh(bm) - bm / std::pow(std::cosh(bm), 2) : 1.0) / std::pow(m, 3);
    }
    return sum / (2 * pi * pi * pi);
  };
  BOOST_TEST(std::abs(levy_alpha(1.0) - 0.01160) < 0.000005);
  for (double ratio : {1.0, 1.4, 2.0}) {
    const double a = 1.0, b = ratio * a;
    double tail = 0;
    const auto w = navier_static(a, b, D, {{a / 2, b / 2, P}}, a / 2, b / 2, 2000, &tail);
    BOOST_TEST(std::abs(w[0] / (levy_alpha(ratio) * P * a * a / D) - 1) < 2e-6, "b/a = " << ratio << ": " << w[0] * D / (P * a * a));
    BOOST_TEST(tail < 1e-5 * std::abs(w[0]));
    BOOST_TEST(std::abs(w[1]) < 1e-9 * std::abs(w[0]));  // the centre is a stationary point
  }
}

// Maxwell reciprocity, the static limit of the receptance, and a resonance: near omega_11 the
// receptance is dominated by the (1,1) term.
BOOST_AUTO_TEST_CASE(navier_receptance_properties) {
  const double a = 1.0, b = 0.6, h = 0.03, D = D_of(h), rh = rho * h;
  const auto h12 = navier_receptance(a, b, D, rh, 0.0, 0.4, 0.2, 0.7, 0.45, 1000.0, 300);
  const auto h21 = navier_receptance(a, b, D, rh, 0.0, 0.7, 0.45, 0.4, 0.2, 1000.0, 300);
  BOOST_TEST(std::abs(h12 - h21) < 1e-14 * std::abs(h12));
  const auto w = navier_static(a, b, D, {{0.4, 0.2, 1.0}}, 0.7, 0.45, 300);
  const auto h0 = navier_receptance(a, b, D, rh, 0.0, 0.4, 0.2, 0.7, 0.45, 0.0, 300);
  BOOST_TEST(std::abs(h0.real() / w[0] - 1) < 1e-12);
  const double w11 = navier_frequencies(a, b, D, rh, 1)[0], eta = 0.01;
  const auto hr = navier_receptance(a, b, D, rh, eta, 0.4, 0.2, 0.4, 0.2, w11, 300);
  const double phi = std::sin(std::numbers::pi * 0.4 / a) * std::sin(std::numbers::pi * 0.2 / b);
  const double modal = phi * phi / (rh * a * b / 4 * w11 * w11 * eta);  // |1 / (M w^2 i eta)|
  BOOST_TEST(std::abs(std::abs(hr) / modal - 1) < 1e-2);
  BOOST_TEST(hr.imag() < 0);  // the response lags the force
}

// Reactions of the simply supported plate (navier_reactions) against closed forms:
//  - an edge's resultant as a hard support (its effective shear plus half of each corner force at
//    its ends) is the integral of the transverse shear Q_x along it; from Navier's series, summed
//    over m with sum_{m odd} 1 / (m^2 + c^2) = pi tanh(pi c / 2) / (4 c), under a uniform p:
//      int_0^b Q_x(0, y) dy = (8 p b^2 / pi^3) sum_{n odd} tanh(n pi a / (2 b)) / n^3
//    (a single series with a 1/n^3 tail, summed here to 2e5 terms);
//  - the corner force of a square plate under uniform p: 0.065 p a^2 (Timoshenko &
//    Woinowsky-Krieger, Table 8, nu = 0.3, three digits);
//  - equilibrium of forces and moments under a patch and a point force.
BOOST_AUTO_TEST_CASE(navier_reactions_against_closed_forms) {
  const double h = 0.01, D = D_of(h), p = -1000.0;
  auto edge_shear = [&](double a, double b) {
    double s = 0;
    for (int n = 199999; n >= 1; n -= 2) s += std::tanh(n * std::numbers::pi * a / (2 * b)) / std::pow(n, 3);
    return -8 * p * b * b / std::pow(std::numbers::pi, 3) * s;  // the support's force on the plate, +z
  };
  for (double b : {0.8, 1.0, 2.5}) {
    const double a = 1.0;
    const NavierReactions r = navier_reactions(a, b, D, nu, {}, {{0, a, 0, b, p}}, 1e-11);
    BOOST_TEST_MESSAGE("b = " << b << ": " << r.terms << " terms, tail " << r.tail_relative);
    BOOST_TEST(r.tail_relative <= 1e-11);
    const double x0 = r.edge_force[0] + (r.corner[0] + r.corner[2]) / 2;
    const double y0 = r.edge_force[2] + (r.corner[0] + r.corner[1]) / 2;
    BOOST_TEST(std::abs(x0 - edge_shear(a, b)) <= 1e-9 * std::abs(p * a * b), "b = " << b << ": x0 " << x0);
    BOOST_TEST(std::abs(y0 - edge_shear(b, a)) <= 1e-9 * std::abs(p * a * b), "b = " << b << ": y0 " << y0);
    if (b == 1.0)
      for (double c : r.corner) BOOST_TEST(std::abs(c / (p * a * a) - 0.065) <= 0.0005, "corner " << c);
  }
  // A patch and a point force on a 1 x 0.6 plate: forces and moments about both axes balance.
  const double a = 1.0, b = 0.6;
  const std::vector<std::array<double, 3>> forces = {{0.3, 0.45, -250.0}};
  const std::vector<PressurePatch> patches = {{0.5, 0.9, 0.1, 0.3, -4000.0}};
  const NavierReactions r = navier_reactions(a, b, D, nu, forces, patches, 1e-11);
  const std::array<std::array<double, 2>, 4> mid = {{{0, b / 2}, {a, b / 2}, {a / 2, 0}, {a / 2, b}}};
  const std::array<std::array<double, 2>, 4> corner = {{{0, 0}, {a, 0}, {0, b}, {a, b}}};
  double fz = -250.0 - 4000.0 * 0.4 * 0.2, mx = 0.45 * -250.0 + 0.2 * -320.0, my = -(0.3 * -250.0 + 0.7 * -320.0);
  for (int k = 0; k < 4; ++k) {
    fz += r.edge_force[k] + r.corner[k];
    // Moments about the origin: M_x = y F, M_y = -x F; the x-edges' first moments are along y.
    const double first = r.edge_first_moment[k];
    mx += mid[k][1] * r.edge_force[k] + (k < 2 ? first : 0.0) + corner[k][1] * r.corner[k];
    my -= mid[k][0] * r.edge_force[k] + (k < 2 ? 0.0 : first) + corner[k][0] * r.corner[k];
  }
  BOOST_TEST(std::abs(fz) <= 1e-10 * 570.0);
  BOOST_TEST(std::abs(mx) <= 1e-10 * 570.0 * a);
  BOOST_TEST(std::abs(my) <= 1e-10 * 570.0 * a);
}
