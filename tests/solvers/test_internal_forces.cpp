// Stress resultants at the probes (result.hpp, InternalForces) against references written out here:
//   - a two-span beam under a uniform load q (spans l): M = -q l^2 / 8 over the middle support,
//     9 q l^2 / 128 at 3 l / 8, shear 3 q l / 8 at the left end and 5 q l / 8 just right of the
//     middle support (beam tables);
//   - a clamped-clamped beam under q: -q L^2 / 12 at the ends, q L^2 / 24 at the middle;
//   - a clamped-free bar and shaft: N = Fx and T = Mx up to the load, 0 beyond;
//   - the free body left of each probe of a stepped shaft under gravity, from the reactions and the
//     loads (equilibrium, computed here): N, Qy, Qz, My, Mz agree to rounding;
//   - rfem's reactions balance the loads to rounding, and its resultants (from them, by the free
//     body) agree with exact within rfem's own estimate;
//   - a simply supported square Kirchhoff plate under uniform pressure: mx = my = 0.0479 q a^2 at
//     the centre, |mxy| = 0.0325 q a^2 at a corner (Timoshenko & Woinowsky-Krieger, table 8, nu =
//     0.3; three digits).
#define BOOST_TEST_MODULE internal_forces
#include <boost/test/unit_test.hpp>

#include <array>
#include <cmath>
#include <string>

#include "modalbench/equilibrium.hpp"
#include "solver_tests.hpp"
#include "solve_options.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

std::string beam(const std::string& physics, const std::string& supports, const std::string& extra,
                 const std::string& probes) {
  return "[scene]\nname = \"forces\"\nkind = \"beam\"\nphysics = \"" + physics +
         "\"\ntheory = \"euler-bernoulli\"\n[geometry]\nlength = 2.0\nwidth = 0.03\nheight = 0.05\n"
         "[material]\nE = 2.1e11\nnu = 0.3\nrho = 7850.0\n[supports]\n" +
         supports + "\n" + extra + "\n[request]\nmodes = 0\nprobes = " + probes + "\n";
}

