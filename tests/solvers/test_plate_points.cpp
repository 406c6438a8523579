// Supports and masses at points of a plate ([[supports.points]] and [[masses]] with x, y) against
// references built here from the simply supported Kirchhoff plate's Navier series (exact back-end's
// functions, each with its own truncation bound):
//   - a rigid point support at (xs, ys) under a pressure: superposition, w = w_p + R G(., s) with
//     R = -w_p(s) / G(s, s) (G the point-force flexibility);
//   - a point mass M at (xm, ym): the lowest root of 1 = omega^2 M H(omega), H the driving-point
//     receptance of the bare plate (between 0 and its first frequency; a mode with a node line
//     through the mass keeps its frequency).
// rfem is held to its own error estimate; dtfm's strips converge at second order (meshes of 16, 32
// and 64 strips; a point on a strip line holds or carries that line's node); exact and the CalculiX
// references say they do not model them.
#define BOOST_TEST_MODULE plate_points
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>
#include <string>

#include "modalbench/exact/plates.hpp"
#include "solve_options.hpp"
#include "solver_tests.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

constexpr double a = 1.0, b = 0.8, h = 0.01, E = 2.1e11, nu = 0.3, rho = 7850.0;
const double D = E * h * h * h / (12 * (1 - nu * nu));

std::string plate(const std::string& extra, int modes, const std::string& probes = "") {
  return steel_plate(extra, "modes = " + std::to_string(modes) + "\n" + probes);
}

Result rfem_default(const Scene& s) {
  const Solver& rfem = registry().get("rfem");
  Options o;
  o.refine_to_tolerance = true;  // as the command line does with its default mesh
  return rfem.solve(s, testing::default_mesh(rfem, s), o);
}

}  // namespace

BOOST_AUTO_TEST_CASE(rigid_point_support_under_pressure_by_superposition) {
  const double xs = 0.6, ys = 0.5, p = -1000.0, xo = 0.3, yo = 0.35;
  const int terms = 2000;
  const std::vector<exact::PressurePatch> pressure = {{0.0, a, 0.0, b, p}};
  double t1 = 0, t2 = 0, t3 = 0, t4 = 0;
  const double wp_s = exact::navier_static(a, b, D, {}, xs, ys, terms, &t1, pressure)[0];
  const double wp_o = exact::navier_static(a, b, D, {}, xo, yo, terms, &t2, pressure)[0];
  const double G_ss = exact::navier_static(a, b, D, {{xs, ys, 1.0}}, xs, ys, terms, &t3)[0];
  const double G_os = exact::navier_static(a, b, D, {{xs, ys, 1.0}}, xo, yo, terms, &t4)[0];
  const double R = -wp_s / G_ss, w_ref = wp_o + R * G_os;
  // The series' own bounds carried through the superposition (relative).
  const double ref_err = (t2 + std::abs(R) * t4) / std::abs(w_ref) + (t1 / std::abs(wp_s) + t3 / G_ss) * std::abs(R * G_os / w_ref);
  BOOST_REQUIRE(ref_err < 1e-5);
  const Scene s = parse_scene(plate("[[supports.points]]\nx = 0.6\ny = 0.5\nkind = \"pinned\"\n[[pressures]]\np = -1000.0", 0,
                                    "probes = [[0.3, 0.35], [0.6, 0.5]]\n"),
                              "support.toml");
  const Result rf = rfem_default(s);
  BOOST_TEST_CONTEXT("rfem " << rf.summary.mesh << ": " << rf.summary.message) {
    BOOST_REQUIRE(rf.summary.status == Status::Success);
    BOOST_TEST_INFO("w " << rf.deflections[0].w << " vs " << w_ref << " (reaction " << R << " N)");
    BOOST_TEST(std::abs(rf.deflections[0].w / w_ref - 1) <= rf.summary.error_estimate.deflections + ref_err);
    // Held: the support holds its point on the element that carries it; a probe there reads the
    // interpolation between centres, which is 0 to the discretization error.
    BOOST_TEST(std::abs(rf.deflections[1].w) <= rf.summary.error_estimate.deflections * std::abs(w_ref));
    // The reactions: held edges at their corner values, the point by its hold's multiplier.
    double fz = 0, point = 0;
    for (const Reaction& e : rf.reactions) {
      fz += e.force[2];
      if (e.support == "points[0]") point = e.force[2];
    }
    BOOST_TEST(rf.reactions.size() == 5u);
    BOOST_TEST(std::abs(fz + p * a * b) <= 1e-8 * std::abs(p * a * b));
    BOOST_TEST(std::abs(point / R - 1) < 2e-3, "reaction " << point << " vs " << R);
  }
  // dtfm: the support holds w of its strip line's node (a pinned point holds no rotation).
  std::vector<double> err;
  for (const std::string mesh : {"16", "32", "64"}) {
    const Result dt = registry().get("dtfm").solve(s, Discretization::parse(mesh), testing::own_error_study());
    BOOST_TEST_REQUIRE((dt.summary.status == Status::Success), mesh << ": " << dt.summary.message);
    BOOST_TEST(dt.deflections[1].w == 0.0);
    err.push_back(dt.deflections[0].w / w_ref - 1);
    double fz = 0, point = 0;
    for (const Reaction& e : dt.reactions) {
      fz += e.force[2];
      if (e.support == "points[0]") point = e.force[2];
    }
    BOOST_TEST(std::abs(fz + p * a * b) <= 1e-6 * std::abs(p * a * b), mesh);
    BOOST_TEST(std::abs(point / R - 1) < 2e-3, mesh << ": reaction " << point << " vs " << R);
  }
  BOOST_TEST_MESSAGE("dtfm support: relative errors " << err[0] << ", " << err[1] << ", " << err[2]);
  BOOST_TEST((err[0] / err[1] > 3 && err[0] / err[1] < 5));
  BOOST_TEST((err[1] / err[2] > 3 && err[1] / err[2] < 5));
  BOOST_TEST(std::abs(err[2]) < 1e-3);
}

