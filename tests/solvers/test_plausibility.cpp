// Plausibility warnings: right numbers for the model, outside what the model means. They name the
// value and never change the status. Each case is made from a built-in scene by one change.
#define BOOST_TEST_MODULE plausibility
#include <boost/test/unit_test.hpp>

#include <string>

#include "solver_tests.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

Scene builtin(const char* file) { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + file); }

/// The plausibility warnings of an exact solve (which must succeed).
std::vector<std::string> warnings_of(const Scene& s) {
  const Result r = registry().get("exact").solve(s, {}, Options{});
  BOOST_TEST_REQUIRE((r.summary.status == Status::Success), r.summary.message);
  std::vector<std::string> out;
  for (const auto& w : r.summary.warnings)
    if (w.rfind("plausibility:", 0) == 0) out.push_back(w);
  return out;
}

bool any_contains(const std::vector<std::string>& ws, const std::string& text) {
  for (const auto& w : ws)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

BOOST_AUTO_TEST_CASE(nominal_scenes_have_none) {
  for (const char* f : {"paper_fixed_beam.toml", "paper_ss_plate.toml", "two_span_beam.toml", "lasecka_elastic_beam.toml"}) {
    const auto ws = warnings_of(builtin(f));
    BOOST_TEST(ws.empty(), f << ": " << (ws.empty() ? "" : ws.front()));
  }
}

BOOST_AUTO_TEST_CASE(material_in_the_wrong_unit) {
  Scene s = builtin("paper_fixed_beam.toml");
  s.request.frf.reset();  // its band would span millions of the soft beam's modes
  s.material.E = 210.0;   // GPa typed as Pa
  s.material.G = 84.0;
  BOOST_TEST(any_contains(warnings_of(s), "typed in GPa"));
  s = builtin("paper_fixed_beam.toml");
  s.request.frf.reset();
  s.material.rho = 7.85;  // g/cm^3
  BOOST_TEST(any_contains(warnings_of(s), "g/cm^3"));
}

BOOST_AUTO_TEST_CASE(deflection_beyond_the_small_deflection_range) {
  Scene s = builtin("paper_ss_plate.toml");
  s.geometry.height = 1e-4;  // 1000 N on a 0.1 mm plate: metres of deflection
  s.request.frf.reset();
  BOOST_TEST(any_contains(warnings_of(s), "times the plate's thickness"));
}

BOOST_AUTO_TEST_CASE(euler_bernoulli_modes_shorter_than_the_depth) {
  Scene s = builtin("paper_fixed_beam.toml");  // 1 m long, 0.25 m deep
  s.theory = Theory::EulerBernoulli;
  s.request.frf.reset();
  s.request.modes = 2;  // half-waves of about 0.4 m
  BOOST_TEST(!any_contains(warnings_of(s), "half-wave"));
  s.request.modes = 12;  // about 1 / 12.5 m
  BOOST_TEST(any_contains(warnings_of(s), "shorter than the section depth"));
}
