// request.transient through Solver::solve: the modal superposition against exact references that
// do not use the code under test.
//  - An undamped simply supported Euler-Bernoulli beam under a midspan step force: every excited
//    mode has omega_n = n^2 omega_1, so at t = T1 / 2 all are at their extreme at once and the
//    midspan reaches exactly twice the static deflection F L^3 / (48 EI); at t = T1 it is at rest.
//  - A long damped history ends at the statics; without the static correction that checks every
//    mode's modal force (the load quadrature) against the independent static solve.
//  - Discretized back-ends miss the beam's peak only by their own frequency and static errors,
//    which converge (at first order at least: see the test).
// The contract in each: the reported truncation estimate covers the distance to the reference.
#define BOOST_TEST_MODULE test_transient_solve
#include <boost/test/unit_test.hpp>

#include <fmt/format.h>

#include <cmath>

#include "solver_tests.hpp"
#include "solve_options.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

constexpr double kL = 2.0, kB = 0.05, kH = 0.1, kE = 2.1e11, kRho = 7850.0, kF = -1000.0;
const double kI = kB * kH * kH * kH / 12, kA = kB * kH;
const double kW1 = M_PI * M_PI / (kL * kL) * std::sqrt(kE * kI / (kRho * kA));
const double kT1 = 2 * M_PI / kW1;
const double kStatic = kF * kL * kL * kL / (48 * kE * kI);  // midspan, Euler-Bernoulli

/// A steel Euler-Bernoulli beam of length L and square-or-rectangular section b x h, on `ends`
/// (both), under Fz = F at midspan, with probes at L/2 and `other`, and the transient table.
std::string steel_beam(double L, double b, double h, const char* ends, double F, double other, double tolerance,
                       const std::string& transient) {
  return fmt::format(R"(
[scene]
name = "beam-step"
kind = "beam"
physics = "bending"
theory = "euler-bernoulli"
[geometry]
length = {}
width = {}
height = {}
[material]
E = {}
nu = 0.3
rho = {}
[supports]
x0 = "{}"
xL = "{}"
[[loads]]
x = {}
Fz = {}
[request]
probes = [{}, {}]
tolerance = {}
[request.transient]
{}
)",
                     L, b, h, kE, kRho, ends, ends, L / 2, F, L / 2, other, tolerance, transient);
}

/// The simply supported beam of the closed forms above.
std::string beam(const std::string& transient, double tolerance) {
  return steel_beam(kL, kB, kH, "pinned", kF, 0.5, tolerance, transient);
}

Result solve(const std::string& text, const std::string& backend, const std::string& mesh = "") {
  const Scene s = parse_scene(text, "transient.toml");
  const Solver& solver = registry().get(backend);
  Options opt;
  opt.estimate_error = false;
  return solver.solve(s, mesh.empty() ? testing::default_mesh(solver, s) : Discretization::parse(mesh), opt);
}

}  // namespace

BOOST_AUTO_TEST_CASE(midspan_step_reaches_twice_the_static_deflection_at_half_the_period) {
  for (const bool correction : {true, false}) {
    const std::string tr = fmt::format("duration = {}\nstep = {}\nload = \"step\"\nstatic_correction = {}\nmoments = false",
                                       1.2 * kT1, kT1 / 200, correction);
    const Result r = solve(beam(tr, 1e-5), "exact");
    BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
    const Transient& t = r.transient;
    BOOST_TEST_REQUIRE(!t.empty());
    BOOST_TEST(t.static_correction == correction);
    BOOST_TEST(t.error_estimate <= 1e-5);
    const double peak = t.peaks[0].w;
    BOOST_TEST(std::abs(peak - 2 * kStatic) <= t.error_estimate * std::abs(peak) + 1e-12 * std::abs(peak),
               "peak " << peak << " vs " << 2 * kStatic << ", estimate " << t.error_estimate << ", " << t.modes_used
                       << " modes");
    BOOST_TEST(std::abs(t.peaks[0].time_s - kT1 / 2) <= 1e-6 * kT1, t.peaks[0].time_s << " vs " << kT1 / 2);
    // At rest again at one period (sample 200): the midspan, within the truncation estimate.
    const std::size_t w = 0;  // components of a bending beam: w, theta_y
    BOOST_TEST(std::abs(t.values[0][w][200]) <= t.error_estimate * std::abs(peak) + 1e-12 * std::abs(peak));
  }
}

