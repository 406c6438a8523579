// Which values the default path reports (solve_pipeline.cpp, choose_values; issue "accuracy on
// demand"): the Richardson extrapolation's where, and only where, its own estimate meets the
// tolerance and the mesh's does not; the output says which, keeps the mesh's own, and the status
// follows the reported values' estimate. A fake back-end whose one frequency on mesh n is
//   f(n) = f0 (1 + C / n^2 + D / n^3)
// (the error expansion the estimate and the extrapolation assume: order 2, then 3) and which has no
// finer mesh, so that the default mesh is the one judged: its estimate and the extrapolation's are
// read off a first solve, and the tolerances placed around them.
#define BOOST_TEST_MODULE reported_values
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "modalbench/json_output.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"
#include "cantilever_scene.hpp"
#include "solve_options.hpp"
#include "fake_kernels.hpp"

using namespace modalbench;

namespace {

constexpr double kF0 = 100.0, kC = 0.2, kD = -0.05;

class Series final : public Solver {
 public:
  std::string name() const override { return "series"; }
  std::string description() const override { return "f0 (1 + C / n^2 + D / n^3) on mesh n"; }
  Capability supports(const Scene&) const override { return {true, false, false, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override {
    MeshFamily f = MeshFamily::single(Discretization::parse("16"));
    f.coarser = [](const Discretization& m) -> std::optional<CoarserMesh> {
      if (m.counts.empty() || m.counts[0] < 4) return std::nullopt;
      return CoarserMesh{{{m.counts[0] / 2}}, 2.0, 2.0, 3.0};
    };
    return f;
  }

 protected:
  std::unique_ptr<Kernels> build(const Scene&, const Discretization& m, const Options&, Result&) const override {
    const double n = m.counts.at(0);
    return testing::modes_kernel([n](Result& r) {
      r.frequencies_rad_s = {kF0 * (1.0 + kC / (n * n) + kD / (n * n * n))};
      r.mode_families = {ModeFamily::BendingXZ};
      r.summary.converges_to_scene_theory = true;
    });
  }
};

Result default_path(double tolerance) {
  Scene s = testing::cantilever_scene("series", 1);
  s.request.tolerance = tolerance;
  Options o;
  o.refine_to_tolerance = true;
  const Series b;
  return b.solve_default(s, o);
}

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

}  // namespace

BOOST_AUTO_TEST_CASE(the_extrapolated_values_answer_only_where_their_own_estimate_meets_the_tolerance) {
  // The two estimates at mesh 16 (a loose tolerance: nothing to refine, nothing reported instead).
  const Result loose = default_path(1.0);
  const double mesh_estimate = loose.summary.error_estimate.frequencies;
  const double x_estimate = loose.extrapolated.frequency_error;
  BOOST_TEST_REQUIRE(x_estimate < mesh_estimate / 10);  // room for a tolerance between them
  BOOST_TEST(loose.ok());
  BOOST_TEST(!loose.extrapolated.frequencies_reported);
  BOOST_TEST(loose.extrapolated.mesh_frequencies_rad_s.empty());
  const double mesh_value = loose.frequencies_rad_s.at(0);
  // Both estimates hold for this series (the truth is f0).
  BOOST_TEST(rel(mesh_value, kF0) <= mesh_estimate);
  BOOST_TEST(rel(loose.extrapolated.frequencies_rad_s.at(0), kF0) <= x_estimate);

  // Between the two: the extrapolated value answers, says so, and keeps the mesh's.
  const Scene s = testing::cantilever_scene("series", 1);
  const Result mid = default_path(std::sqrt(x_estimate * mesh_estimate));
  BOOST_TEST((mid.summary.status == Status::Success), mid.summary.message);
  BOOST_TEST(mid.extrapolated.frequencies_reported);
  BOOST_TEST(mid.frequencies_rad_s.at(0) == mid.extrapolated.frequencies_rad_s.at(0));
  BOOST_TEST(mid.extrapolated.mesh_frequencies_rad_s.at(0) == mesh_value);
  BOOST_TEST(rel(mid.frequencies_rad_s.at(0), kF0) <= mid.extrapolated.frequency_error);
  BOOST_TEST(mid.summary.error_estimate.note.find("reported values: the Richardson extrapolation") != std::string::npos);
  const nlohmann::json j = to_json(s, "series", Discretization::parse("16"), mid);
  BOOST_TEST(j.at("values").at("frequencies").get<std::string>() == "extrapolated");
  BOOST_TEST(j.at("extrapolated").at("mesh_frequencies_rad_s").at(0).get<double>() == mesh_value);

  // Below the extrapolation's estimate: the mesh's value, not converged (no finer mesh here).
  const Result tight = default_path(x_estimate / 2);
  BOOST_TEST((tight.summary.status == Status::NotConverged));
  BOOST_TEST(!tight.extrapolated.frequencies_reported);
  BOOST_TEST(tight.frequencies_rad_s.at(0) == mesh_value);
  BOOST_TEST(to_json(s, "series", Discretization::parse("16"), tight).at("values").at("frequencies").get<std::string>() == "mesh");

  // A mesh given (not the default path): the mesh's value and its own verdict, whatever the
  // extrapolation's estimate.
  Scene given = s;
  given.request.tolerance = std::sqrt(x_estimate * mesh_estimate);
  const Series b;
  const Result m = b.solve(given, Discretization::parse("16"), Options{});
  BOOST_TEST((m.summary.status == Status::NotConverged));
  BOOST_TEST(!m.extrapolated.frequencies_reported);
  BOOST_TEST(m.frequencies_rad_s.at(0) == mesh_value);
}