Result exact(const std::string& text) {
  const Result r = registry().get("exact").solve(parse_scene(text, "forces.toml"), {}, Options{});
  BOOST_REQUIRE_MESSAGE(r.summary.status == Status::Success, r.summary.message);
  for (const Deflection& d : r.deflections) BOOST_REQUIRE(d.has_forces);
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(two_span_beam_under_uniform_load) {
  const double q = 2000.0, l = 1.0;
  const Result r = exact(beam("bending", "x0 = \"pinned\"\nxL = \"pinned\"\n[[supports.points]]\nx = 1.0\nkind = \"pinned\"",
                              "[[line_loads]]\nqz = -2000.0", "[0.0, 0.375, 1.0]"));
  const auto& f0 = r.deflections[0].forces;
  const auto& f1 = r.deflections[1].forces;
  const auto& f2 = r.deflections[2].forces;
  const double scale = q * l * l;  // moments; forces q l
  BOOST_TEST(std::abs(f0.My) <= 1e-9 * scale);
  BOOST_TEST(std::abs(f0.Qz - 3 * q * l / 8) <= 1e-9 * q * l);
  BOOST_TEST(std::abs(f1.My - 9 * q * l * l / 128) <= 1e-9 * scale);
  BOOST_TEST(std::abs(f1.Qz) <= 1e-9 * q * l);  // the largest sagging moment: zero shear
  BOOST_TEST(std::abs(f2.My + q * l * l / 8) <= 1e-9 * scale);
  BOOST_TEST(std::abs(f2.Qz - 5 * q * l / 8) <= 1e-9 * q * l);  // x + 0: right of the support
}

BOOST_AUTO_TEST_CASE(clamped_clamped_beam_under_uniform_load) {
  const double q = 500.0, L = 2.0;
  const Result r = exact(beam("bending", "x0 = \"clamped\"\nxL = \"clamped\"", "[[line_loads]]\nqz = -500.0",
                              "[0.0, 1.0, 2.0]"));
  const double scale = q * L * L;
  BOOST_TEST(std::abs(r.deflections[0].forces.My + q * L * L / 12) <= 1e-9 * scale);
  BOOST_TEST(std::abs(r.deflections[1].forces.My - q * L * L / 24) <= 1e-9 * scale);
  BOOST_TEST(std::abs(r.deflections[2].forces.My + q * L * L / 12) <= 1e-9 * scale);
  BOOST_TEST(std::abs(r.deflections[0].forces.Qz - q * L / 2) <= 1e-9 * q * L);
  BOOST_TEST(std::abs(r.deflections[2].forces.Qz + q * L / 2) <= 1e-9 * q * L);  // L - 0
}

BOOST_AUTO_TEST_CASE(bar_force_and_torque_up_to_the_load) {
  const std::string sup = "x0 = \"clamped\"\nxL = \"free\"";
  const Result r = exact(beam("spatial", sup, "[[loads]]\nx = 1.2\nFx = 3000.0\nMx = 40.0", "[0.5, 1.2, 1.6]"));
  BOOST_TEST(std::abs(r.deflections[0].forces.N - 3000.0) <= 1e-9 * 3000.0);
  BOOST_TEST(std::abs(r.deflections[0].forces.T - 40.0) <= 1e-9 * 40.0);
  for (std::size_t i : {1u, 2u}) {  // at the load, x + 0: beyond it
    BOOST_TEST(std::abs(r.deflections[i].forces.N) <= 1e-9 * 3000.0);
    BOOST_TEST(std::abs(r.deflections[i].forces.T) <= 1e-9 * 40.0);
  }
}

BOOST_AUTO_TEST_CASE(free_body_equilibrium_of_the_stepped_shaft) {
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/stepped_shaft_disc.toml");
  s.request.probes = {{0.1, 0}, {0.3, 0}, {0.45, 0}, {0.5, 0}, {0.8, 0}};
  s.request.modes = 0;
  const Result r = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE_MESSAGE(r.summary.status == Status::Success, r.summary.message);
  double scale_f = 0, scale_m = 0;
  for (const Reaction& rc : r.reactions) scale_f = std::max(scale_f, std::abs(rc.force[2]));
  scale_m = scale_f * s.geometry.length;
  for (const Deflection& d : r.deflections) {
    const double x = d.position[0];
    // What acts on [0, x] (x + 0): reactions, point loads (the disc's weight), the pieces' weight.
    std::array<double, 3> F{}, M{};  // M about the cut
    auto add = [&](double at, const std::array<double, 3>& f, const std::array<double, 3>& couple) {
      for (int k = 0; k < 3; ++k) F[k] += f[k];
      M[1] += -(at - x) * f[2] + couple[1];  // (at - x) e_x cross f, and the couple itself
      M[2] += (at - x) * f[1] + couple[2];
    };
    for (const Reaction& rc : r.reactions)
      if (rc.position[0] <= x) add(rc.position[0], rc.force, rc.moment);
    for (const PointLoad& p : s.all_point_loads())
      if (p.x <= x) add(p.x, {p.Fx, p.Fy, p.Fz}, {p.Mx, p.My, p.Mz});
    for (const DistributedLoad& q : s.all_distributed_loads()) {
      const double hi = std::min(q.to[0], x), lo = q.from[0];
      if (!(hi > lo)) continue;
      add(0.5 * (lo + hi), {q.qx[0] * (hi - lo), q.qy[0] * (hi - lo), q.qz[0] * (hi - lo)}, {});  // uniform pieces
    }
    // The cut's force and moment on the left part are -F and -M; My = -M_cut,y, Qz = -F_cut,z,
    // Mz = +M_cut,z, Qy = -F_cut,y (result.hpp's conventions).
    BOOST_TEST_CONTEXT("x = " << x) {
      BOOST_TEST(std::abs(d.forces.My - M[1]) <= 1e-9 * scale_m);
      BOOST_TEST(std::abs(d.forces.Qz - F[2]) <= 1e-9 * scale_f);
      BOOST_TEST(std::abs(d.forces.Mz + M[2]) <= 1e-9 * scale_m);
      BOOST_TEST(std::abs(d.forces.Qy - F[1]) <= 1e-9 * scale_f);
    }
  }
}

BOOST_AUTO_TEST_CASE(navier_plate_moments_against_timoshenko) {
  const std::string text = R"(
[scene]
name = "square"
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
probes = [[0.5, 0.5], [0.0, 0.0]]
)";
  const Result r = exact(text);
  const double qa2 = 1000.0;
  const auto& c = r.deflections[0].forces;
  BOOST_TEST(std::abs(c.mx / qa2 - 0.0479) <= 0.5e-4);
  BOOST_TEST(std::abs(c.my / qa2 - 0.0479) <= 0.5e-4);
  BOOST_TEST(std::abs(c.mxy) <= 1e-9 * qa2);
  BOOST_TEST(std::abs(std::abs(r.deflections[1].forces.mxy) / qa2 - 0.0325) <= 0.5e-4);
}

