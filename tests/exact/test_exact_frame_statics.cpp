// The exact frames' statics and input against independent references: slope-deflection for a
// portal's sway; the beam line (a one-member frame is a beam, its modes on the cantilever's closed
// forms); the balance of the reactions with the loads; bad input named by key.
#define BOOST_TEST_MODULE exact_frame_statics
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "frame_test_scenes.hpp"
#include "modalbench/exact/exact.hpp"
#include "modalbench/frame.hpp"

using namespace modalbench;
using namespace modalbench::frame_tests;
using ld = long double;

BOOST_AUTO_TEST_CASE(portal_sway_matches_slope_deflection) {
  // Columns EIc high h, beam EIb long L, fixed bases, a lateral load H at B, axial strain made
  // negligible (areas 1e4 m^2): slope-deflection gives the sway
  //   Delta = H h^3 / (12 E Ic) (2a + 3b) / (a + 6b),  a = Ic / h, b = Ib / L,
  // the joint rotation theta = 3 a (Delta / h) / (2a + 3b), and the base moment
  // M_A = (2 E Ic / h) (theta - 3 Delta / h) (the column's end moment on the base, slope-deflection sign).
  const double E = 2.1e11, Ic = 2e-4, Ib = 5e-4, h = 4, L = 6, H = 1e4;
  const std::string toml = fmt::format(R"([scene]
name = "sway"
kind = "frame"
physics = "planar"
theory = "euler-bernoulli"
[material]
E = {}
nu = 0.3
rho = 7850.0
[[nodes]]
id = "A"
x = 0.0
z = 0.0
[[nodes]]
id = "B"
x = 0.0
z = {}
[[nodes]]
id = "C"
x = {}
z = {}
[[nodes]]
id = "D"
x = {}
z = 0.0
[[members]]
id = "AB"
nodes = ["A", "B"]
section = {{ shape = "general", area = 1e6, Iy = {}, Iz = {}, J = {} }}
[[members]]
id = "BC"
nodes = ["B", "C"]
section = {{ shape = "general", area = 1e6, Iy = {}, Iz = {}, J = {} }}
[[members]]
id = "DC"
nodes = ["D", "C"]
section = {{ shape = "general", area = 1e6, Iy = {}, Iz = {}, J = {} }}
[supports]
A = "clamped"
D = "clamped"
[[loads]]
node = "B"
Fx = {}
[request]
probes = ["B", "C"]
)",
                                       E, h, L, h, L, Ic, Ic, Ic, Ib, Ib, Ib, Ic, Ic, Ic, H);
  const Result r = solve(toml);
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const double a = Ic / h, b = Ib / L;
  const double delta = H * h * h * h / (12 * E * Ic) * (2 * a + 3 * b) / (a + 6 * b);
  const double theta = 3 * a * (delta / h) / (2 * a + 3 * b);
  // Slope-deflection neglects axial strain; with areas of 1e6 m^2 the columns' shortening under the
  // overturning moment changes the sway by about 24 Ic / (A L^2) = 1.3e-10 (relative), the beam's
  // by less: the tolerance is 100 times that.
  const double tol = 100 * 24 * Ic / (1e6 * L * L);
  BOOST_TEST(std::abs(r.deflections[0].u / delta - 1) < tol);
  BOOST_TEST(std::abs(r.deflections[1].u / delta - 1) < tol);
  // A sway to +x tilts the columns' tops towards +x: dx/dz = theta_y > 0 (rotation about +y takes z to x).
  BOOST_TEST(r.deflections[0].theta_y > 0);
  BOOST_TEST(std::abs(std::abs(r.deflections[0].theta_y) / theta - 1) < tol);
  const double MA = 2 * E * Ic / h * (theta - 3 * delta / h);
  BOOST_REQUIRE(r.reactions.size() == 2u);
  BOOST_TEST(std::abs(std::abs(r.reactions[0].moment[1]) / std::abs(MA) - 1) < tol);
  BOOST_TEST(std::abs(r.reactions[0].force[0] + r.reactions[1].force[0] + H) < 1e-9 * H);
}

