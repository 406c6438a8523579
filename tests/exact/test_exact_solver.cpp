// The `exact` back-end through the Solver interface and the built-in scene files.
#define BOOST_TEST_MODULE exact_solver
#include <boost/test/unit_test.hpp>

#include "modalbench/exact/exact.hpp"

using namespace modalbench;

namespace {
Scene scene(const char* file) { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + file); }
}  // namespace

BOOST_AUTO_TEST_CASE(paper_fixed_beam_scene) {
  exact::ExactSolver s;
  const Result r = s.solve(scene("paper_fixed_beam.toml"), {}, {});
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const double ref[] = {6211.15, 13848.36, 22763.93, 32186.47, 41982.17, 47172.88};
  BOOST_REQUIRE(r.frequencies_rad_s.size() == 6u);
  for (int i = 0; i < 6; ++i) {
    BOOST_TEST(std::abs(r.frequencies_rad_s[i] / ref[i] - 1) < 1e-6);
    BOOST_TEST((r.mode_families[i] == ModeFamily::BendingXZ));
  }
  BOOST_TEST(r.deflections.size() == 2u);
  BOOST_TEST(r.frf.size() + 0u <= 400u);
  BOOST_TEST(r.frf.size() >= 399u);
  // Clamped-clamped Timoshenko, central force F: w(L/2) = F L^3/(192 EI) + F L/(4 kGA).
  const double E = 2e11, G = 8e10, A = 0.0625, I = 0.25 * std::pow(0.25, 3) / 12, F = -1000, L = 1;
  BOOST_TEST(std::abs(r.deflections[1].w / (F * L * L * L / (192 * E * I) + F * L / (4 * G * A)) - 1) < 1e-10);
}

BOOST_AUTO_TEST_CASE(paper_plate_scene) {
  exact::ExactSolver s;
  const Scene sc = scene("paper_ss_plate.toml");
  const Result r = s.solve(sc, {}, {});
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  BOOST_TEST(r.frequencies_rad_s.size() == 8u);
  BOOST_TEST(std::abs(r.frequencies_rad_s[0] - 1692.45) < 0.01);
  const Capability c = s.supports(sc);
  BOOST_TEST((c.modes && c.statics && c.frf));  // Navier: all three
  BOOST_TEST(r.deflections.size() == 2u);
  BOOST_TEST(r.frf.size() == 400u);
  // A clamped-edge Levy plate has exact frequencies only: statics are refused with a reason.
  Scene levy = sc;
  levy.y0 = levy.yB = Support::named("clamped");
  const Result rl = s.solve(levy, {}, {});
  BOOST_TEST(rl.ok());
  BOOST_TEST(rl.deflections.empty());
  BOOST_TEST(!rl.summary.warnings.empty());
  BOOST_TEST(rl.summary.warnings[0].find("not computed: static deflections, FRF") != std::string::npos);
}

// A 30 x 0.6 m plate strip (aspect 50): the Navier FRF series is truncated at one wavenumber in both
// directions and grown to the tolerance. A square truncation of 300 x 300 left the long direction
// unresolved (its tail estimate 430 times the static flexibility: not-converged). The reported
// tail bounds the distance to a ten times finer truncation of the same series.
BOOST_AUTO_TEST_CASE(an_elongated_plate_s_frf_series_follows_its_aspect_and_the_tolerance) {
  Scene sc = scene("paper_ss_plate.toml");
  sc.geometry.length = 30.0;
  sc.geometry.width = 0.6;
  sc.request.probes.clear();
  sc.request.frf = FrfRequest{{7.3, 0.2}, {11.1, 0.35}, 10.0, 2000.0, 5};
  exact::ExactSolver s;
  const Result r = s.solve(sc, {}, {});
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const double M = r.summary.diagnostic("frf_series_terms_m"), N = r.summary.diagnostic("frf_series_terms_n");
  BOOST_TEST(std::abs(M / 30.0 / (N / 0.6) - 1) < 0.05);  // one wavenumber both ways
  const double a = 30.0, b = 0.6, h = sc.geometry.height, E = sc.material.E, nu = sc.material.nu;
  const double D = E * h * h * h / (12 * (1 - nu * nu)), rho_h = sc.material.rho * h;
  const double flex = std::abs(exact::navier_receptance(a, b, D, rho_h, 0.0, 7.3, 0.2, 11.1, 0.35, 0.0, 30000, 600, nullptr));
  const double tail = r.summary.diagnostic("frf_series_tail_relative_to_flexibility");
  BOOST_TEST(tail <= sc.request.tolerance);
  BOOST_TEST_REQUIRE(r.frf.size() == 5u);
  for (const FrfSample& f : r.frf) {
    const auto fine = exact::navier_receptance(a, b, D, rho_h, sc.material.loss_factor, 7.3, 0.2, 11.1, 0.35,
                                               f.omega_rad_s, 30000, 600, nullptr);
    BOOST_TEST(std::abs(f.receptance - fine) <= tail * flex, f.omega_rad_s << ": " << f.receptance << " vs " << fine);
  }
}

