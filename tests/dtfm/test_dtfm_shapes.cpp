// dtfm mode shapes (request.shapes): against the exact back-end's shapes (one prism is the
// exact Timoshenko beam; the strip plate against Navier), effective masses of a cantilever
// against the closed form, repeated roots of a square section, and no shapes unless asked.
#define BOOST_TEST_MODULE dtfm_shapes
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "modalbench/dtfm/dtfm.hpp"
#include "solve_options.hpp"
#include "modalbench/exact/exact.hpp"

using namespace modalbench;
using namespace modalbench::dtfm;

namespace {

Scene scene(const char* file) { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + file); }

/// Only the modes (and their shapes): no statics, no FRF.
Scene modes_only(Scene s, int modes, ShapeRequest shapes) {
  s.request.modes = modes;
  s.request.probes.clear();
  s.loads.clear();
  s.request.frf.reset();
  s.request.shapes = shapes;
  return s;
}

int slot(const ModeShapes& ms, int dof) {
  const auto it = std::find(ms.components.begin(), ms.components.end(), dof);
  return it == ms.components.end() ? -1 : static_cast<int>(it - ms.components.begin());
}

/// |a.b|^2 / ((a.a)(b.b)) over the concatenation of the given components.
double mac(const ModeShapes& a, std::size_t ka, const ModeShapes& b, std::size_t kb, const std::vector<int>& dofs) {
  double ab = 0, aa = 0, bb = 0;
  for (int dof : dofs) {
    const auto& va = a.values[ka][static_cast<std::size_t>(slot(a, dof))];
    const auto& vb = b.values[kb][static_cast<std::size_t>(slot(b, dof))];
    for (std::size_t i = 0; i < va.size(); ++i) {
      ab += va[i] * vb[i];
      aa += va[i] * va[i];
      bb += vb[i] * vb[i];
    }
  }
  return ab * ab / (aa * bb);
}

}  // namespace

// One prism is the exact Timoshenko beam: the sampled w and theta_y of every mode, the
// (unit) generalized masses and the effective masses agree with the exact back-end's.
BOOST_AUTO_TEST_CASE(one_prism_matches_exact_timoshenko_shapes) {
  const Scene s = modes_only(scene("paper_fixed_beam.toml"), 6, ShapeRequest{41, 1});
  const Result d = DtfmSolver().solve(s, Discretization::parse("1x1"), testing::own_error_study());
  const Result e = exact::ExactSolver().solve(s, {}, {});
  BOOST_TEST_REQUIRE(d.ok(), d.summary.message);
  BOOST_TEST_REQUIRE(e.ok(), e.summary.message);
  const ModeShapes& a = d.mode_shapes;
  const ModeShapes& b = e.mode_shapes;
  BOOST_REQUIRE_EQUAL(a.values.size(), 6u);
  BOOST_REQUIRE_EQUAL(b.values.size(), 6u);
  BOOST_REQUIRE_EQUAL(a.points.size(), 41u);
  BOOST_TEST(a.total_mass == b.total_mass, boost::test_tools::tolerance(1e-14));
  double worst = 0, worst_meff = 0;
  for (std::size_t k = 0; k < 6; ++k) {
    BOOST_TEST(a.generalized_mass[k] == 1.0, boost::test_tools::tolerance(1e-14));
    // A mode's sign is fixed by its largest translation sample; an antisymmetric mode has two
    // of equal size, so the sign is compared up to -1.
    double diff[2] = {0, 0};
    for (int dof : {2, 4}) {
      const auto& va = a.values[k][static_cast<std::size_t>(slot(a, dof))];
      const auto& vb = b.values[k][static_cast<std::size_t>(slot(b, dof))];
      double scale = 0, dp = 0, dm = 0;
      for (std::size_t i = 0; i < vb.size(); ++i) {
        scale = std::max(scale, std::abs(vb[i]));
        dp = std::max(dp, std::abs(va[i] - vb[i]));
        dm = std::max(dm, std::abs(va[i] + vb[i]));
      }
      diff[0] = std::max(diff[0], dp / scale);
      diff[1] = std::max(diff[1], dm / scale);
    }
    const double dk = std::min(diff[0], diff[1]);
    worst = std::max(worst, dk);
    BOOST_TEST(dk <= 1e-8, "mode " << k + 1 << ": shape differs from exact by " << dk);
    const double dmeff = std::abs(a.effective_mass[k][2] - b.effective_mass[k][2]) / a.total_mass;
    worst_meff = std::max(worst_meff, dmeff);
    BOOST_TEST(dmeff <= 1e-8, "mode " << k + 1 << ": effective mass differs by " << dmeff << " of the total");
  }
  BOOST_TEST_MESSAGE("one prism vs exact: largest shape difference " << worst << ", effective mass " << worst_meff);
}

