// Tapered pieces ([[segments]] with a dimension as [start, end]) against references written out
// here in extended precision (long double), independently of the code:
//   - a clamped-clamped Euler-Bernoulli beam whose width falls as b0 e^(-g x) (Code_Aster SDLL10):
//     A and I both go as e^(-g x), and w = e^(g x / 2) (c1 cosh Rx + c2 sinh Rx + c3 cos Sx + c4 sin Sx),
//     R = sqrt(g^2/4 + k^2), S = sqrt(k^2 - g^2/4), k^4 = rho A0 w^2 / (E I0); clamped ends make
//     its 4 x 4 determinant vanish;
//   - a tapered cantilever's tip deflection under a tip load, P int_0^L (L - x)^2 / EI(x) dx (the
//     unit-load integral of M^2 / EI), by composite Simpson in long double;
//   - under gravity the clamp carries the piece's weight, rho g int A dx in closed form;
//   - a staircase of n uniform pieces (each with the section at its middle) tends to the taper at
//     second order in 1 / n;
//   - a truncated cone cantilever: w = xi^-1 (c1 J2 + c2 Y2 + c3 I2 + c4 K2)(2 beta sqrt(xi)), its
//     four end conditions' determinant in long double (libstdc++'s Bessel functions).
// rfem is held to its own error estimate and its observed order (2, as on uniform beams).
#define BOOST_TEST_MODULE tapered
#include <boost/test/unit_test.hpp>

#include <Eigen/Dense>
#include <fmt/format.h>
#include <cmath>
#include <string>
#include <vector>

#include "solver_tests.hpp"
#include "solve_options.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

using ld = long double;
constexpr ld kPiL = 3.141592653589793238462643383279502884L;
constexpr double E = 2.0e11, rho = 7800.0;

std::string beam(const std::string& theory, const std::string& pieces, const std::string& supports,
                 const std::string& extra, int modes) {
  return "[scene]\nname = \"tapered\"\nkind = \"beam\"\nphysics = \"bending\"\ntheory = \"" + theory +
         "\"\n[geometry]\nlength = 0.6\n" + pieces + "\n[material]\nE = 2.0e11\nnu = 0.3\nrho = 7800.0\n[supports]\n" +
         supports + "\n" + extra + "\n[request]\nmodes = " + std::to_string(modes) + "\n";
}

std::string piece(double length, const std::string& section, const std::string& profile = "") {
  return "[[segments]]\nlength = " + std::to_string(length) + "\nsection = " + section + "\n" +
         (profile.empty() ? "" : "profile = \"" + profile + "\"\n");
}

// SDLL10: L = 0.6 m, h = 0.01 m, b = 0.03 e^(-2 x) m.
constexpr double kL = 0.6, kH = 0.01, kB0 = 0.03, kGamma = 2.0;
const std::string kSdll10 = piece(kL, fmt::format("{{ shape = \"rectangle\", width = [0.03, {:.17g}], height = 0.01 }}",
                                              kB0 * std::exp(-kGamma * kL)),
                                  "exponential");

/// The 4 x 4 determinant of the clamped-clamped exponential beam at k (scaled by 1 / cosh(R L)).
ld sdll10_determinant(ld k) {
  const ld g = kGamma, L = kL, R = std::sqrt(g * g / 4 + k * k), S = std::sqrt(k * k - g * g / 4);
  const ld c = std::cosh(R * L), sh = std::sinh(R * L);
  Eigen::Matrix<ld, 4, 4> m;
  m << 1, 0, 1, 0, 0, R, 0, S, c / c, sh / c, std::cos(S * L) / c, std::sin(S * L) / c, R * sh / c, R * c / c,
      -S * std::sin(S * L) / c, S * std::cos(S * L) / c;
  return m.determinant();
}

/// The first `count` natural frequencies (rad/s) of SDLL10 as Euler-Bernoulli: the determinant's
/// sign changes on a fine grid of k, then bisection in long double.
std::vector<ld> sdll10_frequencies(int count) {
  std::vector<ld> out;
  const ld c = std::sqrt(static_cast<ld>(E) / (12 * static_cast<ld>(rho))) * kH;  // omega = c k^2
  ld lo = kGamma / 2 + 1e-3L, flo = sdll10_determinant(lo);
  for (ld hi = lo + 1e-3L; static_cast<int>(out.size()) < count && hi < 100; hi += 1e-3L) {
    const ld fhi = sdll10_determinant(hi);
    if ((flo < 0) != (fhi < 0)) {
      ld a = lo, b = hi, fa = flo;
      for (int i = 0; i < 200 && b - a > 1e-18L * b; ++i) {
        const ld m = (a + b) / 2, fm = sdll10_determinant(m);
        ((fa < 0) == (fm < 0) ? a : b) = m;
        if ((fa < 0) == (fm < 0)) fa = fm;
      }
      out.push_back(c * a * a);
    }
    lo = hi;
    flo = fhi;
  }
  return out;
}

Result rfem_on(const Scene& s, int n) { return registry().get("rfem").solve(s, Discretization{{n}}, Options{}); }

