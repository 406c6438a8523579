// The exact frames against independent references: a planar frame's frequency equation written
// here from the members' general solutions (constants per member, the joints' compatibility and
// equilibrium) and solved in long double; slope-deflection for a portal's sway; the beam line
// (a one-member frame is a beam); rotation invariance of the spatial frame; the balance of the
// reactions with the loads; bad input named by key.
#define BOOST_TEST_MODULE exact_frame
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "modalbench/exact/exact.hpp"
#include "modalbench/frame.hpp"

using namespace modalbench;
using ld = long double;

namespace {

Scene builtin(const char* file) { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + file); }

Result solve(const std::string& toml) {
  exact::ExactSolver s;
  return s.solve(parse_scene(toml, "test.toml"), {}, {});
}

const char* kSteel = "[material]\nE = 2.1e11\nnu = 0.3\nrho = 7850.0\n";

// ---- A planar Euler-Bernoulli frame's frequency equation, independent of the back-end ----------
//
// Each member: u along it, w along t = y x e (e its direction), theta_y = w'; N = EA u', M = EI w'',
// V = -EI w''' (the resultants on a face of outward normal e: force N e + V t, moment M about y).
// w = C0 cos bx + C1 sin bx + C2 exp(-bx) + C3 exp(-b(L - x)), u = D0 cos kx + D1 sin kx.
struct TMember {
  int a = 0, b = 0;
  ld EA = 0, EI = 0, rhoA = 0;
  std::array<bool, 2> released{};
};
struct TNode {
  ld x = 0, z = 0;
  int support = 0;  // 0 free, 1 pinned, 2 clamped
};
struct TFrame {
  std::vector<TNode> nodes;
  std::vector<TMember> members;
};

/// The coefficients (6 per member) of u, w, theta, N, M, V at x of member j at omega.
struct EndRows {
  std::array<ld, 6> u{}, w{}, th{}, N{}, M{}, V{};
  ld c = 0, s = 0;  // e = (c, s) in (x, z); t = (s, -c)
};
EndRows end_rows(const TFrame& f, int j, int end, ld omega) {
  const TMember& m = f.members[static_cast<std::size_t>(j)];
  const TNode &A = f.nodes[static_cast<std::size_t>(m.a)], &B = f.nodes[static_cast<std::size_t>(m.b)];
  const ld L = std::hypot(B.x - A.x, B.z - A.z);
  EndRows r;
  r.c = (B.x - A.x) / L;
  r.s = (B.z - A.z) / L;
  const ld x = end == 0 ? 0.0L : L;
  const ld b = std::pow(m.rhoA * omega * omega / m.EI, 0.25L), k = omega * std::sqrt(m.rhoA / m.EA);
  const ld pi2 = std::numbers::pi_v<ld> / 2;
  auto basis = [&](int n) {
    const ld bn = std::pow(b, static_cast<ld>(n));
    return std::array<ld, 4>{bn * std::cos(b * x + n * pi2), bn * std::sin(b * x + n * pi2),
                             std::pow(-b, static_cast<ld>(n)) * std::exp(-b * x), bn * std::exp(-b * (L - x))};
  };
  const auto w0 = basis(0), w1 = basis(1), w2 = basis(2), w3 = basis(3);
  for (int i = 0; i < 4; ++i) {
    r.w[static_cast<std::size_t>(i)] = w0[static_cast<std::size_t>(i)];
    r.th[static_cast<std::size_t>(i)] = w1[static_cast<std::size_t>(i)];
    r.M[static_cast<std::size_t>(i)] = m.EI * w2[static_cast<std::size_t>(i)];
    r.V[static_cast<std::size_t>(i)] = -m.EI * w3[static_cast<std::size_t>(i)];
  }
  r.u[4] = std::cos(k * x);
  r.u[5] = std::sin(k * x);
  r.N[4] = -m.EA * k * std::sin(k * x);
  r.N[5] = m.EA * k * std::cos(k * x);
  return r;
}

