// The pipeline's kernel steps (core/src/solve_kernels.cpp, kernels.hpp): each quantity a step with
// its own status; a failed step leaves the others' results standing; a statics step that finds a
// mechanism is the input's fault; a quantity the back-end has no kernel for is said, not skipped;
// statics refused on a scene that asks them only for a time history are dropped, not fatal. Also
// the mesh family driving the default path (MeshFamily, Solver::solve_default).
#define BOOST_TEST_MODULE kernel_steps
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"
#include "cantilever_scene.hpp"
#include "fake_kernels.hpp"

using namespace modalbench;

namespace {

/// Frequencies 1, 2, ... and a statics kernel that does what it is told.
class Fake final : public Solver {
 public:
  enum class Statics { Deflect, Throw, Mechanism, Absent };
  explicit Fake(Statics statics) : statics_(statics) {}
  std::string name() const override { return "fake"; }
  std::string description() const override { return "known frequencies; statics as told"; }
  Capability supports(const Scene&) const override { return {true, true, false, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override { return MeshFamily::single({}); }

 protected:
  std::unique_ptr<Kernels> build(const Scene& s, const Discretization&, const Options&, Result& r) const override {
    r.summary.model = "fake";
    auto modes = [&s](Result& x) {
      for (int i = 1; i <= s.request.modes; ++i) {
        x.frequencies_rad_s.push_back(i);
        x.mode_families.push_back(ModeFamily::BendingXZ);
      }
    };
    if (statics_ == Statics::Absent) return std::make_unique<ModesOnly>(modes);
    const Statics how = statics_;
    auto statics = [&s, how](Result& x) {
      x.deflections.resize(s.request.probes.size());  // partly filled before a failure
      if (how == Statics::Throw) throw std::runtime_error("factorization broke down");
      if (how == Statics::Mechanism) throw std::runtime_error("mechanism: nothing holds the beam");
    };
    return std::make_unique<testing::FakeKernels>(modes, statics);
  }

 private:
  /// Kernels that provide the modes and nothing else (Kernels' defaults for the rest).
  class ModesOnly final : public Kernels {
   public:
    explicit ModesOnly(testing::FakeKernels::Fill f) : f_(std::move(f)) {}
    void modes(Result& r) override { f_(r); }

   private:
    testing::FakeKernels::Fill f_;
  };
  Statics statics_;
};

Scene with_probe() {
  Scene s = testing::cantilever_scene("steps", 3);
  s.request.probes.push_back({1.0, 0.0});
  return s;
}

const StepOutcome& step(const Result& r, const std::string& name) {
  for (const auto& s : r.summary.steps)
    if (s.step == name) return s;
  throw std::runtime_error("no step " + name);
}

}  // namespace

BOOST_AUTO_TEST_CASE(each_quantity_is_a_step_with_its_own_status) {
  const Result r = Fake(Fake::Statics::Deflect).solve(with_probe(), {}, Options{});
  BOOST_TEST(r.ok(), r.summary.message);
  BOOST_REQUIRE_EQUAL(r.summary.steps.size(), 2u);
  BOOST_TEST(r.summary.steps[0].step == "modes");
  BOOST_TEST(r.summary.steps[1].step == "statics");
  BOOST_TEST(r.frequencies_rad_s.size() == 3u);
  BOOST_TEST(r.deflections.size() == 1u);
}

BOOST_AUTO_TEST_CASE(a_failed_step_leaves_the_others_standing) {
  const Result r = Fake(Fake::Statics::Throw).solve(with_probe(), {}, Options{});
  BOOST_TEST(to_string(r.summary.status) == "numerical-issue");
  BOOST_TEST(r.frequencies_rad_s.size() == 3u);  // the modes stand
  BOOST_TEST(r.deflections.empty());             // what the failed step left half-done is not reported
  BOOST_TEST(to_string(step(r, "modes").status) == "success");
  BOOST_TEST(to_string(step(r, "statics").status) == "numerical-issue");
  BOOST_TEST(step(r, "statics").message == "fake: statics: factorization broke down");
  BOOST_TEST(r.summary.message == "fake: statics: factorization broke down");
}

BOOST_AUTO_TEST_CASE(a_mechanism_in_statics_is_the_inputs_fault) {
  const Result r = Fake(Fake::Statics::Mechanism).solve(with_probe(), {}, Options{});
  BOOST_TEST(to_string(r.summary.status) == "invalid-input");
  BOOST_TEST(r.summary.message == "steps.toml: supports: static solve impossible: mechanism: nothing holds the beam");
  BOOST_TEST(r.frequencies_rad_s.size() == 3u);
}

BOOST_AUTO_TEST_CASE(a_quantity_without_a_kernel_is_said) {
  // Capability offers statics but the back-end built no kernel for them: a numerical issue that
  // names the quantity, never a silent empty answer.
  const Result r = Fake(Fake::Statics::Absent).solve(with_probe(), {}, Options{});
  BOOST_TEST(to_string(r.summary.status) == "numerical-issue");
  BOOST_TEST(r.summary.message.find("fake: statics: the back-end has no kernel for statics") != std::string::npos,
             r.summary.message);
  BOOST_TEST(r.frequencies_rad_s.size() == 3u);
}

BOOST_AUTO_TEST_CASE(statics_refused_for_a_time_history_are_dropped) {
  // A time history asks for statics only for its static correction: a mechanism there drops them
  // (said in a warning) instead of failing the history.
  Scene s = with_probe();
  PointLoad tip;
  tip.x = 1.0;
  tip.Fz = -1.0;
  s.loads.push_back(tip);
  s.request.transient = TransientRequest{};
  s.request.transient->duration = 0.01;
  s.request.transient->step = 1e-3;
  const Result r = Fake(Fake::Statics::Mechanism).solve(s, {}, Options{});
  BOOST_TEST(to_string(r.summary.status) != "invalid-input", r.summary.message);
  BOOST_TEST(r.deflections.empty());
  bool said = false;
  for (const auto& w : r.summary.warnings) said = said || w.find("not computed: static deflections") != std::string::npos;
  BOOST_TEST(said);
  for (const auto& st : r.summary.steps) BOOST_TEST(st.step != "statics");
}

namespace {

/// f0 (1 + 1 / n^2) on mesh n: a family with a default mesh 4, halving coarser meshes and finer ones
/// by the factor asked; the default path refines it.
class Family final : public Solver {
 public:
  std::string name() const override { return "family"; }
  std::string description() const override { return "f0 (1 + 1 / n^2)"; }
  Capability supports(const Scene&) const override { return {true, false, false, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override {
    MeshFamily f = MeshFamily::single(Discretization::parse("4"));
    f.coarser = [](const Discretization& m) -> std::optional<CoarserMesh> {
      if (m.counts.at(0) < 2) return std::nullopt;
      return CoarserMesh{{{m.counts[0] / 2}}, 2.0, 2.0};
    };
    f.finer = [](const Discretization& m, double factor) -> std::optional<Discretization> {
      return Discretization{{static_cast<int>(std::ceil(m.counts.at(0) * factor))}};
    };
    return f;
  }

 protected:
  std::unique_ptr<Kernels> build(const Scene&, const Discretization& m, const Options&, Result&) const override {
    const double n = m.counts.at(0);
    return testing::modes_kernel([n](Result& r) {
      r.frequencies_rad_s = {100.0 * (1.0 + 1.0 / (n * n))};
      r.mode_families = {ModeFamily::BendingXZ};
      r.summary.converges_to_scene_theory = true;
    });
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(the_default_path_starts_from_the_family_and_refines) {
  Scene s = testing::cantilever_scene("family", 1);
  s.request.tolerance = 1e-3;
  const Result r = Family().solve_default(s, Options{});
  // On 4 the estimate is 3 (|f_4 - f_2| / 3) / f_4, far above 1e-3: the family's finer meshes are
  // solved until it is met; the mesh kept meets it by the same estimate.
  BOOST_TEST(r.ok(), r.summary.message);
  BOOST_TEST(r.summary.mesh != "4");
  BOOST_TEST(r.summary.error_estimate.frequencies <= 1e-3);
  const double n = std::stoi(r.summary.mesh);
  BOOST_TEST(r.frequencies_rad_s.at(0) == 100.0 * (1.0 + 1.0 / (n * n)));
}

// An FRF asked and none computed is not a success (the fuzzer's find: a 1e13 m Mindlin plate on
// dtfm, both samples beyond the model's count range, reported success with an empty FRF); one or
// two samples of several on a resonance stay a warning.
BOOST_AUTO_TEST_CASE(an_frf_with_every_sample_omitted_is_a_numerical_issue) {
  Summary all;
  note_frf_omissions(all, 2, 2, "beyond the model's range");
  BOOST_TEST((all.status == Status::NumericalIssue));
  BOOST_TEST(all.message.find("2 of 2") != std::string::npos);
  Summary some;
  note_frf_omissions(some, 2, 50, "on a resonance");
  BOOST_TEST((some.status == Status::Success));
  BOOST_TEST(some.warnings.size() == 1u);
}