/// Relative errors per mesh (rows, each halving the one before) and mode: the last halving divides
/// every mode's error by 4 (order 2 within 0.1).
void expect_order_two(const std::vector<std::vector<double>>& err) {
  const std::size_t last = err.size() - 1;
  for (std::size_t i = 0; i < err[last].size(); ++i) {
    const double order = std::log2(err[last - 1][i] / err[last][i]);
    BOOST_TEST_INFO("mode " << i + 1 << ": errors " << err[last - 1][i] << ", " << err[last][i] << "; observed order "
                            << order);
    BOOST_TEST(std::abs(order - 2.0) < 0.1);
  }
}

// A truncated cone, clamped where it is D0 across and free where D1 < D0, as Euler-Bernoulli: with
// xi the distance from the cone's apex (D = a xi), A ~ xi^2 and I ~ xi^4, and (xi^4 w'')'' =
// beta^4 xi^2 w (beta^4 = 16 rho omega^2 / (E a^2)) factors into xi w'' + 3 w' -+ beta^2 w = 0:
// w = xi^-1 Z_2(z), z = 2 beta sqrt(xi), Z = J, Y, I, K (Conway, Becker & Dubil 1964). With
// g_n = z^-n Z_n(z), d/dxi g_n = -+ 2 beta^2 g_(n+1) (+ for I), so the k-th derivative of each
// basis function is s^k (2 beta^2)^k z^-(2+k) Z_(2+k)(z), s = -1 but for I.
constexpr double kD0 = 0.05, kD1 = 0.03;

/// The k-th xi-derivative of basis function j (0 J, 1 Y, 2 I, 3 K) at z, without the factors
/// common to a row ((2 beta^2)^k) or to a column.
ld cone_basis(int j, int k, ld z, int order = 2) {
  const ld n = order + k, p = std::pow(z, -n);
  switch (j) {
    case 0: return (k % 2 ? -1 : 1) * p * std::cyl_bessel_j(n, z);
    case 1: return (k % 2 ? -1 : 1) * p * std::cyl_neumann(n, z);
    case 2: return p * std::cyl_bessel_i(n, z);
    default: return (k % 2 ? -1 : 1) * p * std::cyl_bessel_k(n, z);
  }
}

/// The clamped-free cone's determinant at omega: w = w' = 0 at the clamp (xi_c); at the tip (xi_t)
/// no moment and no shear, w'' = 0 and (xi^4 w'')' = 0, so the third derivative vanishes too. The
/// columns of I and K are scaled by e^-z_c and e^z_t (their growth and decay).
ld cone_determinant(ld omega) {
  const ld a = (kD0 - kD1) / kL, xc = kD0 / a, xt = kD1 / a;
  const ld beta = std::pow(16 * rho * omega * omega / (E * a * a), 0.25L);
  const ld zc = 2 * beta * std::sqrt(xc), zt = 2 * beta * std::sqrt(xt);
  Eigen::Matrix<ld, 4, 4> m;
  const ld zs[4] = {zc, zc, zt, zt};
  for (int r = 0; r < 4; ++r)
    for (int j = 0; j < 4; ++j)
      m(r, j) = cone_basis(j, r, zs[r]) * (j == 2 ? std::exp(-zc) : j == 3 ? std::exp(zt) : 1);
  return m.determinant();
}

// A wedge: a rectangle whose height (in the bending plane) falls linearly from kD0 to kD1 at a
// constant width, so that with xi from the apex A ~ xi and I ~ xi^3, and (xi^3 w'')'' =
// beta^4 xi w (beta^4 = 12 rho omega^2 / (E a^2), h = a xi) factors as (xi D^2 + 2 D)^2 w =
// beta^4 w: w = xi^(-1/2) Z_1(2 beta sqrt(xi)) (Cranch & Adler 1956), the cone's basis one order
// lower, with the same clamped and free end conditions.
ld wedge_determinant(ld omega) {
  const ld a = (kD0 - kD1) / kL, xc = kD0 / a, xt = kD1 / a;
  const ld beta = std::pow(12 * rho * omega * omega / (E * a * a), 0.25L);
  const ld zc = 2 * beta * std::sqrt(xc), zt = 2 * beta * std::sqrt(xt);
  Eigen::Matrix<ld, 4, 4> m;
  const ld zs[4] = {zc, zc, zt, zt};
  for (int r = 0; r < 4; ++r)
    for (int j = 0; j < 4; ++j)
      m(r, j) = cone_basis(j, r, zs[r], 1) * (j == 2 ? std::exp(-zc) : j == 3 ? std::exp(zt) : 1);
  return m.determinant();
}

