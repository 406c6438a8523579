// dtfm beams with steps, supports between the ends, point masses and distributed loads, against
// closed forms (beam tables, characteristic equations solved here) and the exact back-end's
// transfer-matrix line (a second method) for a stepped Timoshenko shaft with a disc.
#define BOOST_TEST_MODULE dtfm_structures
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include "modalbench/dtfm/dtfm.hpp"
#include "modalbench/exact/exact.hpp"

using namespace modalbench;
using namespace modalbench::dtfm;

namespace {

constexpr double pi = std::numbers::pi;

double rel(double a, double b) { return std::abs(a / b - 1.0); }

/// An Euler-Bernoulli steel beam, 1 m, 40 x 20 mm, bending in x-z, with `extra` TOML appended.
Scene eb_beam(const std::string& supports, const std::string& extra, const char* theory = "euler-bernoulli") {
  return parse_scene(std::string("[scene]\nname = \"t\"\nkind = \"beam\"\nphysics = \"bending\"\ntheory = \"") + theory +
                         "\"\n[geometry]\nlength = 1.0\nwidth = 0.04\nheight = 0.02\n"
                         "[material]\nE = 2.1e11\nnu = 0.3\nrho = 7850.0\nkappa = 0.85\n" +
                         supports + "\n" + extra + "\n[request]\nmodes = 3\nprobes = [0.5]\n",
                     "test");
}

struct Beam {
  double EI, rhoA, GAk, L;
};
Beam props(const Scene& s) {
  const Section sec = s.section();
  return {s.material.E * sec.Iy, s.material.rho * sec.A, s.material.kappa * s.material.G * sec.A, s.geometry.length};
}

std::vector<Deflection> statics(const Scene& s, const std::vector<double>& xs) {
  const PrismModel m = build_model(s, Discretization::parse("1x1"));
  LineAnalysis la(m);
  std::vector<std::array<double, 2>> probes;
  for (double x : xs) probes.push_back({x, 0.0});
  return la.statics(s.all_point_loads(), probes, s.all_distributed_loads());
}

ModeList modes(const Scene& s, int k) {
  const PrismModel m = build_model(s, Discretization::parse("1x1"));
  LineAnalysis la(m);
  return la.modes(k, {ModeFamily::BendingXZ});
}

/// The k-th root of f above `from` by scanning and bisection (f changes sign at each root).
double root(const std::function<double(double)>& f, double from, int k, double step = 1e-3) {
  double a = from, fa = f(a);
  for (int found = 0;;) {
    const double b = a + step, fb = f(b);
    if ((fa < 0) != (fb < 0) && ++found == k) {
      double lo = a, hi = b, flo = fa;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi), fm = f(mid);
        if ((fm < 0) == (flo < 0)) lo = mid, flo = fm;
        else hi = mid;
      }
      return 0.5 * (lo + hi);
    }
    a = b;
    fa = fb;
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(two_span_beam_under_self_weight) {
  // Three pinned supports: each span is a propped cantilever. w(l/2) = q l^4 / (192 EI) under the
  // weight q = rho A g; antisymmetric modes are the pinned span's (n pi / l)^2 sqrt(EI / rho A),
  // symmetric ones the clamped-pinned span's (beta l = 3.92660231...: tan = tanh).
  const Scene s = eb_beam("[supports]\nx0 = \"pinned\"\nxL = \"pinned\"\n[[supports.points]]\nx = 0.5\nkind = \"pinned\"",
                          "[gravity]\ng = [0.0, 0.0, -9.81]");
  const Beam b = props(s);
  const double l = 0.5, q = -b.rhoA * 9.81;
  const auto d = statics(s, {0.25, 0.75, 0.5});
  BOOST_TEST(rel(d[0].w, q * std::pow(l, 4) / (192 * b.EI)) < 1e-9);
  BOOST_TEST(rel(d[1].w, q * std::pow(l, 4) / (192 * b.EI)) < 1e-9);
  BOOST_TEST(std::abs(d[2].w) < 1e-12 * std::abs(d[0].w));
  const ModeList ml = modes(s, 3);
  const double c = std::sqrt(b.EI / b.rhoA);
  const double bl = root([](double x) { return std::tan(x) - std::tanh(x); }, 3.5, 1);
  BOOST_TEST(rel(ml.omega_rad_s[0], std::pow(pi / l, 2) * c) < 1e-9);
  BOOST_TEST(rel(ml.omega_rad_s[1], std::pow(bl / l, 2) * c) < 1e-9);
  BOOST_TEST(rel(ml.omega_rad_s[2], std::pow(2 * pi / l, 2) * c) < 1e-9);
}

BOOST_AUTO_TEST_CASE(cantilever_with_tip_mass) {
  // 1 + cos b cosh b + mu b (cos b sinh b - sin b cosh b) = 0, mu = m / (rho A L); under gravity
  // the tip deflects q L^4 / (8 EI) + m g L^3 / (3 EI).
  const double m_tip = 2.0;
  const Scene s = eb_beam("[supports]\nx0 = \"clamped\"\nxL = \"free\"",
                          "[[masses]]\nx = 1.0\nmass = 2.0\n[gravity]\ng = [0.0, 0.0, -9.81]");
  const Beam b = props(s);
  const double mu = m_tip / (b.rhoA * b.L);
  auto f = [mu](double x) {
    return 1 + std::cos(x) * std::cosh(x) + mu * x * (std::cos(x) * std::sinh(x) - std::sin(x) * std::cosh(x));
  };
  const ModeList ml = modes(s, 3);
  for (int k = 1; k <= 3; ++k) {
    const double beta = root(f, 0.1, k);
    BOOST_TEST(rel(ml.omega_rad_s[k - 1], beta * beta * std::sqrt(b.EI / (b.rhoA * std::pow(b.L, 4)))) < 1e-8,
               "mode " << k);
  }
  const double q = -b.rhoA * 9.81, P = -m_tip * 9.81;
  const auto d = statics(s, {1.0});
  BOOST_TEST(rel(d[0].w, q * std::pow(b.L, 4) / (8 * b.EI) + P * std::pow(b.L, 3) / (3 * b.EI)) < 1e-9);
}

// The frequency equation of a cantilever carrying a mass m at x = a, from the transfer of
// (w, w', w'', w''') along each span (Krylov functions of beta x) and the shear jump
// EI [w'''] = m omega^2 w(a): the free end's w'' and w''' vanish.
double cantilever_mass_equation(double beta, const Beam& b, double a, double m) {
  auto transfer = [beta](double x) {
    const double ch = std::cosh(beta * x), co = std::cos(beta * x), sh = std::sinh(beta * x), si = std::sin(beta * x);
    const double s[4] = {(ch + co) / 2, (sh + si) / (2 * beta), (ch - co) / (2 * beta * beta),
                         (sh - si) / (2 * beta * beta * beta)};
    Eigen::Matrix4d T;
    T.row(0) << s[0], s[1], s[2], s[3];
    for (int r = 1; r < 4; ++r)
      T.row(r) << std::pow(beta, 4) * T(r - 1, 3), T(r - 1, 0), T(r - 1, 1), T(r - 1, 2);
    return T;
  };
  Eigen::Matrix4d jump = Eigen::Matrix4d::Identity();
  jump(3, 0) = m * std::pow(beta, 4) / b.rhoA;  // m omega^2 / EI
  const Eigen::Matrix4d T = transfer(b.L - a) * jump * transfer(a);
  return T.bottomRightCorner<2, 2>().determinant();
}

BOOST_AUTO_TEST_CASE(cantilever_with_a_mass_between_the_ends) {
  // Fuzz seed 7: at a = 0.365 the commensurate spacing of 0.365 and 0.635 cut the line into 200
  // segments of 5 mm, whose K(lambda) resolves lambda only to about eps / (beta h)^4: mode 1 came
  // out 6e-8 off with a bound of 3e-10. Away from such spacings the error was 3e-12.
  for (double a : {0.365, 0.37, 0.4}) {
    const Scene s = eb_beam("[supports]\nx0 = \"clamped\"\nxL = \"free\"",
                            "[[masses]]\nx = " + std::to_string(a) + "\nmass = 2.0");
    const Beam b = props(s);
    const ModeList ml = modes(s, 3);
    BOOST_REQUIRE(ml.omega_rad_s.size() == 3u);
    for (int k = 1; k <= 3; ++k) {
      const double beta = root([&](double x) { return cantilever_mass_equation(x, b, a, 2.0); }, 0.1, k);
      BOOST_TEST(rel(ml.omega_rad_s[k - 1], beta * beta * std::sqrt(b.EI / b.rhoA)) < 1e-10,
                 "a = " << a << " mode " << k);
    }
  }
}

BOOST_AUTO_TEST_CASE(spring_support_between_the_ends) {
  // A pinned-pinned beam on a spring k at its middle under P there: w = P / (k + 48 EI / L^3).
  const Scene s = eb_beam("[supports]\nx0 = \"pinned\"\nxL = \"pinned\"\n[[supports.points]]\nx = 0.5\n"
                          "translational = 3.0e5\nrotational = 0.0",
                          "[[loads]]\nx = 0.5\nFz = -100.0");
  const Beam b = props(s);
  const auto d = statics(s, {0.5});
  BOOST_TEST(rel(d[0].w, -100.0 / (3.0e5 + 48 * b.EI / std::pow(b.L, 3))) < 1e-10);
}

BOOST_AUTO_TEST_CASE(linear_and_partial_line_loads) {
  // Pinned-pinned under a triangular load 0 .. q0: w(L/2) = 5 q0 L^4 / (768 EI).
  const Scene tri = eb_beam("[supports]\nx0 = \"pinned\"\nxL = \"pinned\"", "[[line_loads]]\nqz = [0.0, -1000.0]");
  const Beam b = props(tri);
  BOOST_TEST(rel(statics(tri, {0.5})[0].w, -5.0 * 1000.0 / (768 * b.EI)) < 1e-10);
  // A cantilever loaded over [0, a]: the tip deflects q a^3 (4 L - a) / (24 EI).
  const Scene part = eb_beam("[supports]\nx0 = \"clamped\"\nxL = \"free\"",
                             "[[line_loads]]\nqz = -500.0\nx_from = 0.0\nx_to = 0.3");
  BOOST_TEST(rel(statics(part, {1.0})[0].w, -500.0 * std::pow(0.3, 3) * (4 - 0.3) / (24 * b.EI)) < 1e-10);
  // Timoshenko, pinned-pinned, uniform: 5 q L^4 / (384 EI) + q L^2 / (8 kappa G A).
  const Scene tim = eb_beam("[supports]\nx0 = \"pinned\"\nxL = \"pinned\"", "[[line_loads]]\nqz = -2000.0", "timoshenko");
  const Beam t = props(tim);
  BOOST_TEST(rel(statics(tim, {0.5})[0].w, -2000.0 * (5.0 / (384 * t.EI) + 1.0 / (8 * t.GAk))) < 1e-10);
}

BOOST_AUTO_TEST_CASE(stepped_cantilever_statics) {
  // Two pieces, EI1 on [0, a], EI2 on [a, L], tip load P: by unit load, w = P [(L^3 - (L - a)^3) /
  // (3 EI1) + (L - a)^3 / (3 EI2)].
  const Scene s = parse_scene(
      "[scene]\nname = \"t\"\nkind = \"beam\"\nphysics = \"bending\"\ntheory = \"euler-bernoulli\"\n"
      "[geometry]\nlength = 1.0\n[material]\nE = 2.1e11\nnu = 0.3\nrho = 7850.0\n"
      "[[segments]]\nlength = 0.4\nsection = { shape = \"circle\", diameter = 0.05 }\n"
      "[[segments]]\nlength = 0.6\nsection = { shape = \"circle\", diameter = 0.03 }\n"
      "[supports]\nx0 = \"clamped\"\nxL = \"free\"\n[[loads]]\nx = 1.0\nFz = -100.0\n[request]\nprobes = [1.0]\n",
      "test");
  const double E = 2.1e11, I1 = pi * std::pow(0.05, 4) / 64, I2 = pi * std::pow(0.03, 4) / 64;
  const double expected = -100.0 * ((1.0 - std::pow(0.6, 3)) / (3 * E * I1) + std::pow(0.6, 3) / (3 * E * I2));
  BOOST_TEST(rel(statics(s, {1.0})[0].w, expected) < 1e-10);
}

BOOST_AUTO_TEST_CASE(stepped_shaft_with_disc_agrees_with_exact) {
  // The built-in stepped Timoshenko shaft on bearings with a disc, spatial: every frequency and
  // the static deflections against `exact`'s transfer-matrix line (another method and code).
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/stepped_shaft_disc.toml");
  s.request.frf = FrfRequest{{0.2, 0.0}, {0.7, 0.0}, 50.0, 4000.0, 12};
  const PrismModel m = build_model(s, Discretization::parse("1x1"));
  LineAnalysis la(m);
  const ModeList ml = la.modes(10);
  const Result ex = exact::ExactSolver().solve(s, {}, {});
  BOOST_REQUIRE_EQUAL(ex.frequencies_rad_s.size(), 10u);
  BOOST_REQUIRE_EQUAL(ml.omega_rad_s.size(), 10u);
  for (std::size_t k = 0; k < 10; ++k)
    BOOST_TEST(rel(ml.omega_rad_s[k], ex.frequencies_rad_s[k]) < 1e-8, "mode " << k + 1);
  const auto d = la.statics(s.all_point_loads(), s.request.probes, s.all_distributed_loads());
  BOOST_REQUIRE_EQUAL(d.size(), ex.deflections.size());
  double scale = 0;
  for (const auto& e : ex.deflections) scale = std::max(scale, std::abs(e.w));
  for (std::size_t j = 0; j < d.size(); ++j) BOOST_TEST(std::abs(d[j].w - ex.deflections[j].w) < 1e-9 * scale);
  // Receptances through the steps and the disc, away from resonances (the samples miss the bending
  // ones by 3 % or more): relative to their largest.
  std::vector<double> omegas;
  for (const auto& p : ex.frf) omegas.push_back(p.omega_rad_s);
  BOOST_REQUIRE_EQUAL(omegas.size(), 12u);
  const auto H = la.receptance(s.request.frf->excite, s.request.frf->observe, omegas, 0.0);
  double hmax = 0;
  for (const auto& p : ex.frf) hmax = std::max(hmax, std::abs(p.receptance));
  for (std::size_t i = 0; i < omegas.size(); ++i)
    BOOST_TEST(std::abs(H[i] - ex.frf[i].receptance) < 1e-9 * hmax, "at " << omegas[i] << " rad/s");
}

BOOST_AUTO_TEST_CASE(torsion_near_rigid_on_one_spring_within_its_bound) {
  // Fuzz seed 7, case 132: the stepped shaft with nu = -0.999999 (G = 1.05e17 Pa), torsion free
  // at x0 and on 1e4 N m / rad at xL, a disc Jx at 0.5: nearly the rigid sqrt(kt / J). Its class
  // is 1e8 times stiffer than the model's scale: the count placed it 1.5e-8 off with a bound of
  // 2.7e-9. Reference: the frequency equation of the three pieces and the disc (transfer of
  // (theta, T), T = G Ip theta'), solved here.
  const Scene s = parse_scene(
      "[scene]\nname = \"t\"\nkind = \"beam\"\nphysics = \"spatial\"\ntheory = \"euler-bernoulli\"\n"
      "[geometry]\nlength = 1.0\n[material]\nE = 2.1e11\nnu = -0.999999\nrho = 7850.0\n"
      "[[segments]]\nlength = 0.3\nsection = { shape = \"circle\", diameter = 0.04 }\n"
      "[[segments]]\nlength = 0.4\nsection = { shape = \"circle\", diameter = 0.06 }\n"
      "[[segments]]\nlength = 0.3\nsection = { shape = \"circle\", diameter = 0.04 }\n"
      "[supports]\nx0 = { translational = 2e7, rotational = 0.0, axial = 1e8, torsional = 0.0 }\n"
      "xL = { translational = 2e7, rotational = 0.0, axial = 0.0, torsional = 1e4 }\n"
      "[[masses]]\nx = 0.5\nmass = 12.33\nJx = 0.06165\nJy = 0.0334\nJz = 0.0334\n[request]\nmodes = 1\n",
      "test");
  const double G = s.material.G, rho = s.material.rho, kt = 1e4, Jd = 0.06165;
  auto equation = [&](double omega) {
    Eigen::Vector2d st(1.0, 0.0);  // free end: T = 0
    auto carry = [&](double len, double d) {
      const double Ip = pi * std::pow(d, 4) / 32, k = omega * std::sqrt(rho / G);
      Eigen::Matrix2d T;
      T << std::cos(k * len), std::sin(k * len) / (G * Ip * k), -G * Ip * k * std::sin(k * len), std::cos(k * len);
      st = T * st;
    };
    carry(0.3, 0.04);
    carry(0.2, 0.06);
    st[1] -= Jd * omega * omega * st[0];
    carry(0.2, 0.06);
    carry(0.3, 0.04);
    return st[1] + kt * st[0];
  };
  const double Jtot = Jd + rho * pi / 32 * (0.6 * std::pow(0.04, 4) + 0.4 * std::pow(0.06, 4));
  const double rigid = std::sqrt(kt / Jtot);
  double lo = 0.999 * rigid, hi = rigid, flo = equation(lo);
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi), fm = equation(mid);
    if ((fm < 0) == (flo < 0)) lo = mid, flo = fm;
    else hi = mid;
  }
  const double reference = 0.5 * (lo + hi);
  const PrismModel m = build_model(s, Discretization::parse("1x1"));
  LineAnalysis la(m);
  const ModeList ml = la.modes(1, {ModeFamily::Torsion});
  BOOST_REQUIRE_EQUAL(ml.omega_rad_s.size(), 1u);
  const double bound = 0.5 * std::max(ml.near_rigid_bound, ml.polish_floor_width);  // in omega
  BOOST_TEST(bound < 1e-6);
  BOOST_TEST(rel(ml.omega_rad_s[0], reference) <= bound);
}

