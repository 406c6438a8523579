// The mesh estimate's factor of safety (discretization_error.cpp, Gci; issue "accuracy on demand":
// "where a fourth mesh confirms the observed order, the estimate uses it (Roache's 1.25) instead of
// the two-mesh factor 3"). A fake back-end whose one frequency on mesh n is
//   f(n) = f0 (1 + C / n^p + D / n^s),
// solved on a given mesh 32 and judged against 16, 8 and 4 (the family states a next order, so the
// fourth mesh is solved). Its truth is f0: each case checks the estimate against the true error of
// the mesh value (the contract: never below it) and which factor of safety was taken.
#define BOOST_TEST_MODULE confirmed_order
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"
#include "cantilever_scene.hpp"
#include "fake_kernels.hpp"

using namespace modalbench;

namespace {

constexpr double kF0 = 100.0;

/// f0 (1 + C / n^p + D / n^s) on mesh n; the family claims order 2 (next 4).
struct Series {
  double C = 0.3, p = 2.0, D = 0.0, s = 4.0;
  double at(double n) const { return kF0 * (1.0 + C / std::pow(n, p) + D / std::pow(n, s)); }
};

class SeriesSolver final : public Solver {
 public:
  explicit SeriesSolver(Series s, int coarsest = 4) : s_(s), coarsest_(coarsest) {}
  std::string name() const override { return "series"; }
  std::string description() const override { return "f0 (1 + C / n^p + D / n^s) on mesh n"; }
  Capability supports(const Scene&) const override { return {true, false, false, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override {
    MeshFamily f = MeshFamily::single(Discretization::parse("32"));
    const int coarsest = coarsest_;
    f.coarser = [coarsest](const Discretization& m) -> std::optional<CoarserMesh> {
      if (m.counts.empty() || m.counts[0] / 2 < coarsest) return std::nullopt;
      return CoarserMesh{{{m.counts[0] / 2}}, 2.0, 2.0, 4.0};
    };
    return f;
  }

 protected:
  std::unique_ptr<Kernels> build(const Scene&, const Discretization& m, const Options&, Result&) const override {
    const double n = m.counts.at(0);
    return testing::modes_kernel([this, n](Result& r) {
      r.frequencies_rad_s = {s_.at(n)};
      r.mode_families = {ModeFamily::BendingXZ};
      r.summary.converges_to_scene_theory = true;
    });
  }

 private:
  Series s_;
  int coarsest_;
};

Result on_mesh_32(Series s, int coarsest = 4) {
  Scene scene = testing::cantilever_scene("series", 1);
  scene.request.tolerance = 1.0;  // judged, not refined
  const SeriesSolver b(s, coarsest);
  return b.solve(scene, Discretization::parse("32"), Options{});
}

double true_error(const Result& r) { return std::abs(r.frequencies_rad_s.at(0) / kF0 - 1.0); }

/// The true error of mesh 32 relative to the pair's larger value, as the estimate measures it.
double true_error_on_pair_scale(const Series& s) {
  return std::abs(s.at(32) - kF0) / std::max(std::abs(s.at(32)), std::abs(s.at(16)));
}

bool says_confirmed(const Result& r) {
  return r.summary.error_estimate.note.find("where the fourth mesh 4 confirms it") != std::string::npos;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_confirmed_formal_order_takes_the_factor_of_safety_1_25) {
  // The formal order, exactly: the estimate is 1.25 times the truth (the three-mesh GCI).
  const Series s;
  const Result r = on_mesh_32(s);
  const double e = r.summary.error_estimate.frequencies;
  BOOST_TEST(r.summary.error_estimate.safety_factor == 1.25);
  BOOST_TEST(says_confirmed(r), r.summary.error_estimate.note);
  BOOST_TEST(e >= true_error(r));
  BOOST_TEST(e == 1.25 * true_error_on_pair_scale(s), boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(an_order_confirmed_below_the_formal_one_is_used_with_1_25) {
  // Order 1.7 on all four meshes (within 20 % of 2): the observed order, not the formal one, so
  // the estimate still holds (with 2 it would be 1.25 (2^1.7 - 1) / 3 = 0.94 of the truth).
  const Series s{.C = 0.3, .p = 1.7};
  const Result r = on_mesh_32(s);
  const double e = r.summary.error_estimate.frequencies;
  BOOST_TEST(r.summary.error_estimate.safety_factor == 1.25);
  BOOST_TEST(e >= true_error(r));
  // The observed order is found by bisection to about 1e-15: the estimate to some 1e-12.
  BOOST_TEST(e == 1.25 * true_error_on_pair_scale(s), boost::test_tools::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(an_order_far_from_the_formal_one_keeps_the_factor_of_safety_3) {
  // First order where the family claims second (a free plate edge's strips): not confirmed.
  const Result r = on_mesh_32({.C = 0.3, .p = 1.0});
  BOOST_TEST(r.summary.error_estimate.safety_factor == 3.0);
  BOOST_TEST(!says_confirmed(r));
  BOOST_TEST(r.summary.error_estimate.frequencies >= true_error(r));
}

BOOST_AUTO_TEST_CASE(coarse_meshes_off_the_asymptotic_range_do_not_confirm) {
  // A higher term that dominates on the coarse meshes: the coarser three show another order than
  // the finer three, and the factor 3 stays.
  const Result r = on_mesh_32({.C = 0.3, .p = 2.0, .D = 60.0, .s = 4.0});
  BOOST_TEST(r.summary.error_estimate.safety_factor == 3.0);
  BOOST_TEST(!says_confirmed(r));
  BOOST_TEST(r.summary.error_estimate.frequencies >= true_error(r));
}

BOOST_AUTO_TEST_CASE(differences_that_change_sign_do_not_confirm) {
  // C and D of opposite signs: the error crosses zero between meshes 4 and 8 (not monotone).
  const Result r = on_mesh_32({.C = 0.3, .p = 2.0, .D = -12.0, .s = 4.0});
  const auto& e = r.summary.error_estimate;
  BOOST_TEST(e.safety_factor == 3.0);
  BOOST_TEST(!says_confirmed(r));
  BOOST_TEST(e.frequencies >= true_error(r));
}

BOOST_AUTO_TEST_CASE(three_meshes_keep_the_factor_of_safety_3) {
  // No fourth mesh (the family stops at 8): nothing to confirm with.
  const Series s;
  const Result r = on_mesh_32(s, 8);
  BOOST_TEST(r.summary.error_estimate.safety_factor == 3.0);
  BOOST_TEST(!says_confirmed(r));
  BOOST_TEST(r.summary.error_estimate.frequencies == 3.0 * true_error_on_pair_scale(s), boost::test_tools::tolerance(1e-9));
}