BOOST_AUTO_TEST_CASE(a_long_damped_history_ends_at_the_statics) {
  const double zeta = 0.1, duration = 30 * kT1;
  for (const bool correction : {true, false}) {
    const std::string tr = fmt::format(
        "duration = {}\nstep = {}\nload = \"step\"\ndamping = {{ modal = {} }}\n"
        "static_correction = {}\nmoments = false",
        duration, kT1 / 20, zeta, correction);
    const Result r = solve(beam(tr, 1e-5), "exact");
    BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
    const Transient& t = r.transient;
    const double decay = std::exp(-zeta * kW1 * duration);
    for (std::size_t p = 0; p < 2; ++p) {
      const double end = t.values[p][0].back(), stat = r.deflections[p].w;
      BOOST_TEST(
          std::abs(end - stat) <= (t.error_estimate + 2 * decay) * std::abs(t.peaks[0].w) + 1e-12 * std::abs(stat),
          "probe " << p << ": " << end << " vs " << stat);
    }
  }
}

BOOST_AUTO_TEST_CASE(a_plate_under_pressure_ends_at_its_statics_without_the_correction) {
  const std::string patch = (R"(
[[pressures]]
p = -1000.0
x = [0.2, 0.7]
y = [0.1, 0.5]
)");
  const std::string request = R"(probes = [[0.5, 0.4], [0.3, 0.2]]
tolerance = 1e-4
[request.transient]
duration = 0.6
step = 0.002
load = { time = [0.0, 0.01], factor = [0.0, 1.0] }
damping = { modal = 0.2 }
static_correction = false)";
  const Scene s = parse_scene(steel_plate(patch, request), "plate.toml");
  Options opt;
  opt.estimate_error = false;
  const Result r = registry().get("exact").solve(s, testing::default_mesh(registry().get("exact"), s), opt);
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const Transient& t = r.transient;
  BOOST_TEST(!t.static_correction);
  // The first mode's period is about 0.015 s: 40 periods at 20 % damping leave nothing.
  for (std::size_t p = 0; p < 2; ++p) {
    const double end = t.values[p][0].back(), stat = r.deflections[p].w;
    BOOST_TEST(std::abs(end - stat) <= t.error_estimate * std::abs(t.peaks[0].w) + 1e-10 * std::abs(stat),
               "probe " << p << ": " << end << " vs " << stat << ", estimate " << t.error_estimate);
  }
}

BOOST_AUTO_TEST_CASE(discretized_back_ends_converge_to_the_peak) {
  const std::string tr = fmt::format("duration = {}\nstep = {}\nload = \"step\"\nmoments = false", 0.6 * kT1, kT1 / 200);
  for (const std::string backend : {"rfem", "difference_eq"}) {
    std::vector<double> errors;
    for (const std::string mesh : {"8", "16", "32"}) {
      const Result r = solve(beam(tr, 1e-6), backend, mesh);
      BOOST_TEST_REQUIRE(!r.transient.empty(), backend << " " << mesh << ": " << r.summary.message);
      errors.push_back(std::abs(r.transient.peaks[0].w / (2 * kStatic) - 1));
    }
    // The peak at T1 / 2 needs every mode in phase: mode n's phase is off by pi n^2 eps_n, with
    // eps_n ~ (n h)^p its frequency error and n^-4 its share, so the sum over the mesh's modes
    // (n up to 1 / h) falls like h, whatever p: first order at least, more while the low modes
    // dominate (rfem p = 2; difference_eq p = 4 showed 2.0 then 1.5).
    for (std::size_t i = 1; i < errors.size(); ++i)
      BOOST_TEST(std::log2(errors[i - 1] / errors[i]) >= 1.0,
                 backend << ": errors " << errors[0] << ", " << errors[1] << ", " << errors[2]);
  }
}