/// The first `count` roots (rad/s) of a determinant: sign changes on a grid 0.1 % apart, then
/// bisection in long double.
std::vector<ld> roots_of(ld (*determinant)(ld), int count) {
  std::vector<ld> out;
  ld lo = 10, flo = determinant(lo);
  for (ld hi = lo * 1.001L; static_cast<int>(out.size()) < count && hi < 1e6; hi *= 1.001L) {
    const ld fhi = determinant(hi);
    if ((flo < 0) != (fhi < 0)) {
      ld x0 = lo, x1 = hi, f0 = flo;
      for (int i = 0; i < 200 && x1 - x0 > 1e-17L * x1; ++i) {
        const ld xm = (x0 + x1) / 2, fm = determinant(xm);
        if ((f0 < 0) == (fm < 0)) x0 = xm, f0 = fm;
        else x1 = xm;
      }
      out.push_back(x0);
    }
    lo = hi;
    flo = fhi;
  }
  return out;
}
std::vector<ld> cone_frequencies(int count) { return roots_of(cone_determinant, count); }
std::vector<ld> wedge_frequencies(int count) { return roots_of(wedge_determinant, count); }

/// exact's frequencies against a closed form's: its Magnus transfer matrices are estimated to
/// 1e-15 and its count's bisection stops at 1e-13; 1e-11 leaves the determinant's own rounding
/// (long double bisection to 1e-17) far below.
void expect_exact(const Scene& s, const std::vector<ld>& ref) {
  const Result r = registry().get("exact").solve_default(s, Options{});
  BOOST_TEST_CONTEXT("exact: " << r.summary.message) {
    BOOST_REQUIRE(r.summary.status == Status::Success);
    BOOST_REQUIRE_GE(r.frequencies_rad_s.size(), ref.size());
    for (std::size_t i = 0; i < ref.size(); ++i) {
      BOOST_TEST_INFO("mode " << i + 1 << ": " << r.frequencies_rad_s[i] << " against " << static_cast<double>(ref[i]));
      BOOST_TEST(rel(r.frequencies_rad_s[i], static_cast<double>(ref[i])) < 1e-11);
    }
  }
}

/// Every Campbell point's roots of `got` within `bound` of `ref`'s (relative to |ref| + spin), and
/// its first forward critical speed.
void expect_campbell_within(const Result& got, const Result& ref, double bound) {
  BOOST_REQUIRE_EQUAL(got.campbell.points.size(), ref.campbell.points.size());
  for (std::size_t p = 0; p < ref.campbell.points.size(); ++p) {
    const auto &a = got.campbell.points[p], &b = ref.campbell.points[p];
    BOOST_REQUIRE_EQUAL(a.frequencies_rad_s.size(), b.frequencies_rad_s.size());
    for (std::size_t i = 0; i < a.frequencies_rad_s.size(); ++i) {
      BOOST_TEST_INFO("spin " << b.spin_rad_s << " root " << i << ": " << a.frequencies_rad_s[i] << " against "
                              << b.frequencies_rad_s[i]);
      BOOST_TEST(std::abs(a.frequencies_rad_s[i] - b.frequencies_rad_s[i]) / (std::abs(b.frequencies_rad_s[i]) + b.spin_rad_s) <=
                 bound);
    }
  }
  BOOST_REQUIRE(!got.campbell.forward_criticals.empty());
  BOOST_REQUIRE(!ref.campbell.forward_criticals.empty());
  BOOST_TEST(rel(got.campbell.forward_criticals[0], ref.campbell.forward_criticals[0]) <= bound);
}

}  // namespace

BOOST_AUTO_TEST_CASE(sections_vary_by_their_profile) {
  const std::string rect = piece(0.4, "{ shape = \"rectangle\", width = [0.04, 0.01], height = [0.05, 0.02] }");
  const std::string tube =
      piece(0.2, "{ shape = \"tube\", outer_diameter = [0.1, 0.06], inner_diameter = 0.04 }", "exponential");
  const Scene s = parse_scene(beam("euler-bernoulli", rect + tube, "x0 = \"clamped\"\nxL = \"free\"", "", 2), "t.toml");
  BOOST_REQUIRE_EQUAL(s.segments.size(), 2u);
  BOOST_TEST(s.has_tapered_pieces());
  const Segment &r = s.segments[0], &t = s.segments[1];
  BOOST_TEST(r.tapered());
  BOOST_TEST(to_string(r.end->profile) == "linear");
  // Linear: at the middle the sides are the means; Iy = b h^3 / 12.
  const Section mid = r.properties_at(0.2);
  BOOST_TEST(rel(mid.A, 0.025 * 0.035) < 1e-15);
  BOOST_TEST(rel(mid.Iy, 0.025 * std::pow(0.035, 3) / 12) < 1e-14);
  BOOST_TEST(rel(r.properties_at(0.4).Iz, 0.02 * std::pow(0.01, 3) / 12) < 1e-14);
  // Exponential: the geometric mean at the middle; the bore stays; Cowper's kappa follows d / D.
  const double D = std::sqrt(0.1 * 0.06), d = 0.04, pi = 3.14159265358979323846;
  BOOST_TEST(rel(t.properties_at(0.5).A, pi * (D * D - d * d) / 4) < 1e-14);
  BOOST_TEST(rel(t.properties_at(0.6).Iy, pi * (std::pow(0.06, 4) - std::pow(d, 4)) / 64) < 1e-14);
  BOOST_TEST(t.kappa_follows_shape);
  BOOST_TEST(rel(t.kappa_at(0.4), cowper_kappa_tube(0.3, 0.4)) < 1e-15);
  BOOST_TEST(rel(t.kappa_at(0.6), cowper_kappa_tube(0.3, d / 0.06)) < 1e-15);
  BOOST_TEST(s.geometry.height == 0.1);  // the largest extent
  BOOST_CHECK_THROW(r.properties(), std::logic_error);  // a tapered piece has no one section
}

