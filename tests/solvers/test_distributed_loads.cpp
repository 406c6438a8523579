// Distributed loads ([[line_loads]], [[pressures]], [gravity]) against closed forms written out
// here (Roark; Timoshenko & Woinowsky-Krieger, Theory of Plates and Shells, Table 8):
//   simply supported beam, uniform q: w(L/2) = 5 q L^4 / 384 EI (+ q L^2 / 8 kGA, Timoshenko);
//   cantilever, q rising linearly from 0 at the root to q0 at the tip: w(L) = 11 q0 L^4 / 120 EI;
//   cantilever with a tip mass M under gravity: w(L) = rho A g L^4 / 8 EI + M g L^3 / 3 EI;
//   two equal spans l under self-weight: w at each span's middle = q l^4 / 192 EI (a propped
//   cantilever's);
//   square simply supported plate, uniform p: w(centre) = alpha p a^4 / D, alpha = 0.00406 (the
//   table, to its 3 digits), and its Navier series summed here.
// exact is held to 1e-9 (the plate to its own series tail); rfem to its own estimate.
#define BOOST_TEST_MODULE distributed_loads
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "solver_tests.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double L = 2.0, b = 0.03, h = 0.05, E = 2.1e11, nu = 0.3, rho = 7850.0;
const double EI = E * b * h * h * h / 12, rhoA = rho * b * h;

std::string beam(const std::string& theory, const std::string& supports, const std::string& extra,
                 const std::string& probes) {
  return R"(
[scene]
name = "distributed"
kind = "beam"
physics = "bending"
theory = ")" + theory + R"("
[geometry]
length = 2.0
width = 0.03
height = 0.05
[material]
E = 2.1e11
nu = 0.3
rho = 7850.0
[supports]
)" + supports + "\n" + extra + "\n[request]\nmodes = 0\nprobes = " + probes + "\n";
}

