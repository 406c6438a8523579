// A free beam on one soft end spring: its rigid motions are a zero mode (rotation about the
// spring) and a near-rigid one, M-orthogonal to it: a rigid bar of mass m, length L on a spring k
// at one end, Euler-Bernoulli (no rotary inertia), has K = diag(k, 0) and M = m [[1, -L/2],
// [-L/2, L^2/3]] over (w_end, theta), so omega^2 = 4 k / m (the bar rocks about its centre of
// percussion); the beam's own flexibility shifts it by O(k L^3 / EI), 1e-12 here. A Rayleigh-Ritz
// over the spring-restrained motion alone gives sqrt(k / m); one over the Euclidean complement of
// the free motion, sqrt(1.5 k / m) (the fuzzer found both, in dtfm and rfem).
#define BOOST_TEST_MODULE near_rigid_rocking
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "solver_tests.hpp"
#include "solve_options.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

BOOST_AUTO_TEST_CASE(a_bar_rocking_on_one_end_spring) {
  for (const std::string physics : {"bending", "spatial"}) {
    const std::string text = R"(
[scene]
name = "rocking"
kind = "beam"
physics = ")" + physics + R"("
theory = "euler-bernoulli"
[geometry]
length = 10.0
width = 2.0
height = 2.0
[material]
E = 2e11
nu = 0.3
rho = 8000.0
[supports]
x0 = "free"
xL = )" + (physics == "bending" ? std::string("{ translational = 1.0, rotational = 0.0 }")
                                  : std::string("{ translational = 1.0, rotational = 0.0, axial = 1.0, torsional = 1.0 }")) +
                             R"(
[request]
modes = 8
)";
    const Scene s = parse_scene(text, "rocking.toml");
    const double m = 8000.0 * 4.0 * 10.0, omega = 2.0 * std::sqrt(1.0 / m);
    for (const std::string name : {"exact", "rfem", "dtfm", "difference_eq"}) {
      if (physics == "spatial" && name == "difference_eq") continue;
      const Solver& b = registry().get(name);
      const Result r = b.solve(s, testing::default_mesh(b, s), Options{});
      BOOST_TEST_CONTEXT(physics << ", " << name << ": " << r.summary.message) {
        BOOST_TEST_REQUIRE((r.summary.status == Status::Success));
        // The rocking mode: in bending after the rotation about the spring; in space one per plane,
        // after the axial and torsional ones on their own springs.
        // exact, dtfm and difference_eq: the continuum (to 1e-6); rfem: its lumped rigid elements,
        // within its own estimate.
        const double tol = name == "rfem" ? r.summary.error_estimate.frequencies : 1e-6;
        int found = 0;
        for (std::size_t i = 0; i < r.frequencies_rad_s.size(); ++i)
          if (std::abs(r.frequencies_rad_s[i] / omega - 1) <= tol) ++found;
        BOOST_TEST(found == (physics == "bending" ? 1 : 2), "omega " << omega << " within " << tol);
        BOOST_TEST(r.frequencies_rad_s[0] == 0.0);
      }
    }
  }
}
