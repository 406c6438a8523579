// Stepped beams ([[segments]]) against references written out here, independently of the code:
//   - a two-piece bar, clamped-free: A1 cos(k l1) cos(k l2) - A2 sin(k l1) sin(k l2) = 0 (one
//     material, k = omega sqrt(rho / E)), from u and N continuous at the step;
//   - a stepped Timoshenko cantilever under a tip load P: w(L) = -P sum_i [((L - a)^3 - (L - b)^3) /
//     (3 EI_i) + (b - a) / kGA_i], the slope from sum_i ((L - a)^2 - (L - b)^2) / (2 EI_i);
//   - a stepped Euler-Bernoulli beam with a point mass: a cubic Hermite finite-element model written
//     here, Richardson-extrapolated from three meshes (frequencies converge at h^4); its own two
//     extrapolations bound its error;
//   - a beam cut into identical pieces is the uniform beam;
//   - under gravity the reactions carry the pieces' weight.
// exact is held to 1e-9 where the reference is a closed form; rfem to its own error estimate, and
// its error falls at second order when steps sit on its nodes.
#define BOOST_TEST_MODULE segments
#include <boost/test/unit_test.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <vector>

#include "solver_tests.hpp"
#include "solve_options.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double E = 2.1e11, nu = 0.3, rho = 7850.0;

std::string stepped(const std::string& physics, const std::string& theory, const std::string& pieces,
                    const std::string& supports, const std::string& extra, int modes) {
  return "[scene]\nname = \"stepped\"\nkind = \"beam\"\nphysics = \"" + physics + "\"\ntheory = \"" + theory +
         "\"\n[geometry]\nlength = 1.0\n" + pieces +
         "\n[material]\nE = 2.1e11\nnu = 0.3\nrho = 7850.0\n[supports]\n" + supports + "\n" + extra +
         "\n[request]\nmodes = " + std::to_string(modes) + "\n";
}

std::string piece(double length, const std::string& section, const std::string& material = "") {
  return "[[segments]]\nlength = " + std::to_string(length) + "\nsection = " + section + "\n" +
         (material.empty() ? "" : "material = " + material + "\n");
}

const std::string kThin = "{ shape = \"circle\", diameter = 0.025 }", kThick = "{ shape = \"circle\", diameter = 0.04 }";

double circle_area(double d) { return kPi * d * d / 4; }
double circle_I(double d) { return kPi * std::pow(d, 4) / 64; }