// A cantilever (Euler-Bernoulli, one prism): the effective masses in z of 64 modes add up to
// the beam's mass within 1 % (the tail beyond mode n is about 4 / (pi^2 n) of it), and mode 1
// carries 61.31 % (closed form 0.6131).
BOOST_AUTO_TEST_CASE(cantilever_effective_masses) {
  Scene s = modes_only(scene("paper_fixed_beam.toml"), 64, ShapeRequest{41, 1});
  s.theory = Theory::EulerBernoulli;
  s.xL = Support::named("free");
  const Result r = DtfmSolver().solve(s, Discretization::parse("1x1"), testing::own_error_study());
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const ModeShapes& ms = r.mode_shapes;
  BOOST_REQUIRE_EQUAL(ms.values.size(), 64u);
  double sum = 0;
  for (std::size_t k = 0; k < 64; ++k) {
    BOOST_TEST(ms.generalized_mass[k] == 1.0, boost::test_tools::tolerance(1e-14));
    BOOST_TEST(ms.effective_mass[k][0] == 0.0);
    sum += ms.effective_mass[k][2];
  }
  const double share1 = ms.effective_mass[0][2] / ms.total_mass;
  BOOST_TEST_MESSAGE("cantilever: 64 modes carry " << sum / ms.total_mass << " of the mass, mode 1 " << share1);
  BOOST_TEST(std::abs(sum / ms.total_mass - 1.0) <= 0.01);
  BOOST_TEST(sum <= ms.total_mass * (1 + 1e-12));
  BOOST_TEST(std::abs(share1 - 0.6131) <= 1e-3);
}

// The strip plate against Navier's shapes: MAC over the sampled w of the first 6 modes.
BOOST_AUTO_TEST_CASE(plate_shapes_match_navier) {
  const Scene s = modes_only(scene("paper_ss_plate.toml"), 8,
                             ShapeRequest{ShapeRequest::kPlateDefaultNx, ShapeRequest::kPlateDefaultNy});
  const Result d = DtfmSolver().solve(s, Discretization::parse("10"), testing::own_error_study());
  const Result e = exact::ExactSolver().solve(s, {}, {});
  BOOST_TEST_REQUIRE(d.ok(), d.summary.message);
  BOOST_TEST_REQUIRE(e.ok(), e.summary.message);
  BOOST_REQUIRE_EQUAL(d.mode_shapes.values.size(), 8u);
  BOOST_REQUIRE_EQUAL(e.mode_shapes.values.size(), 8u);
  BOOST_TEST((d.mode_shapes.components == std::vector<int>{2, 3, 4}));
  for (std::size_t k = 0; k < 6; ++k) {
    const double m = mac(d.mode_shapes, k, e.mode_shapes, k, {2});
    BOOST_TEST_MESSAGE("plate mode " << k + 1 << ": MAC(w) " << m);
    BOOST_TEST(m >= 0.999, "mode " << k + 1 << ": MAC " << m);
    BOOST_TEST(d.mode_shapes.generalized_mass[k] == 1.0, boost::test_tools::tolerance(1e-14));
  }
}

