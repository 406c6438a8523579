// Support reactions (Result::reactions, exact beams) against closed forms written out here and
// against equilibrium: two equal spans l under q: 3ql/8 at the ends, 10ql/8 in the middle
// (Roark); a clamped-clamped beam under q: qL/2 and end moments -+ qL^2/12 (the left clamp's My
// on the beam negative for a downward load); and on a beam with every kind of load and support,
// the reactions balance the applied forces and moments to rounding.
#define BOOST_TEST_MODULE reactions
#include <boost/test/unit_test.hpp>

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