/// det of the frame's condition matrix at omega (LU with partial pivoting, long double).
ld frame_det(const TFrame& f, ld omega) {
  const std::size_t n = 6 * f.members.size();
  std::vector<std::vector<ld>> A;
  auto row = [&]() -> std::vector<ld>& { return A.emplace_back(n, 0.0L); };
  auto put = [](std::vector<ld>& r, int j, const std::array<ld, 6>& v, ld c) {
    for (int i = 0; i < 6; ++i) r[static_cast<std::size_t>(6 * j + i)] += c * v[static_cast<std::size_t>(i)];
  };
  for (std::size_t k = 0; k < f.nodes.size(); ++k) {
    std::vector<std::pair<int, int>> ends;  // (member, end)
    for (std::size_t j = 0; j < f.members.size(); ++j) {
      if (f.members[j].a == static_cast<int>(k)) ends.push_back({static_cast<int>(j), 0});
      if (f.members[j].b == static_cast<int>(k)) ends.push_back({static_cast<int>(j), 1});
    }
    std::vector<EndRows> er;
    for (auto [j, e] : ends) er.push_back(end_rows(f, j, e, omega));
    // ux = u c + w s, uz = u s - w c; force on the node: +R at a start, -R at an end.
    auto ux = [&](std::vector<ld>& r, std::size_t i, ld sg) { put(r, ends[i].first, er[i].u, sg * er[i].c); put(r, ends[i].first, er[i].w, sg * er[i].s); };
    auto uz = [&](std::vector<ld>& r, std::size_t i, ld sg) { put(r, ends[i].first, er[i].u, sg * er[i].s); put(r, ends[i].first, er[i].w, -sg * er[i].c); };
    auto released = [&](std::size_t i) { return f.members[static_cast<std::size_t>(ends[i].first)].released[static_cast<std::size_t>(ends[i].second)]; };
    auto sign = [&](std::size_t i) { return ends[i].second == 0 ? 1.0L : -1.0L; };
    for (std::size_t i = 1; i < ends.size(); ++i) {
      auto& rx = row(); ux(rx, i, 1); ux(rx, 0, -1);
      auto& rz = row(); uz(rz, i, 1); uz(rz, 0, -1);
    }
    int anchor = -1;
    for (std::size_t i = 0; i < ends.size(); ++i) {
      if (released(i)) {
        put(row(), ends[i].first, er[i].M, 1);
      } else if (anchor < 0) {
        anchor = static_cast<int>(i);
      } else {
        auto& r = row();
        put(r, ends[i].first, er[i].th, 1);
        put(r, ends[static_cast<std::size_t>(anchor)].first, er[static_cast<std::size_t>(anchor)].th, -1);
      }
    }
    if (f.nodes[k].support >= 1) {
      ux(row(), 0, 1);
      uz(row(), 0, 1);
    } else {
      auto& fx = row();
      auto& fz = row();
      for (std::size_t i = 0; i < ends.size(); ++i) {
        put(fx, ends[i].first, er[i].N, sign(i) * er[i].c); put(fx, ends[i].first, er[i].V, sign(i) * er[i].s);
        put(fz, ends[i].first, er[i].N, sign(i) * er[i].s); put(fz, ends[i].first, er[i].V, -sign(i) * er[i].c);
      }
    }
    if (anchor >= 0) {
      auto& r = row();
      if (f.nodes[k].support == 2) {
        put(r, ends[static_cast<std::size_t>(anchor)].first, er[static_cast<std::size_t>(anchor)].th, 1);
      } else {
        for (std::size_t i = 0; i < ends.size(); ++i)
          if (!released(i)) put(r, ends[i].first, er[i].M, sign(i));
      }
    }
  }
  BOOST_REQUIRE(A.size() == n);
  ld det = 1;
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t p = c;
    for (std::size_t r = c + 1; r < n; ++r)
      if (std::abs(A[r][c]) > std::abs(A[p][c])) p = r;
    if (A[p][c] == 0) return 0;
    if (p != c) {
      std::swap(A[p], A[c]);
      det = -det;
    }
    det *= A[c][c];
    for (std::size_t r = c + 1; r < n; ++r) {
      const ld m = A[r][c] / A[c][c];
      for (std::size_t q = c; q < n; ++q) A[r][q] -= m * A[c][q];
    }
  }
  return det;
}

/// Every root of the frame's determinant in (0, top): sign changes on a fine scan, then bisection.
std::vector<double> frame_roots(const TFrame& f, double top, int steps) {
  std::vector<double> out;
  ld lo = top * 1e-4, dlo = frame_det(f, lo);
  for (int i = 1; i <= steps; ++i) {
    ld hi = top * static_cast<ld>(i) / steps, dhi = frame_det(f, hi);
    if ((dlo < 0) != (dhi < 0)) {
      ld a = lo, b = hi, da = dlo;
      for (int it = 0; it < 80; ++it) {
        const ld m = 0.5L * (a + b), dm = frame_det(f, m);
        if ((dm < 0) == (da < 0)) { a = m; da = dm; } else { b = m; }
      }
      out.push_back(static_cast<double>(0.5L * (a + b)));
    }
    lo = hi;
    dlo = dhi;
  }
  return out;
}