// rfem: its reactions (multipliers of the held components) and, from them, the resultants by the
// free body. Reactions balance the applied loads to rounding (equilibrium of the discrete model);
// the resultants at the probes agree with exact within rfem's own estimate, which covers them.
BOOST_AUTO_TEST_CASE(rfem_reactions_balance_and_resultants_within_the_estimate) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"x0 = \"pinned\"\nxL = \"pinned\"\n[[supports.points]]\nx = 1.0\nkind = \"pinned\"", "[[line_loads]]\nqz = -2000.0"},
      {"x0 = \"clamped\"\nxL = \"clamped\"", "[[line_loads]]\nqz = [-500.0, -1500.0]\nx_from = 0.4\n[[loads]]\nx = 1.3\nFz = 700.0\nMy = 90.0"},
      {"x0 = \"clamped\"\nxL = { translational = 1e6, rotational = 0.0 }", "[gravity]\ng = [0.0, 0.0, -9.81]"}};
  for (const std::string theory : {"euler-bernoulli", "timoshenko"})
    for (const auto& [sup, load] : cases) {
      std::string text = beam("bending", sup, load, "[0.0, 0.37, 1.0, 1.3, 1.71]");
      text.replace(text.find("euler-bernoulli"), 15, theory);
      const Scene s = parse_scene(text, "rfem_forces.toml");
      const Result ex = exact(text);
      const Solver& rfem = registry().get("rfem");
      Options o;
      o.refine_to_tolerance = true;  // as the command line does with its default mesh
      const Result rf = rfem.solve(s, testing::default_mesh(rfem, s), o);
      BOOST_TEST_CONTEXT(theory << ", " << sup << ": " << rf.summary.message) {
        BOOST_REQUIRE(rf.summary.status == Status::Success);
        BOOST_REQUIRE_EQUAL(rf.reactions.size(), ex.reactions.size());
        // Equilibrium: the free body of the whole beam (just past its right end) carries nothing.
        double scale_f = 0;
        for (const Reaction& r : rf.reactions) scale_f = std::max(scale_f, std::abs(r.force[2]));
        const InternalForces whole = free_body_forces(s, rf.reactions, 2.0);  // L - 0: the right end's support left out
        double right_f = 0, right_m = 0;
        for (const Reaction& r : rf.reactions)
          if (r.position[0] == 2.0) right_f = r.force[2], right_m = r.moment[1];
        BOOST_TEST(std::abs(whole.Qz + right_f) <= 1e-9 * scale_f);  // the right support balances what is left of it
        BOOST_TEST(std::abs(whole.My + right_m) <= 1e-9 * scale_f * 2.0);
        const double est = rf.summary.error_estimate.deflections;
        double m_scale = 0, q_scale = 0;
        for (const Deflection& d : ex.deflections) {
          m_scale = std::max(m_scale, std::abs(d.forces.My));
          q_scale = std::max(q_scale, std::abs(d.forces.Qz));
        }
        for (std::size_t i = 0; i < ex.deflections.size(); ++i) {
          BOOST_REQUIRE(rf.deflections[i].has_forces);
          BOOST_TEST_INFO("probe " << ex.deflections[i].position[0] << ": My " << rf.deflections[i].forces.My << " vs "
                                   << ex.deflections[i].forces.My << ", Qz " << rf.deflections[i].forces.Qz << " vs "
                                   << ex.deflections[i].forces.Qz << ", estimate " << est);
          BOOST_TEST(std::abs(rf.deflections[i].forces.My - ex.deflections[i].forces.My) <= est * m_scale);
          BOOST_TEST(std::abs(rf.deflections[i].forces.Qz - ex.deflections[i].forces.Qz) <= est * q_scale);
        }
      }
    }
}