/// Natural frequencies (rad/s) of an Euler-Bernoulli beam of cubic Hermite elements with consistent
/// mass: pinned at both ends, `n` elements of length 1/n, EI and rho A per element from `props`, a
/// point mass at node `mass_node`.
std::vector<double> hermite_frequencies(int n, const std::function<std::pair<double, double>(double)>& props,
                                        double point_mass, int mass_node, int k) {
  const int dofs = 2 * (n + 1);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(dofs, dofs), M = Eigen::MatrixXd::Zero(dofs, dofs);
  const double h = 1.0 / n;
  for (int e = 0; e < n; ++e) {
    const auto [EI, rhoA] = props((e + 0.5) * h);
    Eigen::Matrix4d ke, me;
    ke << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h, 6 * h, 2 * h * h, -6 * h,
        4 * h * h;
    me << 156, 22 * h, 54, -13 * h, 22 * h, 4 * h * h, 13 * h, -3 * h * h, 54, 13 * h, 156, -22 * h, -13 * h, -3 * h * h,
        -22 * h, 4 * h * h;
    K.block<4, 4>(2 * e, 2 * e) += EI / (h * h * h) * ke;
    M.block<4, 4>(2 * e, 2 * e) += rhoA * h / 420 * me;
  }
  M(2 * mass_node, 2 * mass_node) += point_mass;
  // Pinned ends: w = 0 at nodes 0 and n.
  std::vector<int> keep;
  for (int i = 0; i < dofs; ++i)
    if (i != 0 && i != 2 * n) keep.push_back(i);
  Eigen::MatrixXd Kr(keep.size(), keep.size()), Mr(keep.size(), keep.size());
  for (std::size_t i = 0; i < keep.size(); ++i)
    for (std::size_t j = 0; j < keep.size(); ++j) {
      Kr(i, j) = K(keep[i], keep[j]);
      Mr(i, j) = M(keep[i], keep[j]);
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kr, Mr);
  std::vector<double> out;
  for (int i = 0; i < k; ++i) out.push_back(std::sqrt(es.eigenvalues()[i]));
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(parsing_pieces_sections_and_materials) {
  const std::string tube = "{ shape = \"tube\", outer_diameter = 0.05, inner_diameter = 0.03 }";
  const Scene s = parse_scene(stepped("spatial", "timoshenko", piece(0.25, kThick) + piece(0.5, tube, "{ E = 7.0e10, rho = 2700.0 }") + piece(0.25, kThick),
                                      "x0 = \"pinned\"\nxL = \"pinned\"", "", 4),
                              "ok.toml");
  BOOST_REQUIRE_EQUAL(s.segments.size(), 3u);
  BOOST_TEST(s.is_stepped());
  BOOST_TEST(s.segments[1].x_from == 0.25);
  BOOST_TEST(s.segments[2].x_to == 1.0);
  // Cowper's coefficient per piece's shape; E overridden with nu kept (G follows), rho overridden.
  BOOST_TEST(rel(s.segments[0].material.kappa, 6 * (1 + nu) / (7 + 6 * nu)) < 1e-15);
  const double m = 0.6, m2 = m * m;
  BOOST_TEST(rel(s.segments[1].material.kappa,
                 6 * (1 + nu) * (1 + m2) * (1 + m2) / ((7 + 6 * nu) * (1 + m2) * (1 + m2) + (20 + 12 * nu) * m2)) < 1e-15);
  BOOST_TEST(s.segments[1].material.E == 7.0e10);
  BOOST_TEST(rel(s.segments[1].material.G, 7.0e10 / (2 * (1 + nu))) < 1e-15);
  BOOST_TEST(s.segments[1].material.rho == 2700.0);
  BOOST_TEST(s.segments[2].material.E == E);
  BOOST_TEST(s.geometry.height == 0.05);  // the largest extent

  const std::string sup = "x0 = \"pinned\"\nxL = \"pinned\"";
  expect_input_error(stepped("bending", "timoshenko", piece(0.25, kThick) + piece(0.5, kThick), sup, "", 2), "segments",
                     "add up to 0.75 m");
  expect_input_error(stepped("bending", "timoshenko", "width = 0.1\n" + piece(1.0, kThick), sup, "", 2), "geometry.width",
                     "per piece");
  expect_input_error(stepped("bending", "timoshenko", "[[segments]]\nlength = 1.0\n", sup, "", 2), "segments[0].section",
                     "missing");
  expect_input_error(stepped("bending", "timoshenko",
                             piece(0.5, kThick) + piece(0.5, "{ shape = \"tube\", outer_diameter = 0.03, inner_diameter = 0.03 }"),
                             sup, "", 2),
                     "segments[1].section.inner_diameter", "below outer_diameter");
  expect_input_error(stepped("bending", "timoshenko", piece(0.5, kThick) + piece(0.5, kThick, "{ E = -1.0 }"), sup, "", 2),
                     "segments[1].material.E", "must be > 0");
  expect_input_error(stepped("bending", "timoshenko", piece(0.5, kThick) + piece(0.5, kThick, "{ loss_factor = 0.1 }"), sup,
                         "", 2),
                     "segments[1].material.loss_factor", "unknown key");
  expect_input_error(stepped("bending", "timoshenko",
                             piece(0.5, kThick) + piece(0.5, "{ shape = \"general\", area = 1e-3, Iy = 1e-7, Iz = 1e-7, J = 2e-7 }"),
                             sup, "", 2),
                     "segments[1].material.kappa", "general section");
}

BOOST_AUTO_TEST_CASE(two_piece_bar_axial_closed_form) {
  const double l1 = 0.4, l2 = 0.6, A1 = circle_area(0.04), A2 = circle_area(0.025), c = std::sqrt(E / rho);
  const auto k = roots([&](double x) { return A1 * std::cos(x * l1) * std::cos(x * l2) - A2 * std::sin(x * l1) * std::sin(x * l2); },
                       0.1, 40.0, 3);
  BOOST_REQUIRE_EQUAL(k.size(), 3u);
  const Scene s = parse_scene(stepped("planar", "euler-bernoulli", piece(l1, kThick) + piece(l2, kThin),
                                      "x0 = \"clamped\"\nxL = \"free\"", "", 40),
                              "bar.toml");
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  std::vector<double> axial;
  for (std::size_t i = 0; i < ex.frequencies_rad_s.size(); ++i)
    if (ex.mode_families[i] == ModeFamily::Axial) axial.push_back(ex.frequencies_rad_s[i]);
  BOOST_REQUIRE_GE(axial.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    BOOST_TEST_INFO("axial mode " << i + 1 << ": exact " << axial[i] << ", closed form " << k[i] * c);
    BOOST_TEST(rel(axial[i], k[i] * c) < 1e-9);
  }
}

BOOST_AUTO_TEST_CASE(stepped_cantilever_tip_load) {
  // 0.3 m of 40 mm, then 0.7 m of 25 mm, Timoshenko with Cowper's kappa; Fz = -P at the tip.
  const double P = 100.0, L = 1.0, G = E / (2 * (1 + nu)), kappa = 6 * (1 + nu) / (7 + 6 * nu);
  const std::vector<std::array<double, 3>> parts = {{0.0, 0.3, 0.04}, {0.3, 1.0, 0.025}};
  double w = 0, slope = 0;
  for (const auto& [a, b, d] : parts) {
    w -= P * ((std::pow(L - a, 3) - std::pow(L - b, 3)) / (3 * E * circle_I(d)) + (b - a) / (kappa * G * circle_area(d)));
    slope -= P * ((L - a) * (L - a) - (L - b) * (L - b)) / (2 * E * circle_I(d));  // phi = dw/dx of the bending part
  }
  const Scene s = parse_scene(stepped("bending", "timoshenko", piece(0.3, kThick) + piece(0.7, kThin),
                                      "x0 = \"clamped\"\nxL = \"free\"", "[[loads]]\nx = 1.0\nFz = -100.0", 2) +
                                  "probes = [1.0]\n",
                              "cantilever.toml");
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  BOOST_REQUIRE_EQUAL(ex.deflections.size(), 1u);
  BOOST_TEST(rel(ex.deflections[0].w, w) < 1e-9);
  BOOST_TEST(rel(ex.deflections[0].theta_y, -slope) < 1e-9);  // theta_y = -phi
  const Result rf = registry().get("rfem").solve(s, testing::default_mesh(registry().get("rfem"), s), Options{});
  BOOST_TEST_CONTEXT("rfem " << rf.summary.mesh << ": " << rf.summary.message) {
    BOOST_REQUIRE(rf.summary.status == Status::Success);
    BOOST_TEST(std::abs(rf.deflections[0].w / w - 1) <= rf.summary.error_estimate.deflections);
  }
}

BOOST_AUTO_TEST_CASE(stepped_beam_with_mass_against_hermite_elements) {
  // Pinned-pinned Euler-Bernoulli: 0.3 m of 40 mm, 0.4 m of 60 mm, 0.3 m of 40 mm, 5 kg at x = 0.5.
  const double Mp = 5.0;
  auto props = [](double x) {
    const double d = (x > 0.3 && x < 0.7) ? 0.06 : 0.04;
    return std::pair{E * circle_I(d), rho * circle_area(d)};
  };
  const int k = 4;
  std::vector<std::vector<double>> fe;
  for (int n : {20, 40, 80}) fe.push_back(hermite_frequencies(n, props, Mp, n / 2, k));
  const Scene s = parse_scene(stepped("bending", "euler-bernoulli",
                                      piece(0.3, kThick) + piece(0.4, "{ shape = \"circle\", diameter = 0.06 }") + piece(0.3, kThick),
                                      "x0 = \"pinned\"\nxL = \"pinned\"", "[[masses]]\nx = 0.5\nmass = 5.0", k),
                              "stepped_mass.toml");
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  for (int i = 0; i < k; ++i) {
    // Richardson at order 4 from (20, 40) and (40, 80); their difference bounds the finer one's error.
    const double r1 = (16 * fe[1][i] - fe[0][i]) / 15, r2 = (16 * fe[2][i] - fe[1][i]) / 15;
    const double bound = std::max(3 * std::abs(r2 - r1) / std::abs(r2), 1e-12);
    BOOST_TEST_INFO("mode " << i + 1 << ": exact " << ex.frequencies_rad_s[i] << ", Hermite extrapolated " << r2
                            << " (+- " << bound << ")");
    BOOST_TEST(rel(ex.frequencies_rad_s[i], r2) <= bound);
    BOOST_TEST(bound < 1e-6);  // the reference is sharp enough to test against
  }
  const Result rf = registry().get("rfem").solve(s, testing::default_mesh(registry().get("rfem"), s), Options{});
  BOOST_TEST_CONTEXT("rfem " << rf.summary.mesh << ": " << rf.summary.message) {
    BOOST_REQUIRE(rf.summary.status == Status::Success);
    for (int i = 0; i < k; ++i)
      BOOST_TEST(rel(rf.frequencies_rad_s[i], ex.frequencies_rad_s[i]) <= rf.summary.error_estimate.frequencies);
  }
}

BOOST_AUTO_TEST_CASE(rfem_converges_at_second_order_with_steps_on_nodes) {
  const Scene s = parse_scene(stepped("bending", "timoshenko", piece(0.25, kThick) + piece(0.5, kThin) + piece(0.25, kThick),
                                      "x0 = \"clamped\"\nxL = \"free\"", "", 3),
                              "order.toml");
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  std::vector<double> err;
  for (int n : {32, 64, 128, 256}) {
    Options o;
    o.estimate_error = false;
    const Result r = registry().get("rfem").solve(s, Discretization{{n}}, o);
    BOOST_REQUIRE(r.summary.status == Status::Success);
    double worst = 0;
    for (int i = 0; i < 3; ++i) worst = std::max(worst, rel(r.frequencies_rad_s[i], ex.frequencies_rad_s[i]));
    err.push_back(worst);
  }
  for (std::size_t i = 1; i < err.size(); ++i) {
    const double order = std::log2(err[i - 1] / err[i]);
    BOOST_TEST_INFO("errors " << err[i - 1] << " -> " << err[i]);
    BOOST_TEST(std::abs(order - 2.0) < 0.3);
  }
}

BOOST_AUTO_TEST_CASE(identical_pieces_are_the_uniform_beam) {
  const std::string sup = "x0 = \"clamped\"\nxL = { translational = 1e5, rotational = 0.0, axial = 1e6, torsional = 10.0 }";
  const std::string load = "[[loads]]\nx = 0.6\nFz = -50.0";
  const Scene cut = parse_scene(stepped("spatial", "timoshenko", piece(0.3, kThick) + piece(0.7, kThick), sup, load, 8) +
                                    "probes = [0.45, 1.0]\n",
                                "cut.toml");
  const Scene one = parse_scene(stepped("spatial", "timoshenko", piece(1.0, kThick), sup, load, 8) + "probes = [0.45, 1.0]\n",
                                "one.toml");
  for (const std::string b : {"exact", "rfem"}) {
    const Discretization mesh = b == "rfem" ? Discretization{{64}} : Discretization{};
    Options o;
    o.estimate_error = false;
    const Result a = registry().get(b).solve(cut, mesh, o), c = registry().get(b).solve(one, mesh, o);
    BOOST_TEST_CONTEXT(b) {
      BOOST_REQUIRE(a.summary.status == Status::Success);
      BOOST_REQUIRE(c.summary.status == Status::Success);
      for (std::size_t i = 0; i < c.frequencies_rad_s.size(); ++i) BOOST_TEST(rel(a.frequencies_rad_s[i], c.frequencies_rad_s[i]) < 1e-11);
      for (std::size_t i = 0; i < c.deflections.size(); ++i) BOOST_TEST(rel(a.deflections[i].w, c.deflections[i].w) < 1e-11);
    }
  }
}

BOOST_AUTO_TEST_CASE(gravity_reactions_carry_each_piece) {
  const Scene s = parse_scene(stepped("bending", "euler-bernoulli", piece(0.3, kThick) + piece(0.7, kThin),
                                      "x0 = \"pinned\"\nxL = \"pinned\"", "[gravity]\ng = [0.0, 0.0, -9.81]", 1) +
                                  "probes = [0.5]\n",
                              "weight.toml");
  const double weight = 9.81 * rho * (0.3 * circle_area(0.04) + 0.7 * circle_area(0.025));
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  BOOST_REQUIRE_EQUAL(ex.reactions.size(), 2u);
  BOOST_TEST(rel(ex.reactions[0].force[2] + ex.reactions[1].force[2], weight) < 1e-12);
  // Moments about x = 0: the right reaction carries the pieces' first moment over L.
  const double first = 9.81 * rho * (0.3 * 0.15 * circle_area(0.04) + 0.7 * 0.65 * circle_area(0.025));
  BOOST_TEST(rel(ex.reactions[1].force[2], first) < 1e-12);
}

BOOST_AUTO_TEST_CASE(backends_without_steps_say_so) {
  const Scene s = parse_scene(stepped("bending", "euler-bernoulli", piece(0.3, kThick) + piece(0.7, kThin),
                                      "x0 = \"pinned\"\nxL = \"pinned\"", "", 2),
                              "refused.toml");
  for (const std::string b : {"difference_eq"}) {  // dtfm models steps (tests/dtfm/test_dtfm_structures)
    const Result r = registry().get(b).solve(s, {}, Options{});
    BOOST_TEST_CONTEXT(b << ": " << r.summary.message) {
      BOOST_TEST((r.summary.status == Status::Unsupported));
      BOOST_TEST(r.summary.message.find("stepped") != std::string::npos);
    }
  }
}