namespace {

/// A cantilever 2 m long along x as a beam scene and as a one-member frame, with the same loads.
std::string cantilever(bool frame, const std::string& physics, const std::string& theory) {
  const bool spatial = physics == "spatial";
  const std::string loads = spatial ? "Fx = 500.0\nFy = 300.0\nFz = -1000.0\nMx = 40.0\nMy = 70.0\nMz = -20.0\n"
                                    : "Fx = 500.0\nFz = -1000.0\nMy = 70.0\n";
  const std::string q = spatial ? "qx = [100.0, -50.0]\nqy = [0.0, 200.0]\nqz = [-300.0, 400.0]\n"
                                : "qx = [100.0, -50.0]\nqz = [-300.0, 400.0]\n";
  if (!frame)
    return fmt::format(R"([scene]
name = "cantilever"
kind = "beam"
physics = "{}"
theory = "{}"
[geometry]
length = 2.0
width = 0.04
height = 0.06
{}
[supports]
x0 = "clamped"
xL = "free"
[[loads]]
x = 2.0
{}
[[line_loads]]
{}
[gravity]
g = [1.0, {}, -9.81]
[request]
modes = 10
probes = [0.7, 2.0]
)",
                       physics, theory, kSteel, loads, q, spatial ? "2.0" : "0.0");
  return fmt::format(R"([scene]
name = "cantilever"
kind = "frame"
physics = "{}"
theory = "{}"
{}
[[nodes]]
id = "A"
x = 0.0
z = 0.0
[[nodes]]
id = "B"
x = 2.0
z = 0.0
[[members]]
id = "AB"
nodes = ["A", "B"]
section = {{ shape = "rectangle", width = 0.04, height = 0.06 }}
[supports]
A = "clamped"
[[loads]]
node = "B"
{}
[[line_loads]]
member = "AB"
{}
[gravity]
g = [1.0, {}, -9.81]
[request]
modes = 10
probes = [{{ member = "AB", s = 0.35 }}, "B"]
)",
                     physics, theory, kSteel, loads, q, spatial ? "2.0" : "0.0");
}

/// The Euler-Bernoulli cantilever's closed forms: every frequency of `r`, from 1 + cos bL cosh bL = 0
/// per bending plane (solved here as cos b + sech b = 0 by bisection in long double) and the bars'
/// (2n - 1) pi / 2. The members' Euler-Bernoulli bending is in closed form (frame_members.cpp), so
/// the frequencies hold to the count's bisection (1e-13 in omega^2) at any bL: the 8th bending mode
/// (bL = 23.6) included, where a doubling's rounding had reached 1.7e-9.
void expect_cantilever_frequencies(const Result& r, bool spatial) {
  const ld E = 2.1e11L, G = E / 2.6L, rho = 7850.0L, L = 2, b = 0.04L, h = 0.06L;
  const ld A = b * h, Iy = b * h * h * h / 12, Iz = h * b * b * b / 12;
  const Section sec = rectangular_section(0.04, 0.06);
  std::vector<ld> ref;
  for (int n = 1; n <= 12; ++n) {
    ld lo = (n - 0.5L) * std::numbers::pi_v<ld> - 0.4L, hi = (n - 0.5L) * std::numbers::pi_v<ld> + 0.4L;
    const auto g = [](ld x) { return std::cos(x) + 1 / std::cosh(x); };
    for (int it = 0; it < 100; ++it) {
      const ld m = 0.5L * (lo + hi);
      ((g(m) < 0) == (g(lo) < 0) ? lo : hi) = m;
    }
    const ld bl = 0.5L * (lo + hi);
    ref.push_back(bl * bl / (L * L) * std::sqrt(E * Iy / (rho * A)));
    if (spatial) ref.push_back(bl * bl / (L * L) * std::sqrt(E * Iz / (rho * A)));
  }
  for (int n = 1; n <= 6; ++n) {
    ref.push_back((2 * n - 1) * std::numbers::pi_v<ld> / (2 * L) * std::sqrt(E / rho));
    if (spatial) ref.push_back((2 * n - 1) * std::numbers::pi_v<ld> / (2 * L) * std::sqrt(G * sec.J / (rho * sec.Ip)));
  }
  std::sort(ref.begin(), ref.end());
  BOOST_REQUIRE(r.frequencies_rad_s.size() == 10u);
  for (std::size_t i = 0; i < r.frequencies_rad_s.size(); ++i)
    BOOST_TEST(std::abs(r.frequencies_rad_s[i] / static_cast<double>(ref[i]) - 1) < 1e-12,
               "mode " << i + 1 << ": " << r.frequencies_rad_s[i] << " vs " << static_cast<double>(ref[i]));
}