/// The portal of scenes/frame_portal.toml as TOML, with optional hinge and supports.
std::string portal_toml(const std::string& physics, const std::string& extra_member_bc = "",
                        const std::string& support_d = "clamped") {
  return fmt::format(R"([scene]
name = "portal"
kind = "frame"
physics = "{}"
theory = "euler-bernoulli"
{}
[[nodes]]
id = "A"
x = 0.0
z = 0.0
[[nodes]]
id = "B"
x = 0.0
z = 4.0
[[nodes]]
id = "C"
x = 6.0
z = 4.0
[[nodes]]
id = "D"
x = 6.0
z = 0.0
[[members]]
id = "AB"
nodes = ["A", "B"]
section = {{ shape = "rectangle", width = 0.1, height = 0.2 }}
[[members]]
id = "BC"
nodes = ["B", "C"]
section = {{ shape = "rectangle", width = 0.1, height = 0.3 }}
{}
[[members]]
id = "CD"
nodes = ["C", "D"]
section = {{ shape = "rectangle", width = 0.1, height = 0.2 }}
[supports]
A = "clamped"
D = "{}"
[request]
modes = 8
)",
                     physics, kSteel, extra_member_bc, support_d);
}

TFrame portal_reference(bool hinge_c, int support_d) {
  const ld E = 2.1e11L, rho = 7850.0L;
  auto member = [&](int a, int b, ld h) {
    TMember m;
    m.a = a;
    m.b = b;
    m.EA = E * 0.1L * h;
    m.EI = E * 0.1L * h * h * h / 12;
    m.rhoA = rho * 0.1L * h;
    return m;
  };
  TFrame f;
  f.nodes = {{0, 0, 2}, {0, 4, 0}, {6, 4, 0}, {6, 0, support_d}};
  f.members = {member(0, 1, 0.2L), member(1, 2, 0.3L), member(2, 3, 0.2L)};
  f.members[1].released[1] = hinge_c;
  return f;
}

void expect_frequencies_match(const Result& r, const TFrame& ref, int compare) {
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  BOOST_REQUIRE(static_cast<int>(r.frequencies_rad_s.size()) > compare);
  // Every root below the midpoint of the exact back-end's compare-th and next frequencies.
  const double top = 0.5 * (r.frequencies_rad_s[static_cast<std::size_t>(compare - 1)] + r.frequencies_rad_s[static_cast<std::size_t>(compare)]);
  const std::vector<double> roots = frame_roots(ref, top, 20000);
  BOOST_TEST_REQUIRE(static_cast<int>(roots.size()) == compare);
  // The back-end bisects omega^2 to 1e-13 (omega to 5e-14); the reference's roots are long double.
  for (int i = 0; i < compare; ++i)
    BOOST_TEST(std::abs(r.frequencies_rad_s[static_cast<std::size_t>(i)] / roots[static_cast<std::size_t>(i)] - 1) < 1e-12,
               "mode " << i + 1 << ": " << r.frequencies_rad_s[static_cast<std::size_t>(i)] << " vs " << roots[static_cast<std::size_t>(i)]);
}

}  // namespace

BOOST_AUTO_TEST_CASE(portal_modes_match_the_frequency_equation) {
  expect_frequencies_match(solve(portal_toml("planar")), portal_reference(false, 2), 7);
}

BOOST_AUTO_TEST_CASE(hinged_portal_modes_match_the_frequency_equation) {
  // The beam hinged to column CD at C, and D pinned: a release and a pin together.
  expect_frequencies_match(solve(portal_toml("planar", "releases = [\"C\"]", "pinned")), portal_reference(true, 1), 7);
}

BOOST_AUTO_TEST_CASE(l_frame_modes_match_the_frequency_equation) {
  const std::string toml = fmt::format(R"([scene]
name = "L"
kind = "frame"
physics = "planar"
theory = "euler-bernoulli"
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
z = 1.5
[[members]]
id = "AB"
nodes = ["A", "B"]
section = {{ shape = "rectangle", width = 0.05, height = 0.08 }}
[[members]]
id = "BC"
nodes = ["B", "C"]
section = {{ shape = "rectangle", width = 0.05, height = 0.05 }}
[supports]
A = "clamped"
[request]
modes = 7
)",
                                       kSteel);
  const ld E = 2.1e11L, rho = 7850.0L;
  TFrame f;
  f.nodes = {{0, 0, 2}, {2, 0, 0}, {2, 1.5L, 0}};
  f.members = {{0, 1, E * 0.05L * 0.08L, E * 0.05L * 0.08L * 0.08L * 0.08L / 12, rho * 0.05L * 0.08L, {}},
               {1, 2, E * 0.05L * 0.05L, E * 0.05L * 0.05L * 0.05L * 0.05L / 12, rho * 0.05L * 0.05L, {}}};
  expect_frequencies_match(solve(toml), f, 6);
}

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