BOOST_AUTO_TEST_CASE(round_section_statics_use_the_circle) {
  // One prism of a round section spreads a point load with the circle's own A and I (it used a
  // rectangle's: 0.62 of the deflection): pinned-pinned, central P, Timoshenko.
  const Scene s = parse_scene(
      "[scene]\nname = \"t\"\nkind = \"beam\"\nphysics = \"bending\"\ntheory = \"timoshenko\"\n"
      "[geometry]\nlength = 1.0\nsection = { shape = \"circle\", diameter = 0.04 }\n"
      "[material]\nE = 2.1e11\nnu = 0.3\nrho = 7850.0\n[supports]\nx0 = \"pinned\"\nxL = \"pinned\"\n"
      "[[loads]]\nx = 0.5\nFz = -500.0\n[request]\nprobes = [0.5]\n",
      "test");
  const Section sec = s.section();
  const double EI = s.material.E * sec.Iy, GAk = s.material.kappa * s.material.G * sec.A;
  BOOST_TEST(rel(statics(s, {0.5})[0].w, -500.0 * (1.0 / (48 * EI) + 0.25 / GAk)) < 1e-10);
}

BOOST_AUTO_TEST_CASE(stepped_shaft_reactions_balance_and_agree_with_exact) {
  // The shaft's weight and the disc's (spatial, gravity along -z) are carried by the two bearings:
  // dtfm's reactions (its held rows and springs) against exact's, and their sum against the weight.
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/stepped_shaft_disc.toml");
  const Result ex = exact::ExactSolver().solve(s, {}, {});
  const Result dt = DtfmSolver().solve(s, Discretization::parse("1x1"), {});
  BOOST_REQUIRE(dt.summary.status == Status::Success);
  double weight = 0;
  for (const PointLoad& p : s.all_point_loads()) weight += p.Fz;
  for (const DistributedLoad& d : s.all_distributed_loads()) weight += 0.5 * (d.qz[0] + d.qz[1]) * (d.to[0] - d.from[0]);
  BOOST_REQUIRE(weight < 0);
  BOOST_REQUIRE_EQUAL(dt.reactions.size(), ex.reactions.size());
  double sum = 0, moment = 0;
  for (const Reaction& e : ex.reactions) {
    const auto it = std::find_if(dt.reactions.begin(), dt.reactions.end(), [&](const Reaction& r) { return r.support == e.support; });
    BOOST_REQUIRE(it != dt.reactions.end());
    for (int k = 0; k < 3; ++k) {
      BOOST_TEST(std::abs(it->force[static_cast<std::size_t>(k)] - e.force[static_cast<std::size_t>(k)]) <= 1e-9 * -weight);
      BOOST_TEST(std::abs(it->moment[static_cast<std::size_t>(k)] - e.moment[static_cast<std::size_t>(k)]) <= 1e-9 * -weight);
    }
    sum += it->force[2];
    moment += it->force[2] * it->position[0];
  }
  BOOST_TEST(std::abs(sum + weight) <= 1e-12 * -weight);
  // Moments about x = 0: the reactions' against the loads' first moment.
  double first = 0;
  for (const PointLoad& p : s.all_point_loads()) first += p.Fz * p.x;
  for (const DistributedLoad& d : s.all_distributed_loads()) {
    const double l = d.to[0] - d.from[0];
    first += l * (d.qz[0] * (d.from[0] + l / 3) + d.qz[1] * (d.from[0] + 2 * l / 3)) / 2;
  }
  BOOST_TEST(std::abs(moment + first) <= 1e-12 * -weight * s.geometry.length);
  // The resultants from them at the probes: exact's.
  for (std::size_t j = 0; j < ex.deflections.size(); ++j) {
    BOOST_REQUIRE(dt.deflections[j].has_forces);
    BOOST_TEST(std::abs(dt.deflections[j].forces.My - ex.deflections[j].forces.My) <= 1e-9 * -weight * s.geometry.length);
    BOOST_TEST(std::abs(dt.deflections[j].forces.Qz - ex.deflections[j].forces.Qz) <= 1e-9 * -weight);
  }
}