void expect_close(double a, double b, double scale, double tol, const std::string& what) {
  BOOST_TEST(std::abs(a - b) <= tol * scale, what << ": " << a << " vs " << b << " (scale " << scale << ")");
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_one_member_frame_is_the_beam) {
  // The beam line (exact's beams: per-field lines, Wittrick-Williams) and the frame assembly (one
  // member's fields in its axes, at the nodes) are two derivations of the same model.
  for (const std::string physics : {"planar", "spatial"})
    for (const std::string theory : {"euler-bernoulli", "timoshenko"}) {
      BOOST_TEST_CONTEXT(physics << " " << theory) {
        const Result b = solve(cantilever(false, physics, theory)), f = solve(cantilever(true, physics, theory));
        BOOST_TEST_REQUIRE(b.ok(), b.summary.message);
        BOOST_TEST_REQUIRE(f.ok(), f.summary.message);
        BOOST_REQUIRE(f.frequencies_rad_s.size() == b.frequencies_rad_s.size());
        if (theory == "timoshenko") {
          for (std::size_t i = 0; i < b.frequencies_rad_s.size(); ++i)
            BOOST_TEST(std::abs(f.frequencies_rad_s[i] / b.frequencies_rad_s[i] - 1) < 1e-11);
        } else {
          expect_cantilever_frequencies(f, physics == "spatial");
        }
        BOOST_REQUIRE(f.deflections.size() == 2u);
        double scale = 0, rscale = 0;
        for (const auto& d : b.deflections) scale = std::max({scale, std::abs(d.u), std::abs(d.v), std::abs(d.w)});
        for (std::size_t p = 0; p < 2; ++p) {
          const Deflection &x = b.deflections[p], &y = f.deflections[p];
          expect_close(y.u, x.u, scale, 1e-11, "u");
          expect_close(y.v, x.v, scale, 1e-11, "v");
          expect_close(y.w, x.w, scale, 1e-11, "w");
          expect_close(y.theta_x, x.theta_x, scale / 2.0, 1e-11, "theta_x");
          expect_close(y.theta_y, x.theta_y, scale / 2.0, 1e-11, "theta_y");
          expect_close(y.theta_z, x.theta_z, scale / 2.0, 1e-11, "theta_z");
        }
        // The member probe's stress resultants (member axes = global ones here) against the beam's.
        const InternalForces &x = b.deflections[0].forces, &y = f.deflections[0].forces;
        const double fs = std::max({std::abs(x.N), std::abs(x.Qy), std::abs(x.Qz), std::abs(x.My) / 2, std::abs(x.Mz) / 2, std::abs(x.T) / 2});
        for (auto [a, c, n] : {std::tuple{y.N, x.N, "N"}, {y.Qy, x.Qy, "Qy"}, {y.Qz, x.Qz, "Qz"}, {y.My, x.My, "My"},
                               {y.Mz, x.Mz, "Mz"}, {y.T, x.T, "T"}})
          expect_close(a, c, fs, 1e-11, n);
        BOOST_REQUIRE(f.reactions.size() == 1u);
        BOOST_REQUIRE(b.reactions.size() == 1u);
        for (std::size_t c = 0; c < 3; ++c) rscale = std::max({rscale, std::abs(b.reactions[0].force[c]), std::abs(b.reactions[0].moment[c]) / 2});
        for (std::size_t c = 0; c < 3; ++c) {
          expect_close(f.reactions[0].force[c], b.reactions[0].force[c], rscale, 1e-11, "reaction force");
          expect_close(f.reactions[0].moment[c], b.reactions[0].moment[c], rscale, 1e-11, "reaction moment");
        }
      }
    }
}

