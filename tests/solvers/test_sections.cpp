// Round shafts through every back-end: a solid circle's properties (A = pi d^2 / 4, I = pi d^4 / 64,
// J = Ip = pi d^4 / 32) give the clamped-free shaft's closed forms, written out here independently
// of the code: bending (beta_n L)^2 / L^2 sqrt(E I / rho A) in exact pairs (Iy = Iz), torsion and
// axial (2n - 1) pi / 2L sqrt(G / rho), sqrt(E / rho). Each back-end is held to its own estimate.
#define BOOST_TEST_MODULE sections
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "solver_tests.hpp"
#include "solve_options.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double L = 1.0, d = 0.04, E = 2.1e11, nu = 0.3, rho = 7850.0;

Scene shaft(const std::string& physics, const std::string& theory, int modes) {
  return parse_scene(R"(
[scene]
name = "round-shaft"
kind = "beam"
physics = ")" + physics + R"("
theory = ")" + theory + R"("
[geometry]
length = 1.0
section = { shape = "circle", diameter = 0.04 }
[material]
E = 2.1e11
nu = 0.3
rho = 7850.0
[supports]
x0 = "clamped"
xL = "free"
[request]
modes = )" + std::to_string(modes) + "\n",
                     "round_shaft.toml");
}

/// The clamped-free Euler-Bernoulli circle shaft's lowest 7 frequencies in space, ascending.
std::vector<double> closed_form_spatial() {
  const double G = E / (2 * (1 + nu));
  const double bend = std::sqrt(E * d * d / (16 * rho)) / (L * L);  // sqrt(E I / rho A) / L^2, I / A = d^2 / 16
  std::vector<double> w;
  for (double bl : {1.875104068711961, 4.694091132974175, 7.854757438237613, 10.99554073487547})
    w.insert(w.end(), 2, bl * bl * bend);
  for (int n = 1; n <= 2; ++n) {
    w.push_back((2 * n - 1) * kPi / (2 * L) * std::sqrt(G / rho));  // torsion, J = Ip
    w.push_back((2 * n - 1) * kPi / (2 * L) * std::sqrt(E / rho));  // axial
  }
  std::sort(w.begin(), w.end());
  w.resize(7);
  return w;
}

}  // namespace

BOOST_AUTO_TEST_CASE(exact_matches_the_closed_forms_with_pairs) {
  const auto ref = closed_form_spatial();
  const Result r = registry().get("exact").solve(shaft("spatial", "euler-bernoulli", 7), {}, Options{});
  BOOST_REQUIRE(r.summary.status == Status::Success);
  BOOST_REQUIRE_EQUAL(r.frequencies_rad_s.size(), ref.size());
  for (std::size_t i = 0; i < ref.size(); ++i) {
    BOOST_TEST_INFO("mode " << i + 1 << ": " << r.frequencies_rad_s[i] << " against " << ref[i]);
    // The count's bisection and polish: 1e-10 is four decades above their stated precision.
    BOOST_TEST(rel(r.frequencies_rad_s[i], ref[i]) < 1e-10);
  }
}

BOOST_AUTO_TEST_CASE(rfem_and_dtfm_within_their_estimates) {
  const auto ref = closed_form_spatial();
  const Scene s = shaft("spatial", "euler-bernoulli", 7);
  for (const auto& [backend, mesh] : std::vector<std::pair<std::string, std::string>>{{"rfem", "128"}, {"dtfm", "1x1"}}) {
    const Result r = registry().get(backend).solve(s, Discretization::parse(mesh), Options{});
    BOOST_TEST_CONTEXT(backend << " " << mesh << ": " << r.summary.message) {
      BOOST_REQUIRE(r.summary.status == Status::Success);
      BOOST_REQUIRE_EQUAL(r.frequencies_rad_s.size(), ref.size());
      // rfem's discretization estimate; one dtfm prism is the exact beam (no mesh to estimate):
      // its count's precision, as the exact back-end's.
      const double estimate = backend == "rfem" ? r.summary.error_estimate.frequencies : 1e-10;
      BOOST_REQUIRE(std::isfinite(estimate));
      for (std::size_t i = 0; i < ref.size(); ++i) {
        BOOST_TEST_INFO("mode " << i + 1 << ": " << r.frequencies_rad_s[i] << " against " << ref[i] << ", estimate "
                                << estimate);
        BOOST_TEST(rel(r.frequencies_rad_s[i], ref[i]) <= estimate + 1e-10);
      }
      // The bending pairs are one frequency twice (Iy = Iz): equal within the solve's own bound.
      const double bound = r.summary.diagnostic("frequency_solve_error_bound");
      const double solve = std::isfinite(bound) ? std::max(bound, 1e-12) : 1e-10;
      for (std::size_t i = 0; i + 1 < 6; i += 2) BOOST_TEST(rel(r.frequencies_rad_s[i], r.frequencies_rad_s[i + 1]) <= 2 * solve);
    }
  }
}

BOOST_AUTO_TEST_CASE(timoshenko_shaft_dtfm_one_prism_is_the_exact_beam) {
  // Cowper's kappa of a circle enters both; one prism is the Timoshenko beam itself.
  const Scene s = shaft("bending", "timoshenko", 6);
  BOOST_TEST(s.material.kappa == 6 * (1 + nu) / (7 + 6 * nu), boost::test_tools::tolerance(1e-14));
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  const Result dt = registry().get("dtfm").solve(s, Discretization::parse("1x1"), Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  BOOST_REQUIRE(dt.summary.status == Status::Success);
  for (std::size_t i = 0; i < 6; ++i) BOOST_TEST(rel(dt.frequencies_rad_s[i], ex.frequencies_rad_s[i]) < 1e-9);
}

BOOST_AUTO_TEST_CASE(difference_eq_bending_within_its_estimate) {
  const auto ref = closed_form_spatial();  // bending-only: every other entry of the pairs
  const Scene s = shaft("bending", "euler-bernoulli", 3);
  const Solver& de = registry().get("difference_eq");
  const Result r = de.solve(s, testing::default_mesh(de, s), Options{});
  BOOST_REQUIRE(r.summary.status == Status::Success);
  for (std::size_t i = 0; i < 3; ++i)
    BOOST_TEST(rel(r.frequencies_rad_s[i], ref[2 * i]) <= r.summary.error_estimate.frequencies + 1e-10);
}

BOOST_AUTO_TEST_CASE(dtfm_cuts_only_rectangles) {
  const Scene s = shaft("spatial", "euler-bernoulli", 3);
  const Solver& dt = registry().get("dtfm");
  BOOST_TEST(testing::default_mesh(dt, s).spec() == "1x1");
  const Result r = dt.solve(s, Discretization::parse("2x2"), Options{});
  BOOST_TEST((r.summary.status == Status::InvalidInput));
  BOOST_TEST(r.summary.message.find("only rectangular sections") != std::string::npos, r.summary.message);
}