BOOST_AUTO_TEST_CASE(near_rigid_axial_mode_of_a_stepped_shaft_carries_its_whole_mass) {
  // The stepped shaft with its disc on an axial spring of 35.8 N/m and nothing else axially: its
  // axial mode is the whole mass on the spring, omega^2 = k / (m_shaft + m_disc), up to the shaft's
  // own compliance: relative to omega below k / (2 min EA / L) = 6.8e-8. dtfm finds it by the
  // near-rigid Rayleigh-Ritz over the pieces (a fuzz finding: the middle piece's mass was integrated
  // over 0.7 m instead of 0.4 m, 6 % off).
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/stepped_shaft_disc.toml");
  s.x0 = Support::named("clamped");
  s.x0.kind = "springs";
  s.x0.axial = 35.847775334733576;
  s.xL.axial = 0.0;
  const PrismModel m = build_model(s, Discretization::parse("1x1"));
  LineAnalysis la(m);
  const ModeList ml = la.modes(2, {ModeFamily::Axial});
  double mass = 0;
  for (const Segment& p : s.beam_pieces()) mass += p.material.rho * p.properties().A * p.length();
  for (const PointMass& pm : s.masses) mass += pm.mass;
  BOOST_REQUIRE(!ml.omega_rad_s.empty());
  BOOST_TEST(rel(ml.omega_rad_s[0], std::sqrt(35.847775334733576 / mass)) < 1e-7);
}
