// The exact frames' frequencies against independent references: a planar frame's frequency
// equation written here from the members' general solutions (constants per member, the joints'
// compatibility and equilibrium) and solved in long double; rotation invariance of the spatial
// frame; Code_Aster's published values.
#define BOOST_TEST_MODULE exact_frame_modes
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

namespace {

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