BOOST_AUTO_TEST_CASE(bad_tapers_are_named_by_key_and_reason) {
  const std::string sup = "x0 = \"clamped\"\nxL = \"free\"";
  auto bad = [&](const std::string& pieces, const std::string& key, const std::string& reason) {
    expect_input_error(beam("euler-bernoulli", pieces, sup, "", 2), key, reason);
  };
  bad(piece(0.6, "{ shape = \"rectangle\", width = [0.03, 0.0], height = 0.01 }"), "segments[0].section.width[1]",
      "reach zero or below inside the piece");
  bad(piece(0.6, "{ shape = \"rectangle\", width = [0.03, -0.01], height = 0.01 }", "exponential"),
      "segments[0].section.width[1]", "must be > 0");
  bad(piece(0.6, "{ shape = \"tube\", outer_diameter = [0.06, 0.04], inner_diameter = [0.02, 0.05] }"),
      "segments[0].section.inner_diameter", "reach the outside inside the piece");
  bad(piece(0.6, "{ shape = \"circle\", diameter = 0.05 }", "linear"), "segments[0].profile",
      "no dimension of the section varies");
  bad(piece(0.6, "{ shape = \"circle\", diameter = [0.05, 0.05] }", "exponential"), "segments[0].profile",
      "no dimension of the section varies");
  bad(piece(0.6, "{ shape = \"circle\", diameter = [0.05, 0.03] }", "cubic"), "segments[0].profile",
      "unknown profile");
  bad(piece(0.6, "{ shape = \"circle\", diameter = [0.05, 0.03, 0.01] }"), "segments[0].section.diameter",
      "[start, end]");
  expect_input_error(
      "[scene]\nname = \"u\"\nkind = \"beam\"\nphysics = \"bending\"\ntheory = \"euler-bernoulli\"\n[geometry]\n"
      "length = 1.0\nsection = { shape = \"circle\", diameter = [0.05, 0.03] }\n[material]\nE = 2.0e11\nnu = 0.3\n"
      "rho = 7800.0\n[supports]\nx0 = \"clamped\"\nxL = \"free\"\n[request]\nmodes = 2\n",
      "geometry.section.diameter", "in [[segments]]");
}

BOOST_AUTO_TEST_CASE(exponential_clamped_beam_against_its_frequency_equation) {
  const int k = 4;
  const std::vector<ld> ref = sdll10_frequencies(k);
  BOOST_REQUIRE_EQUAL(ref.size(), static_cast<std::size_t>(k));
  // SDLL10's corrected values (its published 143.303 Hz ... solve a frequency equation with R and S
  // exchanged; docs/sources.md): 145.877, 400.295, 783.232, 1293.572 Hz.
  BOOST_TEST(std::abs(static_cast<double>(ref[0]) / (2 * 3.14159265358979323846) - 145.877) < 1e-3);
  const Scene s = parse_scene(beam("euler-bernoulli", kSdll10, "x0 = \"clamped\"\nxL = \"clamped\"", "", k) +
                                  "tolerance = 1e-6\n",
                              "sdll10.toml");
  Scene coarse = s;  // the ladder's coarse meshes judged against a loose tolerance
  coarse.request.tolerance = 0.5;
  std::vector<std::vector<double>> err;
  for (int n : {32, 64, 128, 256}) {
    const Result r = rfem_on(coarse, n);
    BOOST_REQUIRE(r.summary.status == Status::Success);
    err.emplace_back();
    for (int i = 0; i < k; ++i) err.back().push_back(rel(r.frequencies_rad_s[i], static_cast<double>(ref[i])));
  }
  // Second order: each halving divides the error by 4 (the next term, h^4, is 1 % of it by 64).
  expect_order_two(err);
  // The default solve's reported (extrapolated) values within their estimate of the closed form.
  const Result d = registry().get("rfem").solve_default(s, Options{});
  BOOST_REQUIRE(d.summary.status == Status::Success);
  for (int i = 0; i < k; ++i)
    BOOST_TEST(rel(d.frequencies_rad_s[i], static_cast<double>(ref[i])) <= d.summary.error_estimate.frequencies);
}