// The moments of the same beam: mode n's moment is in phase with its deflection, so at T1 / 2 the
// moment is twice the static moment everywhere (left of the load M = -F x / 2, sagging positive). At
// the load the series of the modes' static moments falls like 1 / modes, which the estimate covers.
// Asked for (moments = true), they drive the modes to the tolerance.
BOOST_AUTO_TEST_CASE(the_moment_at_half_the_period_is_twice_the_static_moment) {
  const std::string tr = fmt::format("duration = {}\nstep = {}\nload = \"step\"\nmoments = true", 0.6 * kT1, kT1 / 200);
  const Result r = solve(beam(tr, 1e-2), "exact");
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const Transient& t = r.transient;
  BOOST_TEST_REQUIRE(t.moments.size() == 2u);
  BOOST_TEST(t.moment_error_estimate <= 1e-2);
  double peak = 0;
  for (const TransientPeak& p : t.moment_peaks) peak = std::max(peak, std::abs(p.w));
  const double xs[2] = {kL / 2, 0.5};
  for (std::size_t p = 0; p < 2; ++p) {
    const double stat = -kF * xs[p] / 2;
    BOOST_TEST(std::abs(r.deflections[p].forces.My / stat - 1) <= 1e-9);
    BOOST_TEST(std::abs(t.moments[p][100] - 2 * stat) <= t.moment_error_estimate * peak + 1e-9 * std::abs(stat),
               "probe " << p << ": " << t.moments[p][100] << " vs " << 2 * stat << ", estimate "
                        << t.moment_error_estimate << ", " << t.modes_used << " modes");
  }
  BOOST_TEST(std::abs(t.moment_peaks[0].w / (2 * -kF * kL / 4) - 1) <= t.moment_error_estimate);
}

// Each back-end's modes carry moments of their own (exact: the transfer-matrix state; dtfm: the
// prism state's forces; difference_eq: the elements' stiffness forces; rfem: the free body of each
// mode under its inertia loads): without the static correction, a long damped history ends at the
// sum of the modes' static moments, which must be the back-end's own statics (free bodies of the
// loads and reactions), within the truncation estimate.
BOOST_AUTO_TEST_CASE(every_back_end_s_modal_moments_sum_to_its_statics) {
  const double zeta = 0.2, duration = 20 * kT1;
  const std::string tr = fmt::format(
      "duration = {}\nstep = {}\nload = \"step\"\ndamping = {{ modal = {} }}\nstatic_correction = false", duration,
      kT1 / 10, zeta);
  const double decay = std::exp(-zeta * kW1 * duration);
  for (const std::string backend : {"exact", "dtfm", "difference_eq", "rfem"}) {
    const Result r = solve(steel_beam(kL, kB, kH, "clamped", kF, 0.3, 1e-2, tr), backend);
    BOOST_TEST_REQUIRE(r.ok(), backend << ": " << r.summary.message);
    const Transient& t = r.transient;
    BOOST_TEST_REQUIRE(t.moments.size() == 2u, backend << ": " << t.note);
    BOOST_TEST(!t.static_correction);
    double peak = 0;
    for (const TransientPeak& p : t.moment_peaks) peak = std::max(peak, std::abs(p.w));
    for (std::size_t p = 0; p < 2; ++p) {
      BOOST_TEST_REQUIRE(r.deflections[p].has_forces);
      const double end = t.moments[p].back(), stat = r.deflections[p].forces.My;
      BOOST_TEST(std::abs(end - stat) <= (t.moment_error_estimate + 2 * decay) * peak,
                 backend << " probe " << p << ": " << end << " vs " << stat << ", estimate " << t.moment_error_estimate
                         << ", " << t.modes_used << " modes");
    }
  }
}