BOOST_AUTO_TEST_CASE(point_mass_lowers_the_first_frequency_as_its_receptance_says) {
  const double M = 3.0, xm = 0.5, ym = 0.4, rho_h = rho * h;
  const int terms = 600;
  const double w11 = exact::navier_frequencies(a, b, D, rho_h, 1)[0];
  auto f = [&](double w) {
    return 1.0 - w * w * M * exact::navier_receptance(a, b, D, rho_h, 0.0, xm, ym, xm, ym, w, terms).real();
  };
  double lo = 1e-6 * w11, hi = w11 * (1 - 1e-9);
  BOOST_REQUIRE(f(lo) > 0 && f(hi) < 0);
  for (int i = 0; i < 80; ++i) ((f(0.5 * (lo + hi)) > 0) ? lo : hi) = 0.5 * (lo + hi);
  const double w_ref = 0.5 * (lo + hi);
  // The truncation: the same root with half the terms (the series converges like terms^-2).
  auto f_half = [&](double w) {
    return 1.0 - w * w * M * exact::navier_receptance(a, b, D, rho_h, 0.0, xm, ym, xm, ym, w, terms / 2).real();
  };
  double lo2 = 1e-6 * w11, hi2 = w11 * (1 - 1e-9);
  for (int i = 0; i < 80; ++i) ((f_half(0.5 * (lo2 + hi2)) > 0) ? lo2 : hi2) = 0.5 * (lo2 + hi2);
  const double ref_err = std::abs(0.5 * (lo2 + hi2) / w_ref - 1);
  BOOST_REQUIRE(ref_err < 1e-5);
  const Scene s = parse_scene(plate("[[masses]]\nx = 0.5\ny = 0.4\nmass = 3.0", 3), "mass.toml");
  const Result rf = rfem_default(s);
  BOOST_TEST_CONTEXT("rfem " << rf.summary.mesh << ": " << rf.summary.message) {
    BOOST_REQUIRE(rf.summary.status == Status::Success);
    BOOST_TEST_INFO("omega_1 " << rf.frequencies_rad_s[0] << " vs " << w_ref << " (bare plate " << w11 << ")");
    BOOST_TEST(rel(rf.frequencies_rad_s[0], w_ref) <= rf.summary.error_estimate.frequencies + ref_err);
    BOOST_TEST(w_ref < 0.95 * w11);  // the mass matters (3 kg on a 63 kg plate: -8.5 %)
    // Modes (2, 1) and (1, 2) have node lines through the plate's centre: the mass leaves them.
    const std::vector<double> bare = exact::navier_frequencies(a, b, D, rho_h, 3);
    BOOST_TEST(rel(rf.frequencies_rad_s[1], bare[1]) <= rf.summary.error_estimate.frequencies);
    BOOST_TEST(rel(rf.frequencies_rad_s[2], bare[2]) <= rf.summary.error_estimate.frequencies);
  }
  // dtfm: the mass on its strip line's node (lumped there: w and the rotations' inertia).
  std::vector<double> err;
  for (const std::string mesh : {"16", "32", "64"}) {
    const Result dt = registry().get("dtfm").solve(s, Discretization::parse(mesh), testing::own_error_study());
    BOOST_TEST_REQUIRE((dt.summary.status == Status::Success), mesh << ": " << dt.summary.message);
    err.push_back(dt.frequencies_rad_s[0] / w_ref - 1);
  }
  BOOST_TEST_MESSAGE("dtfm mass: relative errors " << err[0] << ", " << err[1] << ", " << err[2]);
  BOOST_TEST((err[0] / err[1] > 3.5 && err[0] / err[1] < 4.5));
  BOOST_TEST((err[1] / err[2] > 3.5 && err[1] / err[2] < 4.5));
  BOOST_TEST(std::abs(err[2]) < 2e-4);
}

BOOST_AUTO_TEST_CASE(plate_points_parse_and_exact_refuses) {
  expect_input_error(plate("[[supports.points]]\nx = 0.5\nkind = \"pinned\"", 2), "supports.points[0].y", "missing key");
  expect_input_error(plate("[[supports.points]]\nx = 0.5\ny = 0.8\nkind = \"pinned\"", 2), "supports.points[0].y",
                     "strictly inside");
  expect_input_error(plate("[[masses]]\nx = 0.5\ny = -0.1\nmass = 1.0", 2), "masses[0].y", "must lie in");
  expect_input_error(plate("[[supports.points]]\nx = 0.5\ny = 0.4\nkind = \"pinned\"\n[[supports.points]]\nx = 0.5\ny = 0.4\n"
                           "kind = \"clamped\"",
                           2),
                     "supports.points[1].x", "a second support");
  const Scene s = parse_scene(plate("[[masses]]\nx = 0.5\ny = 0.4\nmass = 3.0", 2), "refused.toml");
  BOOST_REQUIRE_EQUAL(s.masses.size(), 1u);
  BOOST_TEST(s.masses[0].y == 0.4);
  for (const std::string name : {"exact"}) {
    const Solver& b = registry().get(name);
    const Result r = b.solve(s, testing::default_mesh(b, s), Options{});
    BOOST_TEST_CONTEXT(name << ": " << r.summary.message) {
      BOOST_TEST((r.summary.status == Status::Unsupported));
      BOOST_TEST(r.summary.message.find("points") != std::string::npos);
    }
  }
}