BOOST_AUTO_TEST_CASE(tapered_cantilever_tip_deflection_and_weight) {
  // A cone 0.6 m long, 50 mm across at the clamp and 30 mm at the tip, tip load P.
  const ld D0 = 0.05L, D1 = 0.03L, L = kL, P = 1000;
  auto I = [&](ld x) { const ld D = D0 + (D1 - D0) * x / L; return kPiL * D * D * D * D / 64; };
  const int n = 20000;  // Simpson: error ~ (L / n)^4 f'''' / 180, far below double's rounding
  ld sum = 0;
  for (int i = 0; i <= n; ++i) {
    const ld x = L * i / n, f = (L - x) * (L - x) / (E * I(x));
    sum += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
  }
  const double tip = static_cast<double>(-P * sum * L / (3 * n));
  const std::string cone = piece(kL, "{ shape = \"circle\", diameter = [0.05, 0.03] }");
  const Scene s = parse_scene(beam("euler-bernoulli", cone, "x0 = \"clamped\"\nxL = \"free\"",
                                   "[[loads]]\nx = 0.6\nFz = -1000.0\n[gravity]\ng = [0.0, 0.0, -9.81]", 2) +
                                  "probes = [0.6]\ntolerance = 0.5\n",
                              "cone.toml");
  // The weight: rho g pi / 4 L (D0^2 + D0 D1 + D1^2) / 3.
  const double weight = static_cast<double>(rho * 9.81L * kPiL / 4 * L * (D0 * D0 + D0 * D1 + D1 * D1) / 3);
  // Its own tip deflection (unit load at the tip against the weight's moment): int m(x) M_w(x) / EI.
  ld own = 0;
  auto A = [&](ld x) { const ld D = D0 + (D1 - D0) * x / L; return kPiL * D * D / 4; };
  auto Mw = [&](ld x) {  // moment at x of the weight beyond it, int_x^L rho g A(t) (t - x) dt, by Simpson
    const int m = 2000;
    ld acc = 0;
    for (int i = 0; i <= m; ++i) {
      const ld t = x + (L - x) * i / m;
      acc += rho * 9.81L * A(t) * (t - x) * (i == 0 || i == m ? 1 : i % 2 ? 4 : 2);
    }
    return acc * (L - x) / (3 * m);
  };
  for (int i = 0; i <= 2000; ++i) {
    const ld x = L * i / 2000;
    own += (L - x) * Mw(x) / (E * I(x)) * (i == 0 || i == 2000 ? 1 : i % 2 ? 4 : 2);
  }
  const double total = tip - static_cast<double>(own * L / (3 * 2000));
  std::vector<double> err;
  for (int m : {40, 80, 160}) {
    const Result r = rfem_on(s, m);
    BOOST_TEST_CONTEXT("rfem " << m << ": " << r.summary.message) {
      BOOST_REQUIRE(r.summary.status == Status::Success);
      BOOST_REQUIRE_EQUAL(r.deflections.size(), 1u);
      err.push_back(rel(r.deflections[0].w, total));
      // The clamp carries the load and the weight (to the balance's rounding).
      BOOST_REQUIRE_EQUAL(r.reactions.size(), 1u);
      BOOST_TEST(rel(r.reactions[0].force[2], 1000.0 + weight) < 1e-10);
    }
  }
  BOOST_TEST_INFO("tip deflection errors " << err[0] << ", " << err[1] << ", " << err[2]);
  BOOST_TEST(std::abs(std::log2(err[1] / err[2]) - 2.0) < 0.15);
  // exact: the Magnus transfer of the tapered piece and the weight's Gauss points on its segments
  // give the integrals to about 1e-13 (the references' Simpson rules to about 1e-14); the reaction
  // is a residual of K d at the clamp, whose rounding scales with the segments' stiffness (1e-10,
  // as rfem's above).
  const Result e = registry().get("exact").solve_default(s, Options{});
  BOOST_TEST_CONTEXT("exact: " << e.summary.message) {
    BOOST_REQUIRE(e.summary.status == Status::Success);
    BOOST_REQUIRE_EQUAL(e.deflections.size(), 1u);
    BOOST_TEST(rel(e.deflections[0].w, total) < 1e-11);
    BOOST_REQUIRE_EQUAL(e.reactions.size(), 1u);
    BOOST_TEST(rel(e.reactions[0].force[2], 1000.0 + weight) < 1e-10);
  }
}

BOOST_AUTO_TEST_CASE(exponential_weight_is_carried_whole) {
  // The SDLL10 beam as a cantilever under its own weight: rho g h b0 (1 - e^(-g L)) / g.
  const Scene s = parse_scene(
      beam("euler-bernoulli", kSdll10, "x0 = \"clamped\"\nxL = \"free\"", "[gravity]\ng = [0.0, 0.0, -9.81]", 2) +
          "probes = [0.6]\ntolerance = 0.5\n",
      "sdll10_weight.toml");
  const double weight = rho * 9.81 * kH * kB0 * (1 - std::exp(-kGamma * kL)) / kGamma;
  const Result r = rfem_on(s, 64);
  BOOST_REQUIRE(r.summary.status == Status::Success);
  BOOST_REQUIRE_EQUAL(r.reactions.size(), 1u);
  BOOST_TEST(rel(r.reactions[0].force[2], weight) < 1e-10);
}

