// Support reactions (Result::reactions, exact beams) against closed forms written out here and
// against equilibrium: two equal spans l under q: 3ql/8 at the ends, 10ql/8 in the middle
// (Roark); a clamped-clamped beam under q: qL/2 and end moments -+ qL^2/12 (the left clamp's My
// on the beam negative for a downward load); and on a beam with every kind of load and support,
// the reactions balance the applied forces and moments to rounding.
#define BOOST_TEST_MODULE reactions
#include <boost/test/unit_test.hpp>

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "solver_tests.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

std::string beam(const std::string& supports, const std::string& extra) {
  return R"(
[scene]
name = "reactions"
kind = "beam"
physics = "bending"
theory = "euler-bernoulli"
[geometry]
length = 2.0
width = 0.03
height = 0.05
[material]
E = 2.1e11
nu = 0.3
rho = 7850.0
[supports]
)" + supports + "\n" + extra + "\n[request]\nmodes = 0\nprobes = [1.0]\n";
}

const Reaction& named(const Result& r, const std::string& name) {
  for (const Reaction& x : r.reactions)
    if (x.support == name) return x;
  BOOST_FAIL("no reaction named " << name);
  throw std::logic_error("unreachable");
}

}  // namespace

BOOST_AUTO_TEST_CASE(two_spans_under_a_uniform_load) {
  const double q = 3000.0, l = 1.0;
  const Scene s = parse_scene(beam("x0 = \"pinned\"\nxL = \"pinned\"\n[[supports.points]]\nx = 1.0\nkind = \"pinned\"",
                                   "[[line_loads]]\nqz = -3000.0"),
                              "two_span.toml");
  const Result r = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(r.summary.status == Status::Success);
  BOOST_REQUIRE_EQUAL(r.reactions.size(), 3u);
  BOOST_TEST(rel(named(r, "x0").force[2], 3 * q * l / 8) < 1e-9);
  BOOST_TEST(rel(named(r, "xL").force[2], 3 * q * l / 8) < 1e-9);
  BOOST_TEST(rel(named(r, "points[0]").force[2], 10 * q * l / 8) < 1e-9);
  BOOST_TEST(named(r, "points[0]").position[0] == 1.0);
}

BOOST_AUTO_TEST_CASE(clamped_clamped_end_moments) {
  const double q = 3000.0, L = 2.0;
  const Scene s = parse_scene(beam("x0 = \"clamped\"\nxL = \"clamped\"", "[[line_loads]]\nqz = -3000.0"), "cc.toml");
  const Result r = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(r.summary.status == Status::Success);
  BOOST_TEST(rel(named(r, "x0").force[2], q * L / 2) < 1e-9);
  BOOST_TEST(rel(named(r, "x0").moment[1], -q * L * L / 12) < 1e-9);
  BOOST_TEST(rel(named(r, "xL").moment[1], q * L * L / 12) < 1e-9);
}

BOOST_AUTO_TEST_CASE(reactions_balance_every_load) {
  // Clamped at x0, a spring at xL, a spring support and a mass between, under gravity, a linear
  // line load, a point force and a point moment.
  const Scene s = parse_scene(
      beam("x0 = \"clamped\"\nxL = { translational = 1e6, rotational = 0.0 }\n[[supports.points]]\nx = 1.3\n"
           "translational = 5e5\nrotational = 2e4",
           "[[masses]]\nx = 0.7\nmass = 3.0\n[gravity]\ng = [0.0, 0.0, -9.81]\n[[line_loads]]\nqz = [-500.0, 1200.0]\n"
           "x_from = 0.2\nx_to = 1.8\n[[loads]]\nx = 0.45\nFz = 800.0\nMy = -150.0"),
      "balance.toml");
  const Result r = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(r.summary.status == Status::Success);
  BOOST_REQUIRE_EQUAL(r.reactions.size(), 3u);
  // Applied: forces along z and moments about y about the origin, (r x F)_y = -x Fz.
  const double rhoA = 7850.0 * 0.03 * 0.05, g = -9.81;
  double Fz = rhoA * g * 2.0 + 3.0 * g + 800.0, My = -(rhoA * g * 2.0) * 1.0 - 0.7 * 3.0 * g - 0.45 * 800.0 - 150.0;
  // The line load: q(x) = -500 + 1700 (x - 0.2) / 1.6 on [0.2, 1.8].
  const double a = 0.2, b = 1.8, q0 = -500.0, q1 = 1200.0, len = b - a;
  const double load = 0.5 * (q0 + q1) * len;
  const double first_moment = q0 * len * (a + len / 2) + (q1 - q0) * len * (a + 2 * len / 3) / 2;  // int x q dx
  Fz += load;
  My -= first_moment;
  double scale = std::abs(Fz) + 1000.0;
  for (const Reaction& x : r.reactions) {
    Fz += x.force[2];
    My += x.moment[1] - x.position[0] * x.force[2];
    scale = std::max(scale, std::abs(x.force[2]));
  }
  BOOST_TEST(std::abs(Fz) < 1e-9 * scale);
  BOOST_TEST(std::abs(My) < 1e-9 * scale * 2.0);
}