// The moment histories added by default do not judge the request (issue 54): a 1 m, 20 x 20 mm
// simply supported steel beam under a 100 N midspan step, tolerance 1e-3, gives w's peak (twice the
// static deflection at half the first period) within its estimate and succeeds; the moments carry
// their own estimate, above the tolerance, with a warning. Asked for, the same estimate is the
// status. Before: not-converged on exact and difference_eq, exact doubling its modes to 192 for them.
BOOST_AUTO_TEST_CASE(moments_added_by_default_do_not_fail_the_request) {
  const double L = 1.0, b = 0.02, F = 100.0;
  const double I = b * b * b * b / 12;
  const double stat = F * L * L * L / (48 * kE * I);
  const std::string tr =
      fmt::format("duration = {}\nstep = {}\nload = \"step\"\ndamping = {{ modal = 0.0 }}", 0.0256, 5.33e-5);
  for (const std::string backend : {"exact", "difference_eq"}) {
    const Result r = solve(steel_beam(L, b, b, "pinned", F, 0.25, 1e-3, tr), backend);
    BOOST_TEST(r.ok(), backend << ": " << r.summary.message);
    const Transient& t = r.transient;
    BOOST_TEST_REQUIRE(!t.peaks.empty());
    // exact's peak is the continuum beam's; difference_eq's its own discrete model's (checked above).
    if (backend == "exact") BOOST_TEST(std::abs(t.peaks[0].w / (2 * stat) - 1) <= std::max(t.error_estimate, 1e-9));
    BOOST_TEST_REQUIRE(!t.moments.empty(), backend);
    BOOST_TEST(t.moment_error_estimate > 1e-3, backend);  // the scene's moments do not converge by then
    bool warned = false;
    for (const auto& w : r.summary.warnings) warned = warned || w.find("moment histories' truncation") != std::string::npos;
    BOOST_TEST(warned, backend);
  }
  // Asked for, the same estimate is the status (difference_eq: every mode of its 32 elements, quickly).
  const Result asked = solve(steel_beam(L, b, b, "pinned", F, 0.25, 1e-3, tr + "\nmoments = true"), "difference_eq");
  BOOST_TEST(to_string(asked.summary.status) == "not-converged", asked.summary.message);
}

BOOST_AUTO_TEST_CASE(bad_requests_are_named) {
  const std::string ok = "duration = 0.1\nstep = 0.001\nload = \"step\"";
  expect_input_error(beam("duration = 0.1\nstep = 0.2\nload = \"step\"", 1e-3), "request.transient.step",
                     "must not exceed");
  expect_input_error(beam("duration = 0.1\nstep = 0.001\nload = \"ramp\"", 1e-3), "request.transient.rise", "missing");
  expect_input_error(beam("duration = 0.1\nstep = 0.001\nload = \"step\"\nrise = 0.1", 1e-3), "request.transient.rise",
                     "only a ramp");
  expect_input_error(beam("duration = 0.1\nstep = 0.001\nload = { time = [0.1, 0.2], factor = [0, 1] }", 1e-3),
                     "request.transient.load.time", "must start at 0");
  expect_input_error(beam("duration = 0.1\nstep = 0.001\nload = \"kick\"", 1e-3), "request.transient.load", "unknown");
  expect_input_error(beam(ok + "\ndamping = { modal = -0.1 }", 1e-3), "request.transient.damping.modal", "[0, 100]");
  expect_input_error(beam(ok + "\nmoments = 1", 1e-3), "request.transient.moments", "true or false");
  std::string lossy = beam(ok, 1e-3);
  lossy.replace(lossy.find("nu = 0.3"), 8, "nu = 0.3\nloss_factor = 0.01");
  expect_input_error(lossy, "request.transient.damping", "no causal form");
  std::string no_probes = beam(ok, 1e-3);
  const auto at = no_probes.find("probes = [");
  no_probes.erase(at, no_probes.find('\n', at) - at);
  expect_input_error(no_probes, "request.transient", "needs request.probes");
}