// A square spatial beam: bending in x-z and x-y coincide (multiplicity 2 with both labels),
// axial and torsion modes are interleaved with their own labels.
BOOST_AUTO_TEST_CASE(spatial_square_beam_families) {
  Scene sc = scene("paper_fixed_beam.toml");
  sc.physics = Physics::Spatial;
  sc.request.modes = 10;
  sc.request.frf.reset();
  exact::ExactSolver s;
  const Result r = s.solve(sc, {}, {});
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  int xz = 0, xy = 0, ax = 0, tor = 0;
  for (auto f : r.mode_families) {
    xz += f == ModeFamily::BendingXZ;
    xy += f == ModeFamily::BendingXY;
    ax += f == ModeFamily::Axial;
    tor += f == ModeFamily::Torsion;
  }
  BOOST_TEST(xz == xy);
  BOOST_TEST(ax >= 1);
  BOOST_TEST(tor >= 1);
  BOOST_TEST(r.frequencies_rad_s[0] == r.frequencies_rad_s[1], boost::test_tools::tolerance(1e-12));
  // Clamped-clamped torsion: pi/L sqrt(GJ / (rho Ip)); the square's J = 0.1406 a^4 (Roark).
  const Section sec = sc.section();
  BOOST_TEST(std::abs(sec.J / (0.140577 * std::pow(0.25, 4)) - 1) < 1e-5);
}

BOOST_AUTO_TEST_CASE(unsupported_and_invalid) {
  exact::ExactSolver s;
  Scene plate = scene("paper_ss_plate.toml");
  plate.x0 = plate.xL = plate.y0 = plate.yB = Support::named("clamped");
  const Result r = s.solve(plate, {}, {});
  BOOST_TEST((r.summary.status == Status::Unsupported));
  BOOST_TEST(r.summary.message.find("Levy") != std::string::npos);
  const Result bad = s.solve(scene("paper_fixed_beam.toml"), Discretization::parse("8"), {});
  BOOST_TEST((bad.summary.status == Status::InvalidInput));
  BOOST_TEST(bad.summary.message.find("--mesh") != std::string::npos);
  // A static load on a mechanism: refused with the reason, modes still given.
  Scene mech = scene("paper_fixed_beam.toml");
  mech.x0 = mech.xL = Support::named("free");
  mech.request.frf.reset();
  const Result m = s.solve(mech, {}, {});
  BOOST_TEST((m.summary.status == Status::InvalidInput));
  BOOST_TEST(m.summary.message.find("mechanism") != std::string::npos);
  BOOST_TEST(m.frequencies_rad_s.size() == 6u);
  BOOST_TEST((m.mode_families[0] == ModeFamily::Rigid));
  BOOST_TEST(m.frequencies_rad_s[0] == 0.0);
}

BOOST_AUTO_TEST_CASE(mesh_specs) {
  BOOST_TEST(Discretization::parse("100x60").counts == (std::vector<int>{100, 60}));
  BOOST_TEST(Discretization::parse("64").spec() == "64");
  BOOST_CHECK_THROW(Discretization::parse("0"), InputError);
  BOOST_CHECK_THROW(Discretization::parse("4x"), InputError);
  BOOST_CHECK_THROW(Discretization::parse("-3"), InputError);
  BOOST_CHECK_THROW(Discretization::parse("abc"), InputError);
}