/// exact to 1e-9 and rfem (mesh) within its own estimate, at every probe, against `expected`.
void check(const Scene& s, const std::vector<double>& expected, const std::string& mesh = "512") {
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_TEST_CONTEXT("exact: " << ex.summary.message) {
    BOOST_REQUIRE(ex.summary.status == Status::Success);
    BOOST_REQUIRE_EQUAL(ex.deflections.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) BOOST_TEST(rel(ex.deflections[i].w, expected[i]) < 1e-9);
  }
  const Result rf = registry().get("rfem").solve(s, Discretization::parse(mesh), Options{});
  BOOST_TEST_CONTEXT("rfem " << mesh << ": " << rf.summary.message) {
    BOOST_REQUIRE(rf.summary.status == Status::Success);
    BOOST_REQUIRE_EQUAL(rf.deflections.size(), expected.size());
    double scale = 0;
    for (double e : expected) scale = std::max(scale, std::abs(e));
    for (std::size_t i = 0; i < expected.size(); ++i) {
      BOOST_TEST_INFO("probe " << i << ": " << rf.deflections[i].w << " against " << expected[i] << ", estimate "
                               << rf.summary.error_estimate.deflections);
      BOOST_TEST(std::abs(rf.deflections[i].w - expected[i]) / scale <= rf.summary.error_estimate.deflections);
    }
  }
  // dtfm's one prism is the beam itself, difference_eq's nodal values are the Euler-Bernoulli beam's
  // (the loads' consistent nodal forces are their exact equivalents): both to 1e-9, with their
  // reactions (which balance the loads) and the resultants from them against exact's.
  double total = 0;  // the applied load along z
  for (const PointLoad& p : s.all_point_loads()) total += p.Fz;
  for (const DistributedLoad& d : s.all_distributed_loads()) total += 0.5 * (d.qz[0] + d.qz[1]) * (d.to[0] - d.from[0]);
  // Resultants on the structure's own scales (a probe may sit where one is zero): the total load
  // and its moment over the length.
  const double q_scale = std::abs(total), m_scale = std::abs(total) * L;
  for (const std::string name : {"dtfm", "difference_eq"}) {
    if (name == "difference_eq" && s.theory != Theory::EulerBernoulli) continue;
    const Result r = registry().get(name).solve(s, Discretization::parse(name == "dtfm" ? "1x1" : "16"), Options{});
    BOOST_TEST_CONTEXT(name << ": " << r.summary.message) {
      BOOST_REQUIRE(r.summary.status == Status::Success);
      BOOST_REQUIRE_EQUAL(r.deflections.size(), expected.size());
      for (std::size_t i = 0; i < expected.size(); ++i) {
        BOOST_TEST(rel(r.deflections[i].w, expected[i]) < 1e-9);
        BOOST_REQUIRE(r.deflections[i].has_forces);
        BOOST_TEST(std::abs(r.deflections[i].forces.My - ex.deflections[i].forces.My) <= 1e-9 * m_scale);
        BOOST_TEST(std::abs(r.deflections[i].forces.Qz - ex.deflections[i].forces.Qz) <= 1e-9 * q_scale);
      }
      BOOST_REQUIRE_EQUAL(r.reactions.size(), ex.reactions.size());
      double sum = 0;
      for (const Reaction& e : ex.reactions) {
        const auto it = std::find_if(r.reactions.begin(), r.reactions.end(),
                                     [&](const Reaction& x) { return x.support == e.support; });
        BOOST_REQUIRE(it != r.reactions.end());
        BOOST_TEST(std::abs(it->force[2] - e.force[2]) <= 1e-9 * std::abs(total));
        BOOST_TEST(std::abs(it->moment[1] - e.moment[1]) <= 1e-9 * std::abs(total) * L);
        sum += it->force[2];
      }
      BOOST_TEST(std::abs(sum + total) <= 1e-12 * std::abs(total));
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(simply_supported_uniform_euler_bernoulli_and_timoshenko) {
  const double q = -3000.0;
  const std::string sup = "x0 = \"pinned\"\nxL = \"pinned\"";
  check(parse_scene(beam("euler-bernoulli", sup, "[[line_loads]]\nqz = -3000.0", "[1.0]"), "ss.toml"),
        {5 * q * std::pow(L, 4) / (384 * EI)});
  const Scene t = parse_scene(beam("timoshenko", sup, "[[line_loads]]\nqz = -3000.0", "[1.0]"), "sst.toml");
  const double kGA = t.material.kappa * t.material.G * b * h;
  check(t, {5 * q * std::pow(L, 4) / (384 * EI) + q * L * L / (8 * kGA)});
}

BOOST_AUTO_TEST_CASE(cantilever_with_a_linearly_rising_load) {
  const double q0 = -1500.0;
  check(parse_scene(beam("euler-bernoulli", "x0 = \"clamped\"\nxL = \"free\"", "[[line_loads]]\nqz = [0.0, -1500.0]",
                         "[2.0]"),
                    "tri.toml"),
        {11 * q0 * std::pow(L, 4) / (120 * EI)});
}

BOOST_AUTO_TEST_CASE(cantilever_with_a_tip_mass_under_gravity) {
  const double g = -9.81, M = 2.0;
  check(parse_scene(beam("euler-bernoulli", "x0 = \"clamped\"\nxL = \"free\"",
                         "[[masses]]\nx = 2.0\nmass = 2.0\n[gravity]\ng = [0.0, 0.0, -9.81]", "[2.0]"),
                    "weight.toml"),
        {rhoA * g * std::pow(L, 4) / (8 * EI) + M * g * std::pow(L, 3) / (3 * EI)});
}

BOOST_AUTO_TEST_CASE(two_spans_under_self_weight) {
  const double l = L / 2, q = rhoA * -9.81;
  check(parse_scene(beam("euler-bernoulli", "x0 = \"pinned\"\nxL = \"pinned\"\n[[supports.points]]\nx = 1.0\nkind = \"pinned\"",
                         "[gravity]\ng = [0.0, 0.0, -9.81]", "[0.5, 1.5]"),
                    "two_span.toml"),
        {q * std::pow(l, 4) / (192 * EI), q * std::pow(l, 4) / (192 * EI)});
}

BOOST_AUTO_TEST_CASE(square_plate_under_uniform_pressure) {
  const double a = 1.0, t = 0.01, p = -1000.0;
  const double D = E * t * t * t / (12 * (1 - nu * nu));
  const std::string text = R"(
[scene]
name = "pressure"
kind = "plate"
physics = "bending"
theory = "kirchhoff"
[geometry]
length = 1.0
width = 1.0
height = 0.01
[material]
E = 2.1e11
nu = 0.3
rho = 7850.0
[supports]
x0 = "pinned"
xL = "pinned"
y0 = "pinned"
yB = "pinned"
[[pressures]]
p = -1000.0
[request]
modes = 0
probes = [[0.5, 0.5]]
)";
  // Navier at the centre: w = 16 p / (pi^6 D) sum_{m, n odd} (-1)^((m + n)/2 - 1) / (m n (m^2 + n^2)^2 / a^4).
  double series = 0;
  for (int m = 1; m < 4001; m += 2)
    for (int n = 1; n < 4001; n += 2)
      series += (((m + n) / 2 - 1) % 2 ? -1.0 : 1.0) / (m * n * std::pow(m * m + n * n, 2));
  const double w = 16 * p * std::pow(a, 4) / (std::pow(kPi, 6) * D) * series;
  BOOST_TEST(std::abs(w / (p * std::pow(a, 4) / D) - 0.00406) < 0.5e-5);  // Timoshenko's Table 8
  const Scene s = parse_scene(text, "plate.toml");
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  BOOST_TEST(rel(ex.deflections[0].w, w) < 1e-9);
  const Result rf = registry().get("rfem").solve(s, Discretization::parse("100x100"), Options{});
  BOOST_TEST_CONTEXT("rfem 100x100: " << rf.summary.message) {
    BOOST_REQUIRE(rf.summary.status == Status::Success);
    BOOST_TEST(rel(rf.deflections[0].w, w) <= rf.summary.error_estimate.deflections);
    // Its edge reactions carry the whole pressure and their moments about the centre balance, to
    // the 1e-8 rfem guarantees where it reports reactions (their residual in the unreduced model);
    // a quarter each by the square's symmetry (the corner values, pinned by two edges, share their
    // force equally).
    BOOST_REQUIRE_EQUAL(rf.reactions.size(), 4u);
    const double total = p * a * a;
    double fz = 0, mx = 0, my = 0;
    for (const Reaction& e : rf.reactions) {
      BOOST_TEST(std::abs(e.force[2] + total / 4) <= 1e-6 * std::abs(total), e.support);
      fz += e.force[2];
      mx += e.moment[0] + (e.position[1] - a / 2) * e.force[2];
      my += e.moment[1] - (e.position[0] - a / 2) * e.force[2];
    }
    BOOST_TEST(std::abs(fz + total) <= 1e-8 * std::abs(total));
    BOOST_TEST(std::abs(mx) <= 1e-8 * std::abs(total) * a);
    BOOST_TEST(std::abs(my) <= 1e-8 * std::abs(total) * a);
  }
  // dtfm's strips take the pressure against their hat functions across y, exactly along x.
  const Result dt = registry().get("dtfm").solve(s, Discretization::parse("64"), Options{});
  BOOST_TEST_CONTEXT("dtfm 64: " << dt.summary.message) {
    BOOST_REQUIRE(dt.summary.status == Status::Success);
    BOOST_TEST(rel(dt.deflections[0].w, w) <= dt.summary.error_estimate.deflections);
    BOOST_TEST(rel(dt.deflections[0].w, w) < 1e-3);  // the estimate is not vacuous
  }
}

BOOST_AUTO_TEST_CASE(dtfm_and_difference_eq_take_line_loads_and_gravity) {
  // Pinned-pinned under a uniform q and its own weight: 5 (q + rho A g_z) L^4 / (384 EI) at the
  // middle. dtfm's one prism is the beam itself; difference_eq's nodal values are exact under the
  // loads' consistent nodal forces (Hermite elements), and between nodes (x = 0.7 on 8 elements of
  // 0.25 m) the loaded element's own clamped solution completes them.
  const Scene s = parse_scene(beam("euler-bernoulli", "x0 = \"pinned\"\nxL = \"pinned\"",
                                   "[[line_loads]]\nqz = -3000.0\n[gravity]\ng = [0.0, 0.0, -9.81]", "[1.0, 0.7]"),
                              "ss.toml");
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  const Result dt = registry().get("dtfm").solve(s, Discretization::parse("1x1"), Options{});
  BOOST_REQUIRE(dt.summary.status == Status::Success);
  const Result de = registry().get("difference_eq").solve(s, Discretization::parse("8"), Options{});
  BOOST_TEST_CONTEXT(de.summary.message) { BOOST_REQUIRE(de.summary.status == Status::Success); }
  for (std::size_t j = 0; j < 2; ++j) {
    BOOST_TEST(rel(dt.deflections[j].w, ex.deflections[j].w) < 1e-10);
    BOOST_TEST(rel(de.deflections[j].w, ex.deflections[j].w) < 1e-10);
    BOOST_TEST(std::abs(de.deflections[j].theta_y - ex.deflections[j].theta_y) < 1e-10 * std::abs(ex.deflections[1].theta_y));
  }
}

BOOST_AUTO_TEST_CASE(bad_distributed_loads_are_named) {
  const auto expect = expect_input_error;
  const std::string sup = "x0 = \"pinned\"\nxL = \"pinned\"";
  expect(beam("euler-bernoulli", sup, "[[line_loads]]\nqz = -1.0\nx_from = 1.5\nx_to = 0.5", "[1.0]"), "line_loads[0].x_to",
         "must exceed x_from");
  expect(beam("euler-bernoulli", sup, "[[line_loads]]\nqx = -1.0", "[1.0]"), "line_loads[0].qx", "unknown key");
  expect(beam("euler-bernoulli", sup, "[[line_loads]]\nx_from = 0.5", "[1.0]"), "line_loads[0]", "at least one component");
  expect(beam("euler-bernoulli", sup, "[[line_loads]]\nqz = [1.0, 2.0, 3.0]", "[1.0]"), "line_loads[0].qz", "[start, end]");
  expect(beam("euler-bernoulli", sup, "[[pressures]]\np = 1.0", "[1.0]"), "pressures", "line_loads");
  expect(beam("euler-bernoulli", sup, "[gravity]\ng = [9.81, 0.0, 0.0]", "[1.0]"), "gravity.g[0]", "no load along x");
  expect(beam("euler-bernoulli", sup, "[gravity]\ng = [0.0, -9.81]", "[1.0]"), "gravity.g", "[gx, gy, gz]");
}