BOOST_AUTO_TEST_CASE(a_turned_portal_keeps_its_in_plane_frequencies) {
  // The portal turned 30 degrees about z as a space frame (the columns' `up` turned with it): its
  // in-plane frequencies are the planar portal's; its out-of-plane ones come in between.
  const Result planar = solve(portal_toml("planar"));
  const double c = std::cos(std::numbers::pi / 6), s = std::sin(std::numbers::pi / 6);
  std::string nodes;
  const double xz[4][2] = {{0, 0}, {0, 4}, {6, 4}, {6, 0}};
  for (int i = 0; i < 4; ++i)
    nodes += fmt::format("[[nodes]]\nid = \"{}\"\nx = {:.17g}\ny = {:.17g}\nz = {}\n", "ABCD"[i], c * xz[i][0], s * xz[i][0], xz[i][1]);
  const std::string up = fmt::format("up = [{:.17g}, {:.17g}, 0.0]", c, s);
  const std::string toml = fmt::format(R"([scene]
name = "turned"
kind = "frame"
physics = "spatial"
theory = "euler-bernoulli"
{}{}
[[members]]
id = "AB"
nodes = ["A", "B"]
section = {{ shape = "rectangle", width = 0.1, height = 0.2 }}
{}
[[members]]
id = "BC"
nodes = ["B", "C"]
section = {{ shape = "rectangle", width = 0.1, height = 0.3 }}
[[members]]
id = "CD"
nodes = ["C", "D"]
section = {{ shape = "rectangle", width = 0.1, height = 0.2 }}
{}
[supports]
A = "clamped"
D = "clamped"
[request]
modes = 20
)",
                                       kSteel, nodes, up, up);
  const Result spatial = solve(toml);
  BOOST_TEST_REQUIRE(spatial.ok(), spatial.summary.message);
  BOOST_TEST_REQUIRE(planar.ok(), planar.summary.message);
  const double top = spatial.frequencies_rad_s.back();
  for (const double w : planar.frequencies_rad_s) {
    if (w > top) break;
    double best = 1;
    for (const double v : spatial.frequencies_rad_s) best = std::min(best, std::abs(v / w - 1));
    BOOST_TEST(best < 1e-11, "in-plane " << w << " rad/s: nearest out of the space frame's " << best);
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

BOOST_AUTO_TEST_CASE(code_aster_frames_match_their_published_values) {
  // SDLX01 (V2.05.001): the VPCS sheet's 13 frequencies by the dynamic stiffness method, stated
  // to 0.5 % (its values are given to 3 or 4 digits).
  const Result x = exact::ExactSolver().solve(builtin("code_aster_sdlx01_plane_frame.toml"), {}, {});
  BOOST_TEST_REQUIRE(x.ok(), x.summary.message);
  const double sdlx01[] = {8.8, 29.4, 43.8, 56.3, 96.2, 102.6, 147.1, 174.8, 178.8, 206.0, 266.4, 320.0, 335.0};
  BOOST_REQUIRE(x.frequencies_rad_s.size() == 13u);
  for (std::size_t i = 0; i < 13; ++i)
    BOOST_TEST(std::abs(x.frequencies_rad_s[i] / (2 * std::numbers::pi) / sdlx01[i] - 1) < 5e-3, "mode " << i + 1);
  // SDLL02 (V2.02.002): the folded strip's frequencies are double, the roots of cos(lambda) = 0,
  // f = lambda^2 / (2 pi L^2) sqrt(E I / (rho A)) (its published 11.76, 105.88, 294.1, 576.44 Hz).
  const Result f = exact::ExactSolver().solve(builtin("code_aster_sdll02_folded_cantilever.toml"), {}, {});
  BOOST_TEST_REQUIRE(f.ok(), f.summary.message);
  BOOST_REQUIRE(f.frequencies_rad_s.size() == 8u);
  const double E = 2.1e11, rho = 7800, b = 0.05, h = 0.005, L = 0.5;
  const double c = std::sqrt(E * b * h * h * h / 12 / (rho * b * h)) / (L * L);
  for (std::size_t i = 0; i < 8; ++i) {
    const double lam = (2.0 * static_cast<double>(i / 2) + 1) * std::numbers::pi / 2;
    BOOST_TEST(std::abs(f.frequencies_rad_s[i] / (lam * lam * c) - 1) < 1e-12, "mode " << i + 1);
  }
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