BOOST_AUTO_TEST_CASE(a_staircase_tends_to_the_taper_at_second_order) {
  // The cone clamped-free, tapered and as n uniform pieces with the diameter at each middle; both
  // on rfem's mesh of 240 segments (the steps on its nodes), so that only the staircase differs.
  const Scene taper = parse_scene(beam("euler-bernoulli", piece(kL, "{ shape = \"circle\", diameter = [0.05, 0.03] }"),
                                       "x0 = \"clamped\"\nxL = \"free\"", "", 3) +
                                      "tolerance = 0.5\n",
                                  "cone.toml");
  const Result ref = rfem_on(taper, 240);
  BOOST_REQUIRE(ref.summary.status == Status::Success);
  std::vector<double> diff;
  for (int n : {4, 8, 16}) {
    std::string pieces;
    for (int i = 0; i < n; ++i)
      pieces += piece(kL / n, "{ shape = \"circle\", diameter = " + std::to_string(0.05 - 0.02 * (i + 0.5) / n) + " }");
    const Scene stairs = parse_scene(
        beam("euler-bernoulli", pieces, "x0 = \"clamped\"\nxL = \"free\"", "", 3) + "tolerance = 0.5\n", "s.toml");
    const Result r = rfem_on(stairs, 240);
    BOOST_REQUIRE(r.summary.status == Status::Success);
    diff.push_back(rel(r.frequencies_rad_s[0], ref.frequencies_rad_s[0]));
  }
  BOOST_TEST_INFO("staircase differences " << diff[0] << ", " << diff[1] << ", " << diff[2]);
  BOOST_TEST(std::abs(std::log2(diff[0] / diff[1]) - 2.0) < 0.15);
  BOOST_TEST(std::abs(std::log2(diff[1] / diff[2]) - 2.0) < 0.15);
}

BOOST_AUTO_TEST_CASE(back_ends_without_tapers_say_so) {
  const Scene s = parse_scene(beam("euler-bernoulli", kSdll10, "x0 = \"clamped\"\nxL = \"clamped\"", "", 2), "t.toml");
  const Capability c = registry().get("difference_eq").supports(s);
  BOOST_TEST_INFO(c.reason);
  BOOST_TEST(!c.any());
  BOOST_TEST(c.reason.find("tapered") != std::string::npos);
  for (const std::string name : {"exact", "rfem", "dtfm"}) BOOST_TEST(registry().get(name).supports(s).modes);
}

