// dtfm plates against independent references: Table 2 of the paper, the exact Kirchhoff plate
// (Navier, Levy) and the exact Mindlin plate; Navier's static and dynamic series; counts.
#define BOOST_TEST_MODULE dtfm_plate
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <iomanip>
#include <numbers>
#include <string>

#include "modalbench/dtfm/dtfm.hpp"
#include "modalbench/exact/exact.hpp"

using namespace modalbench;
using namespace modalbench::dtfm;

namespace {

Scene paper_plate() { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml"); }

double rel(double a, double b) { return std::abs(a / b - 1.0); }

std::vector<double> plate_modes(const Scene& s, const char* mesh, int k, ModelOptions o = {}) {
  const PrismModel m = build_model(s, Discretization::parse(mesh), o);
  LineAnalysis la(m);
  const ModeList ml = la.modes(k);
  BOOST_REQUIRE(ml.count_consistent);
  for (auto f : ml.family) BOOST_TEST((f == ModeFamily::Plate));
  return ml.omega_rad_s;
}

double max_rel(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0;
  for (std::size_t i = 0; i < b.size(); ++i) e = std::max(e, rel(a[i], b[i]));
  return e;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(table2)

// Table 2: the prism columns (4, 7, 10 prisms) next to ours. The printed model (Eq. (25)
// springs, beam moduli, no cross terms) reproduces the 7 and 10 prism columns closely although
// its edge supports here hold the edge strips instead of the paper's 5x spring layers; the
// consistent model is printed beside them with the exact values (57), which it approaches.
BOOST_AUTO_TEST_CASE(prism_columns) {
  const double exact57[] = {1692, 3036, 5276, 5425, 6769, 8412, 9009, 11648};
  const double p7[] = {1812.36, 3274.93, 5359.35, 5411.67, 7117.69, 8263.06, 9571.59, 10958.05};
  const double p10[] = {1632.08, 2916.00, 4996.67, 5121.91, 6417.73, 7850.63, 8487.07, 10754.84};
  const Scene s = paper_plate();
  ModelOptions paper;
  paper.layers = LayerModel::Paper;
  const auto w7 = plate_modes(s, "7", 8, paper), w10 = plate_modes(s, "10", 8, paper);
  const auto c4 = plate_modes(s, "4", 8), c7 = plate_modes(s, "7", 8), c10 = plate_modes(s, "10", 8);
  for (int i = 0; i < 8; ++i) {
    BOOST_TEST_MESSAGE("mode " << i + 1 << ": exact " << exact57[i] << " | paper 7: " << p7[i] << " printed model 7: "
                               << w7[i] << " | paper 10: " << p10[i] << " printed model 10: " << w10[i]
                               << " | consistent 4/7/10: " << c4[i] << " / " << c7[i] << " / " << c10[i]);
    BOOST_TEST(rel(w10[i], p10[i]) < 0.015);
    BOOST_TEST(rel(w7[i], p7[i]) < 0.025);
  }
  // The consistent model at 10 strips is closer to the exact column than the paper's 10 prisms.
  double ours = 0, theirs = 0;
  for (int i = 0; i < 8; ++i) {
    ours += rel(c10[i], exact57[i]);
    theirs += rel(p10[i], exact57[i]);
  }
  BOOST_TEST(ours < theirs);
}

// The printed model does not converge to the plate: with more strips it drifts far below the
// exact values (it keeps half of the twisting stiffness and the beam modulus E).
BOOST_AUTO_TEST_CASE(printed_model_does_not_converge) {
  const Scene s = paper_plate();
  ModelOptions paper;
  paper.layers = LayerModel::Paper;
  const auto ex = exact::navier_frequencies(1.0, 0.6, s.plate_D(), s.material.rho * s.geometry.height, 8);
  BOOST_TEST(plate_modes(s, "40", 1, paper)[0] < 0.9 * ex[0]);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(convergence)

// Simply supported and Levy plates (x-edges simply supported; long edges clamped, free, or one
// of each): within 1 % of the exact Kirchhoff frequencies for the first 8 modes at 20 strips,
// and second-order convergence (10 -> 20 -> 40 strips).
BOOST_AUTO_TEST_CASE(kirchhoff_ss_and_levy) {
  const Scene base = paper_plate();
  const double D = base.plate_D(), rho_h = base.material.rho * base.geometry.height;
  struct Edges {
    const char* y0;
    const char* yB;
  };
  for (const Edges& e : {Edges{"pinned", "pinned"}, Edges{"clamped", "clamped"}, Edges{"free", "free"},
                         Edges{"clamped", "free"}}) {
    Scene s = base;
    s.y0 = Support::named(e.y0);
    s.yB = Support::named(e.yB);
    const auto ex = exact::levy_frequencies(1.0, 0.6, D, s.material.nu, rho_h, {s.y0.translational, s.y0.rotational},
                                            {s.yB.translational, s.yB.rotational}, 8);
    const double e10 = max_rel(plate_modes(s, "10", 8), ex.omega_rad_s);
    const double e20 = max_rel(plate_modes(s, "20", 8), ex.omega_rad_s);
    BOOST_TEST_CONTEXT("SS-" << e.y0 << "-SS-" << e.yB) {
      BOOST_TEST(e20 < 0.01);
      BOOST_TEST(e10 > e20);
    }
    // 40 strips (the observed order) only in optimized builds: the sanitizer build is Debug and
    // takes over ten minutes on the four 40-strip Levy plates.
#ifdef NDEBUG
    const double e40 = max_rel(plate_modes(s, "40", 8), ex.omega_rad_s);
    BOOST_TEST_MESSAGE("SS-" << e.y0 << "-SS-" << e.yB << ": max error 10/20/40 strips " << 100 * e10 << " / "
                             << 100 * e20 << " / " << 100 * e40 << " %");
    BOOST_TEST_CONTEXT("SS-" << e.y0 << "-SS-" << e.yB) { BOOST_TEST(std::log2(e20 / e40) > 1.7); }
#else
    BOOST_TEST_MESSAGE("SS-" << e.y0 << "-SS-" << e.yB << ": max error 10/20 strips " << 100 * e10 << " / "
                             << 100 * e20 << " % (40 strips in optimized builds only)");
#endif
  }
}

// A Mindlin scene gives Mindlin strips (transverse shear kappa G h in strips and layers, rotary
// inertia): it converges to the exact Mindlin plate (all branches in this range are bending).
BOOST_AUTO_TEST_CASE(mindlin_ss) {
  Scene s = paper_plate();
  s.theory = Theory::Mindlin;
  const auto ex = exact::mindlin_ss_frequencies(1.0, 0.6, 0.03, s.material.E, s.material.nu, s.material.G,
                                                s.material.kappa, s.material.rho, 8);
  const double e20 = max_rel(plate_modes(s, "20", 8), ex);
  const double e40 = max_rel(plate_modes(s, "40", 8), ex);
  BOOST_TEST_MESSAGE("Mindlin: max error 20/40 strips " << 100 * e20 << " / " << 100 * e40 << " %");
  BOOST_TEST(e20 < 0.01);
  BOOST_TEST(e40 < e20 / 3);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(spectrum)

// The paper's plate (10 strips): the first 100 modes are finite, ordered and counted.
BOOST_AUTO_TEST_CASE(hundred_modes) {
  const Scene s = paper_plate();
  const PrismModel m = build_model(s, Discretization::parse("10"));
  LineAnalysis la(m);
  const ModeList ml = la.modes(100);
  BOOST_REQUIRE(ml.omega_rad_s.size() == 100u);
  BOOST_TEST(ml.count_consistent);
  for (std::size_t i = 0; i < 100; ++i) {
    BOOST_TEST(std::isfinite(ml.omega_rad_s[i]));
    if (i) BOOST_TEST(ml.omega_rad_s[i] >= ml.omega_rad_s[i - 1]);
  }
  for (std::size_t k : {1u, 37u, 100u}) {
    const double lam = std::pow(ml.omega_rad_s[k - 1], 2);
    BOOST_TEST(la.count_below(lam * (1 + 1e-8)) >= static_cast<int>(k));
    BOOST_TEST(la.count_below(lam * (1 - 1e-8)) <= static_cast<int>(k) - 1);
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(elongated)

// Regression: a 30 m x 0.6 m simply supported Kirchhoff plate. Its (m, 1) modes crowd just above
// the first (1246.4 / 1244.9 rad/s for m = 2), so det K spans e^26 across the interval that
// isolates mode 1, and Brent's first secant step landed 4e-13 (relative) from the bracket end,
// below the lambda resolution of K: the repeated determinant value passed for the rounding floor
// and the bracket end, 1246.129 rad/s at every mesh from 16 strips on, was returned as mode 1
// (the true one missed; the reproducibility check flagged it). Each of the (m, 1) modes, m = 1..3,
// must be the one nearest its Navier value, omega_mn = pi^2 (m^2 / a^2 + n^2 / b^2) sqrt(D / rho h),
// D = E h^3 / (12 (1 - nu^2)), below it (the strips converge from below here) and converge to it
// at second order.
BOOST_AUTO_TEST_CASE(thirty_metre_strip_first_modes_against_navier) {
  const Scene s = parse_scene(R"(
[scene]
name = "elongated"
kind = "plate"
physics = "bending"
theory = "kirchhoff"
[geometry]
length = 30.0
width = 0.6
height = 0.03
[material]
E = 2.0e11
nu = 0.3
rho = 8000.0
kappa = 1.0
[supports]
x0 = "pinned"
xL = "pinned"
y0 = "pinned"
yB = "pinned"
[request]
modes = 8
)",
                              "elongated plate (test)");
  const double a = s.geometry.length, b = s.geometry.width, h = s.geometry.height;
  const double D = s.material.E * h * h * h / (12.0 * (1.0 - s.material.nu * s.material.nu));
  const double pi2 = std::numbers::pi * std::numbers::pi;
  auto navier = [&](int m, int n) {
    return pi2 * (m * m / (a * a) + n * n / (b * b)) * std::sqrt(D / (s.material.rho * h));
  };
  const int meshes[] = {16, 24, 38};
  double err[3][3];  // [mesh][m - 1], relative, exact minus computed
  for (int i = 0; i < 3; ++i) {
    const PrismModel model = build_model(s, Discretization{{meshes[i]}});
    LineAnalysis la(model);
    const ModeList ml = la.modes(s.request.modes);
    BOOST_TEST_CONTEXT(meshes[i] << " strips") {
      BOOST_TEST(ml.count_consistent, ml.count_message);
      BOOST_REQUIRE(ml.omega_rad_s.size() == 8u);
      for (int m = 1; m <= 3; ++m) {
        const double w = ml.omega_rad_s[static_cast<std::size_t>(m - 1)], ex = navier(m, 1);
        BOOST_TEST_MESSAGE(meshes[i] << " strips: mode " << m << " " << std::setprecision(10) << w << " rad/s, Navier ("
                                     << m << ", 1) " << ex);
        // Nearer its own Navier value than half the gap to the next one: the right mode.
        BOOST_TEST(std::abs(w - ex) < 0.5 * (navier(m + 1, 1) - ex));
        BOOST_TEST(w < ex);
        err[i][m - 1] = 1.0 - w / ex;
      }
    }
    // Through the Solver interface: the same numbers pass the back-end's own checks.
    if (meshes[i] == 24) {
      const Result r = DtfmSolver().solve(s, Discretization{{meshes[i]}}, {});
      BOOST_TEST((r.summary.status == Status::Success), r.summary.message);
    }
  }
  for (int m = 0; m < 3; ++m)
    for (int i = 0; i + 1 < 3; ++i) {
      const double order =
          std::log(err[i][m] / err[i + 1][m]) / std::log(static_cast<double>(meshes[i + 1]) / meshes[i]);
      BOOST_TEST_CONTEXT("mode " << m + 1 << ", " << meshes[i] << " -> " << meshes[i + 1] << " strips") {
        BOOST_TEST(std::abs(order - 2.0) < 0.1);
      }
    }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(responses)

// Static deflection and receptance converge to Navier's series (second order), with the
// slopes theta_x = dw/dy and theta_y = -dw/dx; the receptance is reciprocal.
BOOST_AUTO_TEST_CASE(navier_statics_and_receptance) {
  const Scene s = paper_plate();
  const double D = s.plate_D(), rho_h = s.material.rho * s.geometry.height;
  const auto w_drive = exact::navier_static(1.0, 0.6, D, {{0.4, 0.2, -1000.0}}, 0.4, 0.2, 2000);
  const auto w_off = exact::navier_static(1.0, 0.6, D, {{0.4, 0.2, -1000.0}}, 0.5, 0.3, 400);
  std::vector<double> err_off, err_h;
  for (const char* mesh : {"20", "40"}) {
    const PrismModel m = build_model(s, Discretization::parse(mesh));
    LineAnalysis la(m);
    const auto d = la.statics(s.loads, s.request.probes);
    err_off.push_back(rel(d[1].w, w_off[0]));
    BOOST_TEST_MESSAGE(mesh << " strips: w(load) " << d[0].w << " vs " << w_drive[0] << ", w(0.5, 0.3) " << d[1].w
                            << " vs " << w_off[0]);
    if (std::string(mesh) == "40") {
      BOOST_TEST(rel(d[0].w, w_drive[0]) < 0.006);  // the driving point converges slowest (log singularity)
      BOOST_TEST(err_off.back() < 0.002);
      BOOST_TEST(rel(d[1].theta_x, w_off[2]) < 0.005);
      BOOST_TEST(rel(d[1].theta_y, -w_off[1]) < 0.005);
    }
    double eh = 0;
    for (double omega : {500.0, 2500.0, 7000.0}) {
      const auto H = la.receptance({0.4, 0.2}, {0.5, 0.3}, {omega}, 0.0)[0];
      const auto E = exact::navier_receptance(1.0, 0.6, D, rho_h, 0.0, 0.4, 0.2, 0.5, 0.3, omega, 400);
      eh = std::max(eh, rel(H.real(), E.real()));
      const auto Hr = la.receptance({0.5, 0.3}, {0.4, 0.2}, {omega}, 0.0)[0];
      BOOST_TEST(std::abs(H - Hr) < 1e-9 * std::abs(H));
    }
    err_h.push_back(eh);
  }
  BOOST_TEST(err_off[1] < err_off[0] / 3);
  BOOST_TEST(err_h[1] < err_h[0] / 3);
  BOOST_TEST(err_h[1] < 0.005);
}

// Damped receptance (structural damping) against Navier's damped series at 40 strips.
BOOST_AUTO_TEST_CASE(damped_receptance) {
  const Scene s = paper_plate();
  const double D = s.plate_D(), rho_h = s.material.rho * s.geometry.height, eta = 0.05;
  const PrismModel m = build_model(s, Discretization::parse("40"));
  LineAnalysis la(m);
  for (double omega : {1692.5, 4000.0}) {
    const auto H = la.receptance({0.4, 0.2}, {0.5, 0.3}, {omega}, eta)[0];
    const auto E = exact::navier_receptance(1.0, 0.6, D, rho_h, eta, 0.4, 0.2, 0.5, 0.3, omega, 400);
    BOOST_TEST_CONTEXT("omega " << omega) { BOOST_TEST(std::abs(H - E) < 0.01 * std::abs(E)); }
  }
}

BOOST_AUTO_TEST_SUITE_END()