BOOST_AUTO_TEST_CASE(reactions_balance_the_loads) {
  // A space frame under node loads, line loads and gravity: the reactions' forces and moments
  // (about the origin) cancel the loads', to the rounding of the solve.
  const std::string toml = fmt::format(R"([scene]
name = "L3"
kind = "frame"
physics = "spatial"
theory = "timoshenko"
{}
[[nodes]]
id = "A"
x = 0.0
z = 0.0
[[nodes]]
id = "B"
x = 2.0
z = 0.0
[[nodes]]
id = "C"
x = 2.0
y = 1.5
z = 0.5
[[members]]
id = "AB"
nodes = ["A", "B"]
section = {{ shape = "tube", outer_diameter = 0.1, inner_diameter = 0.08 }}
[[members]]
id = "BC"
nodes = ["B", "C"]
section = {{ shape = "rectangle", width = 0.05, height = 0.08 }}
[supports]
A = "clamped"
C = {{ ux = 1e6, uy = inf, uz = inf }}
[[masses]]
node = "B"
mass = 50.0
[[loads]]
node = "B"
Fx = 300.0
Fy = -200.0
Mz = 50.0
[[line_loads]]
member = "BC"
qy = [100.0, -400.0]
qz = 250.0
[gravity]
g = [0.0, 0.0, -9.81]
[request]
modes = 4
probes = ["B", {{ member = "BC", s = 0.5 }}]
)",
                                       kSteel);
  const Scene sc = parse_scene(toml, "test.toml");
  const Result r = exact::ExactSolver().solve(sc, {}, {});
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const Frame& f = *sc.frame;
  std::array<double, 3> F{}, M{};
  double scale = 0;
  auto add = [&](const std::array<double, 3>& at, const std::array<double, 3>& force, const std::array<double, 3>& mom) {
    const std::array<double, 3> m = {at[1] * force[2] - at[2] * force[1], at[2] * force[0] - at[0] * force[2],
                                     at[0] * force[1] - at[1] * force[0]};
    for (std::size_t i = 0; i < 3; ++i) {
      F[i] += force[i];
      M[i] += mom[i] + m[i];
      scale = std::max({scale, std::abs(force[i]), std::abs(mom[i]), std::abs(m[i])});
    }
  };
  for (const FrameLoad& p : f.all_node_loads(sc.gravity))
    add(f.nodes[static_cast<std::size_t>(p.node)].x, {p.F[0], p.F[1], p.F[2]}, {p.F[3], p.F[4], p.F[5]});
  // Linear intensities over each member: its resultant at the two-point Gauss points (exact).
  for (const FrameLineLoad& q : f.all_line_loads(sc.gravity)) {
    const FrameMember& m = f.members[static_cast<std::size_t>(q.member)];
    for (const double t : {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)}) {
      auto at = [t](const std::array<double, 2>& v) { return v[0] + (v[1] - v[0]) * t; };
      add(f.point_on(m, t), {0.5 * m.length * at(q.qx), 0.5 * m.length * at(q.qy), 0.5 * m.length * at(q.qz)}, {0, 0, 0});
    }
  }
  BOOST_REQUIRE(r.reactions.size() == 2u);
  for (const Reaction& rc : r.reactions) add(rc.point, rc.force, rc.moment);
  for (std::size_t i = 0; i < 3; ++i) {
    BOOST_TEST(std::abs(F[i]) < 1e-12 * scale);
    BOOST_TEST(std::abs(M[i]) < 1e-12 * scale);
  }
  // The spring at C: its reaction is -k ux there (a node probe would give ux; C's x reaction force).
  BOOST_TEST(r.reactions[1].support == "C");
}