// rfem's reactions are held to their balance's own rounding, not to a fixed 1e-8 (issue 54): a
// slender Timoshenko beam (L/h = 1000, clamped-pinned, stiff shear springs carrying small motions)
// balanced to 5.6e-8 and a beam on springs of 1e-12 EI / L^3 to 0.064 (its rigid motion is 1e12
// times its bending), both within the rounding of B'(f - K q), and their reactions were withheld with
// a warning on runs that asked for frequencies. Here they are reported, equal to the closed form:
// a load P at a on a clamped-pinned beam leaves R_B = P a^2 (3 L - a) / (2 L^3) at the pin; on the
// free-floating springs, the free body's 0.54 and 0.46 of a unit load at 0.3 L (the exact back-end's).
BOOST_AUTO_TEST_CASE(rfem_reactions_within_their_rounding_are_reported) {
  const auto slender = R"(
[scene]
name = "slender"
kind = "beam"
physics = "bending"
theory = "timoshenko"
[geometry]
length = 1.0
width = 0.001
height = 0.001
[material]
E = 2e11
nu = 0.3
rho = 7850.0
kappa = 0.8333333333333334
[supports]
x0 = "clamped"
xL = "pinned"
[[loads]]
x = 0.5
Fz = -1.0
[request]
modes = 10
probes = [0.25, 0.5, 0.75]
)";
  const Result r = registry().get("rfem").solve(parse_scene(slender, "slender.toml"), Discretization{{512}}, Options{});
  BOOST_TEST_REQUIRE(to_string(r.summary.status) == "success", r.summary.message);
  for (const auto& w : r.summary.warnings) BOOST_TEST(w.find("reactions not reported") == std::string::npos, w);
  BOOST_TEST_REQUIRE(r.reactions.size() == 2u);
  const double residual = r.summary.diagnostic("reaction_residual"), floor = r.summary.diagnostic("reaction_rounding_floor");
  BOOST_TEST(residual > 1e-8);            // the case the fixed threshold refused
  BOOST_TEST(residual <= 64 * floor);     // within its own rounding
  const double a = 0.5, L = 1.0, pin = 1.0 * a * a * (3 * L - a) / (2 * L * L * L);
  // The Timoshenko beam's pin reaction differs from Euler-Bernoulli's by the shear flexibility,
  // (h / L)^2 = 1e-6 here; rfem's mesh error is second order in 1/512.
  BOOST_TEST(rel(named(r, "xL").force[2], pin) < 1e-4);
  BOOST_TEST(rel(named(r, "x0").force[2] + named(r, "xL").force[2], 1.0) < 64 * floor);

  const double EI = 2e11 * 1e-8 / 12, k = 1e-12 * EI;
  const std::string soft = fmt::format(R"(
[scene]
name = "soft"
kind = "beam"
physics = "bending"
theory = "euler-bernoulli"
[geometry]
length = 1.0
width = 0.01
height = 0.01
[material]
E = 2e11
nu = 0.3
rho = 7850.0
[supports]
x0 = {{ translational = {0}, rotational = {0} }}
xL = {{ translational = {0}, rotational = {0} }}
[[loads]]
x = 0.3
Fz = -1.0
[request]
modes = 0
probes = [0.5]
)",
                                       k);
  const Result s = registry().get("rfem").solve(parse_scene(soft, "soft.toml"), Discretization{{256}}, Options{});
  BOOST_TEST_REQUIRE(s.reactions.size() == 2u, s.summary.message);
  BOOST_TEST(rel(named(s, "x0").force[2], 0.54) < 1e-9);
  BOOST_TEST(rel(named(s, "xL").force[2], 0.46) < 1e-9);
}
