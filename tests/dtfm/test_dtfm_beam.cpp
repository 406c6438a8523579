// dtfm beams against independent references: the exact Timoshenko beam, bar and torsion bar
// (one prism), the paper's Table 1 and the converged 3D values (docs/sources.md, P1, P7, P8), a direct
// evaluation of the paper's Green's function (45)/(55) where it is well conditioned, and
// structural checks (counts, multiplicity, reciprocity) that need no reference.
#define BOOST_TEST_MODULE dtfm_beam
#include <boost/test/unit_test.hpp>

#include <unsupported/Eigen/MatrixFunctions>

#include <cmath>
#include <complex>
#include <map>
#include <numbers>
#include <ostream>
#include <string>

#include "modalbench/dtfm/dtfm.hpp"
#include "modalbench/exact/exact.hpp"

namespace modalbench {
inline std::ostream& operator<<(std::ostream& o, ModeFamily f) { return o << to_string(f); }
}  // namespace modalbench

using namespace modalbench;
using namespace modalbench::dtfm;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

Scene paper_beam() { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml"); }

double rel(double a, double b) { return std::abs(a / b - 1.0); }

ModeList modes_of(const Scene& s, const char* mesh, int k, std::vector<ModeFamily> families = {},
                  ModelOptions o = {}) {
  const PrismModel m = build_model(s, Discretization::parse(mesh), o);
  LineAnalysis la(m);
  return la.modes(k, families);
}

/// The paper's transfer function (51) with the Green's function (45), clamped ends
/// (M = [I 0; 0 0], N = [0 0; I 0]), structural damping E -> E (1 + i eta): w(xo) / Fz(xe).
std::complex<double> direct_receptance(const PrismModel& m, double xe, double xo, double omega, double eta) {
  using Mat = Eigen::MatrixXcd;
  const int n = m.m;
  const std::complex<double> c(1.0, eta), s(0.0, omega);
  const Mat A20 = c * m.A20().cast<std::complex<double>>(), A10 = c * m.A10().cast<std::complex<double>>();
  const Mat A00 = c * m.A00().cast<std::complex<double>>(), A02 = m.A02().cast<std::complex<double>>();
  const Mat A20i = A20.inverse();
  Mat F = Mat::Zero(2 * n, 2 * n);
  F.topRightCorner(n, n).setIdentity();
  F.bottomLeftCorner(n, n) = -A20i * (A02 * s * s + A00);
  F.bottomRightCorner(n, n) = -A20i * A10;
  Mat Mb = Mat::Zero(2 * n, 2 * n), Nb = Mat::Zero(2 * n, 2 * n);
  Mb.topLeftCorner(n, n).setIdentity();
  Nb.bottomLeftCorner(n, n).setIdentity();
  PointLoad unit;
  unit.Fz = 1.0;
  Eigen::VectorXcd u = Eigen::VectorXcd::Zero(2 * n);
  u.tail(n) = A20i * m.load_vector(unit).cast<std::complex<double>>();
  const double L = m.length;
  const Mat base = (Mb + Nb * Mat(F * L).exp()).inverse();
  const Mat G = xe <= xo ? Mat(Mat(F * xo).exp() * base * Mb * Mat(F * (-xe)).exp())
                         : Mat(-Mat(F * xo).exp() * base * Nb * Mat(F * (L - xe)).exp());
  const Eigen::VectorXcd eta_x = G * u;
  return (m.w_observer(0.0).cast<std::complex<double>>() * eta_x.head(n))(0);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(one_prism)

// Table 1, "1 prism" (G = 8e10, P1): one prism is the exact Timoshenko beam.
BOOST_AUTO_TEST_CASE(table1_one_prism_column) {
  const double table[] = {6211.15, 13848.36, 22763.93, 32186.47, 41982.17, 47172.88};
  const Scene s = paper_beam();
  const ModeList ml = modes_of(s, "1x1", 6, {ModeFamily::BendingXZ});
  const auto ex = exact::beam_bending_frequencies(exact::bending_xz(s), {inf, inf}, {inf, inf}, 6);
  BOOST_REQUIRE(ml.omega_rad_s.size() == 6u);
  for (int i = 0; i < 6; ++i) {
    BOOST_TEST_MESSAGE("mode " << i + 1 << ": " << ml.omega_rad_s[i] << " rad/s (Table 1: " << table[i] << ")");
    BOOST_TEST(rel(ml.omega_rad_s[i], table[i]) < 1e-6);
    BOOST_TEST(rel(ml.omega_rad_s[i], ex.omega_rad_s[i]) < 1e-9);
    BOOST_TEST(ml.family[i] == ModeFamily::BendingXZ);
  }
}

// Euler-Bernoulli and Timoshenko, clamped, pinned, free and elastic ends.
BOOST_AUTO_TEST_CASE(bending_with_any_end_conditions) {
  Scene s = paper_beam();
  s.geometry.length = 2.0;
  struct Ends {
    Support a, b;
  };
  Support springs;
  springs.kind = "springs";
  springs.translational = 3e8;
  springs.rotational = 2e7;
  for (Theory th : {Theory::Timoshenko, Theory::EulerBernoulli})
    for (const Ends& e : {Ends{Support::named("pinned"), Support::named("pinned")},
                          Ends{Support::named("clamped"), Support::named("free")}, Ends{springs, Support::named("pinned")},
                          Ends{springs, springs}}) {
      s.theory = th;
      s.x0 = e.a;
      s.xL = e.b;
      const ModeList ml = modes_of(s, "1x1", 6, {ModeFamily::BendingXZ});
      const auto ex = exact::beam_bending_frequencies(exact::bending_xz(s), {e.a.translational, e.a.rotational},
                                                      {e.b.translational, e.b.rotational}, 6);
      BOOST_REQUIRE(ml.omega_rad_s.size() == 6u);
      for (int i = 0; i < 6; ++i)
        BOOST_TEST_CONTEXT(to_string(th) << " " << e.a.kind << "-" << e.b.kind << " mode " << i + 1) {
          BOOST_TEST(rel(ml.omega_rad_s[i], ex.omega_rad_s[i]) < 1e-9);
        }
    }
}

// Dimensional analysis: all lengths times c scale every frequency by 1/c. Fuzz seed 7, case 660:
// a cantilever 1e12 m long (section 5e10 m deep) solved as clamped-pinned with success, its
// free end's w taken for rounding when the end's motions were measured against a map that
// divides translations by the section depth and leaves rotations alone.
BOOST_AUTO_TEST_CASE(frequencies_scale_with_the_geometry) {
  Scene base = paper_beam();
  base.theory = Theory::EulerBernoulli;
  base.x0 = Support::named("clamped");
  base.xL = Support::named("free");
  const ModeList ref = modes_of(base, "1x1", 4, {ModeFamily::BendingXZ});
  BOOST_REQUIRE(ref.omega_rad_s.size() == 4u);
  for (double c : {1e-9, 1e12, 1e15}) {
    Scene s = base;
    s.geometry.length *= c;
    s.geometry.width *= c;
    s.geometry.height *= c;
    const ModeList ml = modes_of(s, "1x1", 4, {ModeFamily::BendingXZ});
    BOOST_REQUIRE(ml.omega_rad_s.size() == 4u);
    for (int i = 0; i < 4; ++i)
      BOOST_TEST_CONTEXT("scale " << c << " mode " << i + 1) {
        BOOST_TEST(rel(ml.omega_rad_s[i] * c, ref.omega_rad_s[i]) < 1e-9);
      }
  }
}

// A spatial prism: bar (EA), torsion bar (G J with the Saint-Venant J), bending in both planes.
BOOST_AUTO_TEST_CASE(bar_torsion_and_two_planes) {
  Scene s = paper_beam();
  s.physics = Physics::Spatial;
  s.geometry.width = 0.15;
  Support springs;
  springs.kind = "springs";
  springs.translational = 5e8;
  springs.rotational = 1e7;
  springs.axial = 2e9;
  springs.torsional = 3e6;
  s.x0 = Support::named("clamped");
  s.xL = springs;
  const int k = 16;
  const ModeList ml = modes_of(s, "1x1", k);
  const Section sec = s.section();
  const auto& mat = s.material;
  const double L = s.geometry.length;
  const auto ax = exact::bar_frequencies({mat.E * sec.A, mat.rho * sec.A, L}, inf, springs.axial, k);
  const auto tor = exact::bar_frequencies({mat.G * sec.J, mat.rho * sec.Ip, L}, inf, springs.torsional, k);
  const auto bxz = exact::beam_bending_frequencies(exact::bending_xz(s), {inf, inf},
                                                   {springs.translational, springs.rotational}, k);
  const auto bxy = exact::beam_bending_frequencies(exact::bending_xy(s), {inf, inf},
                                                   {springs.translational, springs.rotational}, k);
  std::map<ModeFamily, const exact::Frequencies*> ref = {{ModeFamily::Axial, &ax},
                                                         {ModeFamily::Torsion, &tor},
                                                         {ModeFamily::BendingXZ, &bxz},
                                                         {ModeFamily::BendingXY, &bxy}};
  std::map<ModeFamily, int> seen;
  BOOST_REQUIRE(ml.omega_rad_s.size() == static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i) {
    const ModeFamily f = ml.family[i];
    BOOST_REQUIRE(ref.count(f));
    const double want = ref[f]->omega_rad_s[seen[f]++];
    BOOST_TEST_CONTEXT("mode " << i + 1 << " " << to_string(f)) { BOOST_TEST(rel(ml.omega_rad_s[i], want) < 1e-9); }
  }
  BOOST_TEST(seen[ModeFamily::Axial] >= 1);
  BOOST_TEST(seen[ModeFamily::Torsion] >= 2);
}

// Static deflection of one prism equals the exact Timoshenko beam and bars (w, theta, u, v,
// theta_x at probes), loads and probes anywhere.
BOOST_AUTO_TEST_CASE(statics_match_exact) {
  Scene s = paper_beam();
  s.physics = Physics::Spatial;
  s.geometry.width = 0.2;
  s.x0 = Support::named("clamped");
  s.xL = Support::named("pinned");
  PointLoad p1, p2;
  p1.x = 0.3, p1.Fz = -2e5, p1.My = 3e4, p1.Fx = 1e6, p1.Mx = 5e3;
  p2.x = 0.7, p2.Fy = 4e5, p2.Mz = -2e4;
  s.loads = {p1, p2};
  const std::vector<std::array<double, 2>> probes = {{0.15, 0}, {0.3, 0}, {0.5, 0}, {0.85, 0}};
  const PrismModel m = build_model(s, Discretization::parse("1x1"));
  LineAnalysis la(m);
  const auto d = la.statics(s.loads, probes);
  std::vector<double> xs;
  for (auto& p : probes) xs.push_back(p[0]);
  const auto wz = exact::beam_static(exact::bending_xz(s), {inf, inf}, {inf, 0}, {{0.3, -2e5, 3e4}}, xs, -1.0);
  const auto wy = exact::beam_static(exact::bending_xy(s), {inf, inf}, {inf, 0}, {{0.7, 4e5, -2e4}}, xs, +1.0);
  const Section sec = s.section();
  const auto u = exact::bar_static({s.material.E * sec.A, 1.0, 1.0}, inf, inf, {{0.3, 1e6, 0}}, xs);
  const auto t = exact::bar_static({s.material.G * sec.J, 1.0, 1.0}, inf, inf, {{0.3, 5e3, 0}}, xs);
  for (std::size_t i = 0; i < probes.size(); ++i) {
    BOOST_TEST(std::abs(d[i].w - wz[i].w) < 1e-10 * std::abs(wz[1].w));
    BOOST_TEST(std::abs(d[i].theta_y - wz[i].theta) < 1e-10 * std::abs(wz[0].theta) + 1e-18);
    BOOST_TEST(std::abs(d[i].v - wy[i].w) < 1e-10 * std::abs(wy[2].w));
    BOOST_TEST(std::abs(d[i].theta_z - wy[i].theta) < 1e-10 * std::abs(wy[2].theta) + 1e-18);
    BOOST_TEST(std::abs(d[i].u - u[i]) < 1e-10 * std::abs(u[1]));
    BOOST_TEST(std::abs(d[i].theta_x - t[i]) < 1e-10 * std::abs(t[1]));
  }
}

// The receptance of one prism equals the exact Timoshenko receptance over the Fig. 5 band.
BOOST_AUTO_TEST_CASE(frf_matches_exact) {
  const Scene s = paper_beam();
  const PrismModel m = build_model(s, Discretization::parse("1x1"));
  LineAnalysis la(m);
  std::vector<double> w;
  for (int i = 1; i < 200; ++i) w.push_back(250.0 * i + 0.37);
  const auto H = la.receptance({0.1, 0}, {0.4, 0}, w, 0.0);
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double ref = exact::beam_receptance(exact::bending_xz(s), {inf, inf}, {inf, inf}, 0.1, 0.4, w[i]);
    BOOST_TEST_CONTEXT("omega " << w[i]) {
      BOOST_TEST(std::abs(H[i].imag()) == 0.0);
      BOOST_TEST(std::abs(H[i].real() - ref) < 1e-8 * std::abs(ref));
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(direct_formula)

// The stable path (segment dynamic stiffness, symmetry classes, end plates) agrees with a
// direct evaluation of the paper's Eqs. (45) and (55) where e^{F l} is harmless: a short span
// and low frequencies; one prism and a 1x2 prism model (with its layers' cross terms), with
// and without structural damping.
BOOST_AUTO_TEST_CASE(green_function_45_55) {
  Scene s = paper_beam();
  s.geometry.length = 0.25;
  for (const char* mesh : {"1x1", "1x2"})
    for (double eta : {0.0, 0.02})
      for (double omega : {50.0, 300.0, 900.0})
        for (auto [xe, xo] : {std::pair{0.025, 0.1}, std::pair{0.2, 0.05}}) {
          s.material.loss_factor = eta;
          const PrismModel m = build_model(s, Discretization::parse(mesh));
          LineAnalysis la(m);
          const auto H = la.receptance({xe, 0}, {xo, 0}, {omega}, eta);
          const auto D = direct_receptance(m, xe, xo, omega, eta);
          BOOST_TEST_CONTEXT(mesh << " eta " << eta << " omega " << omega << " xe " << xe << " xo " << xo) {
            BOOST_TEST(std::abs(H[0] - D) < 1e-8 * std::abs(D));
          }
        }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(paper_table1)

// Table 1, "4 prisms" (6191.7, 13568.31, 21184.5, 29587.12, 38913.2, 41321.6): the paper's
// primary/secondary division is not fully given (P7), so this is a few-percent target.
// Our 2x2 (consistent layers) lies within 6.5 % of it, and closer than one prism to the
// converged 3D values (P8) for modes 1-5.
BOOST_AUTO_TEST_CASE(four_prisms_column) {
  const double table[] = {6191.7, 13568.31, 21184.5, 29587.12, 38913.2, 41321.6};
  const double ref3d[] = {6079.75, 13380.23, 21900.37, 30888.10, 40216.80, 43225.29};
  const Scene s = paper_beam();
  const ModeList four = modes_of(s, "2x2", 6, {ModeFamily::BendingXZ});
  const ModeList one = modes_of(s, "1x1", 6, {ModeFamily::BendingXZ});
  BOOST_REQUIRE(four.omega_rad_s.size() == 6u);
  for (int i = 0; i < 6; ++i) {
    BOOST_TEST_MESSAGE("mode " << i + 1 << ": 2x2 " << four.omega_rad_s[i] << " (Table 1: " << table[i]
                               << ", " << 100 * (four.omega_rad_s[i] / table[i] - 1) << " %; 3D " << ref3d[i] << ")");
    BOOST_TEST(rel(four.omega_rad_s[i], table[i]) < 0.065);
    if (i < 5) BOOST_TEST(rel(four.omega_rad_s[i], ref3d[i]) < rel(one.omega_rad_s[i], ref3d[i]));
  }
}

// Refining the section moves the bending frequencies to the 3D values (P8, 20-node
// hexahedra): within 1 % for the first four at 8x8. The printed spring model instead converges
// to a beam with half the shear stiffness (its layers and prisms share the shear in series).
BOOST_AUTO_TEST_CASE(section_refinement_toward_3d) {
  const double ref3d[] = {6079.75, 13380.23, 21900.37, 30888.10};
  const Scene s = paper_beam();
  std::vector<double> worst;
  for (const char* mesh : {"1x1", "2x2", "4x4", "8x8"}) {
    const ModeList ml = modes_of(s, mesh, 4, {ModeFamily::BendingXZ});
    double e = 0;
    std::string row;
    for (int i = 0; i < 4; ++i) {
      e = std::max(e, rel(ml.omega_rad_s[i], ref3d[i]));
      row.append(" ").append(std::to_string(ml.omega_rad_s[i]));
    }
    worst.push_back(e);
    BOOST_TEST_MESSAGE(mesh << ":" << row << "  max |error| vs 3D " << 100 * e << " %");
  }
  BOOST_TEST(worst.back() < 0.01);
  BOOST_TEST(worst.back() < worst.front() / 4);
  ModelOptions paper;
  paper.layers = LayerModel::Paper;
  const ModeList springs = modes_of(s, "8x8", 1, {ModeFamily::BendingXZ}, paper);
  BOOST_TEST(springs.omega_rad_s[0] < 0.9 * ref3d[0]);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(spectrum)

// A square section's bending frequencies in x-z and x-y coincide: each comes twice, and the
// count jumps by two there. Families are never mixed: a plane model's axial modes are axial.
BOOST_AUTO_TEST_CASE(multiplicity_and_families) {
  Scene s = paper_beam();
  s.physics = Physics::Spatial;
  const PrismModel m = build_model(s, Discretization::parse("2x2"));
  LineAnalysis la(m);
  const ModeList ml = la.modes(10);
  int pairs = 0;
  for (std::size_t i = 0; i + 1 < ml.omega_rad_s.size(); ++i)
    if ((ml.family[i] == ModeFamily::BendingXY && ml.family[i + 1] == ModeFamily::BendingXZ) ||
        (ml.family[i] == ModeFamily::BendingXZ && ml.family[i + 1] == ModeFamily::BendingXY)) {
      BOOST_TEST(rel(ml.omega_rad_s[i], ml.omega_rad_s[i + 1]) < 1e-9);
      const double w = ml.omega_rad_s[i];
      BOOST_TEST(la.count_below(w * w * (1 + 1e-7)) - la.count_below(w * w * (1 - 1e-7)) == 2);
      ++pairs;
    }
  BOOST_TEST(pairs >= 2);
  s.physics = Physics::Planar;
  const ModeList pl = modes_of(s, "1x4", 8);
  const double c = std::sqrt(s.material.E / s.material.rho), pi = std::numbers::pi;
  int axial = 0;
  for (std::size_t i = 0; i < pl.omega_rad_s.size(); ++i) {
    BOOST_TEST(pl.family[i] != ModeFamily::Unknown);
    if (pl.family[i] == ModeFamily::Axial) {
      ++axial;
      // The clamped bar's pi c / L, within the model's lateral (Poisson) inertia and stiffness.
      BOOST_TEST(rel(pl.omega_rad_s[i], axial * pi * c / s.geometry.length) < 0.02);
    }
  }
  BOOST_TEST(axial >= 1);
}

// The count agrees with the modes returned: for every mode k, just below it there are fewer
// than k, just above at least k (several models, counted on meshes of their own).
BOOST_AUTO_TEST_CASE(count_agrees_with_modes) {
  Scene s = paper_beam();
  for (auto [physics, mesh] : {std::pair{Physics::Bending, "2x2"}, std::pair{Physics::Planar, "1x4"},
                               std::pair{Physics::Spatial, "2x3"}}) {
    s.physics = physics;
    const PrismModel m = build_model(s, Discretization::parse(mesh));
    LineAnalysis la(m);
    const std::vector<ModeFamily> fam = physics == Physics::Bending ? std::vector{ModeFamily::BendingXZ}
                                                                    : std::vector<ModeFamily>{};
    const ModeList ml = la.modes(12, fam);
    BOOST_TEST(ml.count_consistent);
    for (std::size_t k = 1; k <= ml.omega_rad_s.size(); ++k) {
      const double lam = std::pow(ml.omega_rad_s[k - 1], 2);
      BOOST_TEST_CONTEXT(to_string(physics) << " " << mesh << " mode " << k) {
        BOOST_TEST(la.count_below(lam * (1 - 1e-8), fam) <= static_cast<int>(k) - 1);
        BOOST_TEST(la.count_below(lam * (1 + 1e-8), fam) >= static_cast<int>(k));
      }
    }
  }
}

// A slender beam (L/h = 1000): the first 100 modes are finite, ordered and counted; one prism
// stays the exact Timoshenko beam.
BOOST_AUTO_TEST_CASE(slender_beam_100_modes) {
  Scene s = paper_beam();
  s.geometry.length = 250.0;
  const auto ex = exact::beam_bending_frequencies(exact::bending_xz(s), {inf, inf}, {inf, inf}, 100);
  for (const char* mesh : {"1x1", "2x2"}) {
    const PrismModel m = build_model(s, Discretization::parse(mesh));
    LineAnalysis la(m);
    const ModeList ml = la.modes(100, {ModeFamily::BendingXZ});
    BOOST_REQUIRE(ml.omega_rad_s.size() == 100u);
    BOOST_TEST(ml.count_consistent);
    for (std::size_t i = 0; i < 100; ++i) {
      BOOST_TEST(std::isfinite(ml.omega_rad_s[i]));
      if (i) BOOST_TEST(ml.omega_rad_s[i] > ml.omega_rad_s[i - 1]);
      if (std::string(mesh) == "1x1") BOOST_TEST(rel(ml.omega_rad_s[i], ex.omega_rad_s[i]) < 1e-6);
    }
    const double w100 = ml.omega_rad_s[99];
    BOOST_TEST(la.count_below(w100 * w100 * (1 + 1e-7), {ModeFamily::BendingXZ}) == 100);
    BOOST_TEST(la.count_below(w100 * w100 * (1 - 1e-7), {ModeFamily::BendingXZ}) == 99);
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(responses)

// Static flexibility and receptance of a multi-prism model are reciprocal (symmetric), and a
// free-free beam has two rigid bending modes.
BOOST_AUTO_TEST_CASE(reciprocity_and_rigid_modes) {
  Scene s = paper_beam();
  const PrismModel m = build_model(s, Discretization::parse("4x4"));
  LineAnalysis la(m);
  PointLoad a, b;
  a.x = 0.2, a.Fz = 1.0;
  b.x = 0.65, b.Fz = 1.0;
  const double wab = la.statics({a}, {{0.65, 0}})[0].w, wba = la.statics({b}, {{0.2, 0}})[0].w;
  BOOST_TEST(std::abs(wab - wba) < 1e-10 * std::abs(wab));
  for (double omega : {3000.0, 17000.0}) {
    const auto h1 = la.receptance({0.2, 0}, {0.65, 0}, {omega}, 0.0)[0];
    const auto h2 = la.receptance({0.65, 0}, {0.2, 0}, {omega}, 0.0)[0];
    BOOST_TEST(std::abs(h1 - h2) < 1e-9 * std::abs(h1));
  }
  s.x0 = s.xL = Support::named("free");
  const ModeList ml = modes_of(s, "2x2", 4, {ModeFamily::BendingXZ});
  BOOST_TEST(ml.rigid == 2);
  BOOST_TEST(ml.family[0] == ModeFamily::Rigid);
  BOOST_TEST(ml.omega_rad_s[1] == 0.0);
  BOOST_TEST(ml.omega_rad_s[2] > 0.0);
  const PrismModel mf = build_model(s, Discretization::parse("2x2"));
  LineAnalysis lf(mf);
  BOOST_CHECK_THROW(lf.statics({a}, {{0.5, 0}}), std::runtime_error);
}

// With structural damping the receptance is finite at a natural frequency, and tends to the
// undamped one away from resonance as eta -> 0.
BOOST_AUTO_TEST_CASE(damped_receptance) {
  const Scene s = paper_beam();
  const PrismModel m = build_model(s, Discretization::parse("2x2"));
  LineAnalysis la(m);
  const double w1 = la.modes(1, {ModeFamily::BendingXZ}).omega_rad_s[0];
  const auto at_res = la.receptance({0.1, 0}, {0.4, 0}, {w1}, 0.01)[0];
  BOOST_TEST(std::isfinite(std::abs(at_res)));
  BOOST_TEST(std::abs(at_res.imag()) > 10 * std::abs(at_res.real()));  // quadrature at resonance
  const auto und = la.receptance({0.1, 0}, {0.4, 0}, {0.6 * w1}, 0.0)[0];
  const auto small = la.receptance({0.1, 0}, {0.4, 0}, {0.6 * w1}, 1e-7)[0];
  BOOST_TEST(std::abs(small - und) < 1e-5 * std::abs(und));
}

BOOST_AUTO_TEST_SUITE_END()