BOOST_AUTO_TEST_CASE(bad_frames_are_named_by_key_and_reason) {
  const std::string head = std::string("[scene]\nname = \"bad\"\nkind = \"frame\"\nphysics = \"planar\"\ntheory = "
                                       "\"euler-bernoulli\"\n") + kSteel;
  const std::string nodes = "[[nodes]]\nid = \"A\"\nx = 0.0\nz = 0.0\n[[nodes]]\nid = \"B\"\nx = 1.0\nz = 0.0\n";
  const std::string member = "[[members]]\nid = \"AB\"\nnodes = [\"A\", \"B\"]\nsection = { shape = \"rectangle\", width = 0.1, height = 0.1 }\n";
  const std::string sup = "[supports]\nA = \"clamped\"\n";
  auto expect = [&](const std::string& toml, const std::string& key, const std::string& reason) {
    try {
      parse_scene(toml, "bad.toml");
      BOOST_ERROR("accepted: " << key);
    } catch (const InputError& e) {
      BOOST_TEST(e.key() == key);
      BOOST_TEST(e.reason().find(reason) != std::string::npos, e.reason());
    }
  };
  expect(head + nodes + "[[members]]\nid = \"AB\"\nnodes = [\"A\", \"X\"]\nsection = { shape = \"rectangle\", width = 0.1, height = 0.1 }\n" + sup,
         "members[0].nodes[1]", "unknown node 'X'");
  expect(head + nodes + "[[members]]\nid = \"AA\"\nnodes = [\"A\", \"A\"]\nsection = { shape = \"rectangle\", width = 0.1, height = 0.1 }\n" + sup,
         "members[0].nodes", "zero length");
  expect(head + nodes + member + "[[members]]\nid = \"BA\"\nnodes = [\"B\", \"A\"]\nsection = { shape = \"rectangle\", width = 0.1, height = 0.1 }\n" + sup,
         "members[1].nodes", "already joins");
  expect(head + "[[nodes]]\nid = \"A\"\nx = 0.0\ny = 1.0\nz = 0.0\n" + nodes.substr(nodes.find("[[nodes]]", 2)) + member + sup,
         "nodes[0].y", "x-z plane");
  expect(head + nodes + member + "[supports]\nQ = \"clamped\"\n", "supports.Q", "unknown node");
  expect(head + nodes + member + "releases = [\"C\"]\n" + sup, "members[0].releases[0]", "not one of the member's nodes");
  const std::string spatial = std::string("[scene]\nname = \"bad\"\nkind = \"frame\"\nphysics = \"spatial\"\ntheory = "
                                          "\"euler-bernoulli\"\n") + kSteel;
  expect(spatial + nodes + member + "up = [2.0, 0.0, 0.0]\n" + sup, "members[0].up", "parallel");
  // A hinge chain: both members hinged at the middle node of a beam pinned at its ends is a
  // mechanism for statics; its modes report the rigid motion at 0.
  const std::string chain = head + nodes + "[[nodes]]\nid = \"C\"\nx = 2.0\nz = 0.0\n" + member +
                            "releases = [\"B\"]\n[[members]]\nid = \"BC\"\nnodes = [\"B\", \"C\"]\nsection = { shape = "
                            "\"rectangle\", width = 0.1, height = 0.1 }\nreleases = [\"B\"]\n[supports]\nA = \"pinned\"\nC = "
                            "\"pinned\"\n[[loads]]\nnode = \"B\"\nFz = -100.0\n[request]\nmodes = 3\nprobes = [\"B\"]\n";
  const Result r = solve(chain);
  BOOST_TEST((r.summary.status == Status::InvalidInput));
  BOOST_TEST(r.summary.message.find("mechanism") != std::string::npos, r.summary.message);
  BOOST_REQUIRE(r.frequencies_rad_s.size() == 3u);
  BOOST_TEST(r.frequencies_rad_s[0] == 0.0);
  BOOST_TEST((r.mode_families[0] == ModeFamily::Rigid));
  BOOST_TEST(r.frequencies_rad_s[1] > 0.0);
}

BOOST_AUTO_TEST_CASE(a_load_on_a_held_node_moves_nothing_and_is_its_own_reaction) {
  // Found by the fuzzer: a load on the clamped foot alone left no load on any unknown; the static
  // solve's backward error was 0 / 0 and the statics were flagged as non-finite.
  std::string toml = portal_toml("planar");
  toml.replace(toml.find("[request]"), 9, "[[loads]]\nnode = \"A\"\nFx = 5000.0\nMy = 300.0\n[request]\nprobes = [\"B\"]");
  const Result r = solve(toml);
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  BOOST_TEST(r.deflections[0].u == 0.0);
  BOOST_TEST(r.deflections[0].theta_y == 0.0);
  BOOST_REQUIRE(r.reactions.size() == 2u);
  BOOST_TEST(r.reactions[0].force[0] == -5000.0);
  BOOST_TEST(r.reactions[0].moment[1] == -300.0);
}