// NAFEMS 13T undamped: a doubly symmetric load on a simply supported square Kirchhoff plate excites
// only odd (m, n), whose frequencies are odd multiples of omega_11, so the centre reaches exactly
// twice its static deflection at T11 / 2 (3.548871 mm = 2 x 1.774436 mm, the Navier series).
BOOST_AUTO_TEST_CASE(thin_plate_13T_undamped_reaches_twice_its_static_deflection) {
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/nafems_13t_thin_plate.toml");
  s.request.transient->damping = TransientRequest::Damping::None;
  s.request.tolerance = 1e-4;
  Options opt;
  opt.estimate_error = false;
  const Result r = registry().get("exact").solve(s, Discretization{}, opt);
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const double D = 2e11 * std::pow(0.05, 3) / (12 * (1 - 0.09)),
               w11 = 2 * M_PI * M_PI / 100 * std::sqrt(D / (8000 * 0.05));
  const double twice = 2 * r.deflections[0].w;
  BOOST_TEST(std::abs(twice / -3.548871e-3 - 1) <= 3e-7);  // the statics against the published-precision value
  const TransientPeak& p = r.transient.peaks[0];
  BOOST_TEST(std::abs(p.w - twice) <= r.transient.error_estimate * std::abs(p.w), p.w << " vs " << twice);
  BOOST_TEST(std::abs(p.time_s - M_PI / w11) <= 1e-6 * M_PI / w11, p.time_s << " vs " << M_PI / w11);
}

// The deep beam's seventh mode is its thickness-shear mode (w = 0, omega^2 = kappa G A / rho I):
// its participation is zero to rounding, which no relative tolerance reaches (the exact back-end's
// shapes failed on it). Its modal force under any transverse load is zero too.
BOOST_AUTO_TEST_CASE(a_mode_without_w_has_zero_participation) {
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/nafems_5t_deep_beam.toml");
  s.request.transient.reset();
  s.request.modes = 8;
  s.request.shapes = ShapeRequest{41, 1};
  const Result r = registry().get("exact").solve(s, Discretization{}, Options{});
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const double G = 2e11 / 2.6, cutoff = std::sqrt(0.8496732026143791 * G * 4.0 / (8000 * 16.0 / 12));
  BOOST_TEST(std::abs(r.frequencies_rad_s[6] / cutoff - 1) <= 1e-10);
  BOOST_TEST(std::abs(r.mode_shapes.participation[6][2]) <= 1e-9 * std::abs(r.mode_shapes.participation[0][2]));
}

// A free-free beam under a step force F at midspan: its statics are a mechanism (refused, said), the
// rigid modes are integrated exactly, and once the damped elastic modes have settled the beam
// moves as F t^2 / (2 m) plus the inertia-relief shape of a half-beam clamped at midspan under -F/L
// with zero mean: w(L/2) - F t^2 / (2m) = F L^3 / (320 EI), w(0) - F t^2 / (2m) = -3 F L^3 / (640 EI).
BOOST_AUTO_TEST_CASE(a_free_beam_accelerates_as_a_rigid_body_plus_its_inertia_relief) {
  const double L = 1.0, b = 0.05, F = 100.0;
  const double EI = kE * std::pow(b, 4) / 12, m = kRho * b * b * L;
  const double w1 = 22.3733 * std::sqrt(EI / (kRho * b * b)) / (L * L), duration = 40 * 2 * M_PI / w1;
  const std::string text = steel_beam(L, b, b, "free", F, 0.0, 1e-6,
                                      fmt::format("duration = {}\nstep = {}\nload = \"step\"\ndamping = {{ modal = 0.3 }}\nmoments = false",
                                                  duration, duration / 100));
  const Result r = solve(text, "exact");
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const Transient& t = r.transient;
  BOOST_TEST(t.rigid_modes == 2);
  BOOST_TEST(!t.static_correction);
  bool said = false;
  for (const auto& w : r.summary.warnings) said = said || w.rfind("not computed: static deflections", 0) == 0;
  BOOST_TEST(said);
  const double rigid = F * duration * duration / (2 * m), slack = t.error_estimate * std::abs(t.peaks[0].w) + 1e-12 * rigid;
  const double mid = F * L * L * L / (320 * EI), end = -3 * F * L * L * L / (640 * EI);
  BOOST_TEST(std::abs(t.values[0][0].back() - rigid - mid) <= slack, t.values[0][0].back() - rigid << " vs " << mid);
  BOOST_TEST(std::abs(t.values[1][0].back() - rigid - end) <= slack, t.values[1][0].back() - rigid << " vs " << end);
}