// A square section: the two bending modes of each order coincide (two symmetry classes); their
// shapes are orthogonal and every mode is mass-normalized.
BOOST_AUTO_TEST_CASE(square_section_repeated_roots) {
  Scene s = modes_only(scene("dtfm_spatial_beam.toml"), 12, ShapeRequest{41, 1});
  s.geometry.width = s.geometry.height;
  const Result r = DtfmSolver().solve(s, Discretization::parse("2x2"), testing::own_error_study());
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const ModeShapes& ms = r.mode_shapes;
  BOOST_REQUIRE_EQUAL(ms.values.size(), r.frequencies_rad_s.size());
  BOOST_TEST((ms.directions == std::array<bool, 3>{true, true, true}));
  int pairs = 0;
  for (std::size_t k = 0; k + 1 < ms.values.size(); ++k) {
    const double w0 = r.frequencies_rad_s[k], w1 = r.frequencies_rad_s[k + 1];
    if (std::abs(w1 - w0) > 1e-6 * w1) continue;
    ++pairs;
    const double m = mac(ms, k, ms, k + 1, {0, 1, 2});
    BOOST_TEST_MESSAGE("square section: modes " << k + 1 << ", " << k + 2 << " at " << w0 << " rad/s: MAC " << m);
    BOOST_TEST(m < 1e-6);
  }
  BOOST_TEST(pairs >= 2);
  double sum[3] = {0, 0, 0};
  for (std::size_t k = 0; k < ms.values.size(); ++k) {
    BOOST_TEST(ms.generalized_mass[k] == 1.0, boost::test_tools::tolerance(1e-14));
    for (int d = 0; d < 3; ++d) sum[d] += ms.effective_mass[k][static_cast<std::size_t>(d)];
  }
  for (int d = 0; d < 3; ++d) BOOST_TEST(sum[d] <= ms.total_mass * (1 + 1e-12));
}

// The rigid modes of a free-free beam (three translations, three rotations; in the bending
// class a translation and a rotation together) are mass-orthonormalized: together they carry
// the whole mass in every direction.
BOOST_AUTO_TEST_CASE(rigid_modes_carry_the_whole_mass) {
  Scene s = modes_only(scene("dtfm_spatial_beam.toml"), 6, ShapeRequest{41, 1});
  s.x0 = s.xL = Support::named("free");
  const Result r = DtfmSolver().solve(s, Discretization::parse("2x2"), testing::own_error_study());
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  const ModeShapes& ms = r.mode_shapes;
  BOOST_REQUIRE_EQUAL(ms.values.size(), 6u);
  double sum[3] = {0, 0, 0};
  for (std::size_t k = 0; k < 6; ++k) {
    BOOST_TEST((r.mode_families[k] == ModeFamily::Rigid));
    BOOST_TEST(ms.generalized_mass[k] == 1.0, boost::test_tools::tolerance(1e-14));
    for (int d = 0; d < 3; ++d) sum[d] += ms.effective_mass[k][static_cast<std::size_t>(d)];
  }
  for (int d = 0; d < 3; ++d) BOOST_TEST(sum[d] / ms.total_mass == 1.0, boost::test_tools::tolerance(1e-10));
}

// Without request.shapes nothing is computed.
BOOST_AUTO_TEST_CASE(no_shapes_unless_requested) {
  Scene s = scene("paper_fixed_beam.toml");
  BOOST_TEST(!s.request.shapes.has_value());
  const Result r = DtfmSolver().solve(s, Discretization::parse("2x2"), testing::own_error_study());
  BOOST_TEST(r.ok());
  BOOST_TEST(r.frequencies_rad_s.size() == 6u);
  BOOST_TEST(r.mode_shapes.empty());
  BOOST_TEST(r.mode_shapes.points.empty());
}