BOOST_AUTO_TEST_CASE(dtfm_staircase_tends_to_the_exponential_beam_at_second_order) {
  const int k = 4;
  const std::vector<ld> ref = sdll10_frequencies(k);
  BOOST_REQUIRE_EQUAL(ref.size(), static_cast<std::size_t>(k));
  Scene s = parse_scene(beam("euler-bernoulli", kSdll10, "x0 = \"clamped\"\nxL = \"clamped\"", "", k), "sdll10.toml");
  Scene coarse = s;
  coarse.request.tolerance = 0.5;
  std::vector<std::vector<double>> err;
  for (int n : {8, 16, 32, 64}) {
    const Result r = registry().get("dtfm").solve(coarse, Discretization{{n}}, Options{});
    BOOST_TEST_CONTEXT("dtfm " << n << " steps: " << r.summary.message) {
      BOOST_REQUIRE(r.summary.status == Status::Success);
      BOOST_TEST(r.summary.model.find("uniform steps") != std::string::npos);
    }
    err.emplace_back();
    for (int i = 0; i < k; ++i) err.back().push_back(rel(r.frequencies_rad_s[i], static_cast<double>(ref[i])));
  }
  expect_order_two(err);
  // The next term is of order 4 (the family extrapolates on it): Richardson of each pair removes
  // the h^2 term, and what is left falls at least 2^3.5-fold per halving (mode 4's 2^4.7: its h^4
  // term is small beside the h^6 one at these steps).
  std::vector<std::vector<double>> values;
  for (int n : {8, 16, 32, 64}) values.push_back(registry().get("dtfm").solve(coarse, Discretization{{n}}, Options{}).frequencies_rad_s);
  for (int i = 0; i < k; ++i) {
    auto extrapolated = [&](int a) { return values[a + 1][i] + (values[a + 1][i] - values[a][i]) / 3.0; };
    const double e1 = rel(extrapolated(1), static_cast<double>(ref[i])), e2 = rel(extrapolated(2), static_cast<double>(ref[i]));
    BOOST_TEST_INFO("mode " << i + 1 << ": extrapolated errors " << e1 << ", " << e2);
    BOOST_TEST(std::log2(e1 / e2) >= 3.5);
  }
  // The default path refines the steps until its estimate meets the tolerance, and holds to it.
  s.request.tolerance = 1e-5;
  const Result d = registry().get("dtfm").solve_default(s, Options{});
  BOOST_TEST_CONTEXT("dtfm default " << d.summary.mesh << ": " << d.summary.message) {
    BOOST_REQUIRE(d.summary.status == Status::Success);
    BOOST_TEST(d.summary.error_estimate.frequencies <= 1e-5);
    for (int i = 0; i < k; ++i)
      BOOST_TEST(rel(d.frequencies_rad_s[i], static_cast<double>(ref[i])) <= d.summary.error_estimate.frequencies);
  }
  // A staircase mesh is N steps: anything else is the user's input, named.
  const Result bad = registry().get("dtfm").solve(s, Discretization{{2, 2}}, Options{});
  BOOST_TEST((bad.summary.status == Status::InvalidInput));
  BOOST_TEST(bad.summary.message.find("the uniform steps per tapered piece") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_conical_shaft_whirls_alike_on_rfem_dtfm_and_exact) {
  // The built-in conical shaft with a disc: rfem's integrated cells and dtfm's staircase are two
  // models of the tapered Timoshenko shaft; their Campbell diagrams and critical speeds agree within
  // the sum of their own estimates, and rfem's lie within its estimate of exact's.
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/conical_shaft_disc.toml");
  BOOST_REQUIRE(s.has_tapered_pieces());
  const Result rf = registry().get("rfem").solve_default(s, Options{});
  const Result dt = registry().get("dtfm").solve_default(s, Options{});
  BOOST_REQUIRE_MESSAGE(rf.ok(), rf.summary.message);
  BOOST_REQUIRE_MESSAGE(dt.ok(), dt.summary.message);
  const double bound = rf.summary.error_estimate.campbell + dt.summary.error_estimate.campbell;
  BOOST_TEST(bound < 1e-3);
  expect_campbell_within(dt, rf, bound);
  // exact (the whirl lines' Magnus transfer matrices): rfem within its own estimate of it.
  const Result ex = registry().get("exact").solve_default(s, Options{});
  BOOST_REQUIRE_MESSAGE(ex.ok(), ex.summary.message);
  expect_campbell_within(rf, ex, rf.summary.error_estimate.campbell);
}

BOOST_AUTO_TEST_CASE(a_cone_cantilever_against_its_bessel_solution) {
  // The basis solves the field equation, (xi^4 w'')'' = 12 xi^2 w'' + 8 xi^3 w''' + xi^4 w'''' =
  // beta^4 xi^2 w, by the derivative rule above (for J and for I).
  const ld beta = 3.0L, xi = 1.2L, z = 2 * beta * std::sqrt(xi), c = 2 * beta * beta;
  for (int j : {0, 2}) {
    auto d = [&](int k) { return std::pow(c, static_cast<ld>(k)) * cone_basis(j, k, z); };
    const ld lhs = 12 * xi * xi * d(2) + 8 * xi * xi * xi * d(3) + xi * xi * xi * xi * d(4);
    const ld rhs = std::pow(beta, 4.0L) * xi * xi * d(0);
    BOOST_TEST_INFO("basis " << j << ": " << static_cast<double>(lhs) << " vs " << static_cast<double>(rhs));
    BOOST_TEST(std::abs(static_cast<double>(lhs / rhs - 1)) < 1e-12);
  }
  const int k = 4;
  const std::vector<ld> ref = cone_frequencies(k);
  BOOST_REQUIRE_EQUAL(ref.size(), static_cast<std::size_t>(k));
  const Scene s = parse_scene(beam("euler-bernoulli", piece(kL, "{ shape = \"circle\", diameter = [0.05, 0.03] }"),
                                   "x0 = \"clamped\"\nxL = \"free\"", "", k) +
                                  "tolerance = 1e-5\n",  // dtfm's 512 steps reach 6.9e-6, not 1e-6
                              "cone.toml");
  for (const std::string name : {"rfem", "dtfm"}) {
    const Result d = registry().get(name).solve_default(s, Options{});
    BOOST_TEST_CONTEXT(name << " " << d.summary.mesh << ": " << d.summary.message) {
      BOOST_REQUIRE(d.summary.status == Status::Success);
      for (int i = 0; i < k; ++i) {
        BOOST_TEST_INFO("mode " << i + 1 << ": " << d.frequencies_rad_s[i] << " against " << static_cast<double>(ref[i]));
        BOOST_TEST(rel(d.frequencies_rad_s[i], static_cast<double>(ref[i])) <= d.summary.error_estimate.frequencies);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(exact_solves_tapered_pieces_to_their_closed_forms) {
  // The exponential beam (its frequency equation), the cone and the wedge cantilevers (their Bessel
  // solutions): every mode, in order, none missed (the count is exact on the comparison pieces).
  const int k = 6;
  const std::string clamped = "x0 = \"clamped\"\nxL = \"clamped\"", cantilever = "x0 = \"clamped\"\nxL = \"free\"";
  expect_exact(parse_scene(beam("euler-bernoulli", kSdll10, clamped, "", k), "sdll10.toml"), sdll10_frequencies(k));
  expect_exact(parse_scene(beam("euler-bernoulli", piece(kL, "{ shape = \"circle\", diameter = [0.05, 0.03] }"),
                                cantilever, "", k),
                           "cone.toml"),
               cone_frequencies(k));
  const std::vector<ld> wedge = wedge_frequencies(k);
  BOOST_REQUIRE_EQUAL(wedge.size(), static_cast<std::size_t>(k));
  expect_exact(parse_scene(beam("euler-bernoulli",
                                piece(kL, "{ shape = \"rectangle\", width = 0.03, height = [0.05, 0.03] }"), cantilever,
                                "", k),
                           "wedge.toml"),
               wedge);
}

BOOST_AUTO_TEST_CASE(the_wedge_against_rfem_and_dtfm) {
  // The wedge's Bessel solution as a check on the two discrete models too (within their estimates).
  const int k = 4;
  const std::vector<ld> ref = wedge_frequencies(k);
  const Scene s = parse_scene(beam("euler-bernoulli", piece(kL, "{ shape = \"rectangle\", width = 0.03, height = [0.05, 0.03] }"),
                                   "x0 = \"clamped\"\nxL = \"free\"", "", k) +
                                  "tolerance = 1e-4\n",
                              "wedge.toml");
  for (const std::string name : {"rfem", "dtfm"}) {
    const Result d = registry().get(name).solve_default(s, Options{});
    BOOST_TEST_CONTEXT(name << " " << d.summary.mesh << ": " << d.summary.message) {
      BOOST_REQUIRE(d.summary.status == Status::Success);
      for (int i = 0; i < k; ++i)
        BOOST_TEST(rel(d.frequencies_rad_s[i], static_cast<double>(ref[i])) <= d.summary.error_estimate.frequencies);
    }
  }
}

BOOST_AUTO_TEST_CASE(exact_axial_cone_and_free_tapered_beam) {
  // A cone as a bar, clamped at its wide end: (A u')' + k^2 A u = 0 with A ~ xi^2 (xi from the apex)
  // has u = sin(k (xi - xi_c)) / xi; a free narrow end (u' = 0 at xi_t = xi_c - L) gives
  // sin(k L) + k xi_t cos(k L) = 0, k = omega sqrt(rho / E): roots by bisection in long double.
  const ld a = (kD0 - kD1) / kL, xt = kD1 / a;
  const auto f = [&](ld k) { return std::sin(k * kL) + k * xt * std::cos(k * kL); };
  std::vector<ld> axial;
  for (ld k = 0.01L; axial.size() < 3; k += 0.01L) {
    if ((f(k) < 0) == (f(k + 0.01L) < 0)) continue;
    ld lo = k, hi = k + 0.01L;
    for (int i = 0; i < 200 && hi - lo > 1e-18L * hi; ++i) ((f(lo) < 0) == (f((lo + hi) / 2) < 0) ? lo : hi) = (lo + hi) / 2;
    axial.push_back(lo * std::sqrt(static_cast<ld>(E) / rho));
  }
  std::string planar = beam("euler-bernoulli", piece(kL, "{ shape = \"circle\", diameter = [0.05, 0.03] }"),
                            "x0 = \"clamped\"\nxL = \"free\"", "", 10);  // axial: modes 4, 7 and 10
  planar.replace(planar.find("physics = \"bending\""), 19, "physics = \"planar\"");
  const Result r = registry().get("exact").solve_default(parse_scene(planar, "cone_bar.toml"), Options{});
  BOOST_REQUIRE_MESSAGE(r.summary.status == Status::Success, r.summary.message);
  std::vector<double> got;
  for (std::size_t i = 0; i < r.frequencies_rad_s.size(); ++i)
    if (r.mode_families[i] == ModeFamily::Axial) got.push_back(r.frequencies_rad_s[i]);
  BOOST_REQUIRE_GE(got.size(), axial.size());
  for (std::size_t i = 0; i < axial.size(); ++i) {
    BOOST_TEST_INFO("axial mode " << i + 1 << ": " << got[i] << " against " << static_cast<double>(axial[i]));
    BOOST_TEST(rel(got[i], static_cast<double>(axial[i])) < 1e-11);
  }
  // The cone free at both ends: two rigid modes, then the elastic ones as rfem's within its estimate;
  // the rigid translation's modal mass is the cone's mass (exact integrates rho A over the taper).
  std::string free_free = beam("euler-bernoulli", piece(kL, "{ shape = \"circle\", diameter = [0.05, 0.03] }"),
                               "x0 = \"free\"\nxL = \"free\"", "", 4) + "shapes = true\ntolerance = 1e-5\n";
  const Scene s = parse_scene(free_free, "cone_free.toml");
  const Result e = registry().get("exact").solve_default(s, Options{});
  const Result rf = registry().get("rfem").solve_default(s, Options{});
  BOOST_REQUIRE_MESSAGE(e.summary.status == Status::Success, e.summary.message);
  BOOST_REQUIRE_MESSAGE(rf.summary.status == Status::Success, rf.summary.message);
  BOOST_TEST(e.frequencies_rad_s[0] == 0.0);
  BOOST_TEST(e.frequencies_rad_s[1] == 0.0);
  for (std::size_t i = 2; i < 4; ++i) BOOST_TEST(rel(rf.frequencies_rad_s[i], e.frequencies_rad_s[i]) <= rf.summary.error_estimate.frequencies);
  const double mass = static_cast<double>(rho * kPiL / 4 * kL * (kD0 * kD0 + kD0 * kD1 + kD1 * kD1) / 3);
  BOOST_TEST(rel(e.mode_shapes.total_mass, mass) < 1e-13);
  // The rigid modes carry the whole mass in z (a translation and a rotation about the centre of
  // mass, which exact finds by integrating rho A and rho A x over the taper).
  BOOST_REQUIRE_GE(e.mode_shapes.effective_mass.size(), 2u);
  BOOST_TEST(rel(e.mode_shapes.effective_mass[0][2] + e.mode_shapes.effective_mass[1][2], mass) < 1e-12);
}
