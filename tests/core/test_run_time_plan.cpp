// The pipeline's run-time plan (solve_pipeline.cpp): the estimate is reported with the plan, and a
// run more than 3 times longer than its plan says so in a warning (issue: estimates that miss were
// silent). A fake back-end whose cost model says 10 ms and whose solve takes 1.1 s.
#define BOOST_TEST_MODULE run_time_plan
#include <boost/test/unit_test.hpp>

#include <chrono>
#include <string>
#include <thread>

#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"
#include "cantilever_scene.hpp"
#include "fake_kernels.hpp"

using namespace modalbench;

namespace {

class Slow final : public Solver {
 public:
  explicit Slow(double seconds) : seconds_(seconds) {}
  std::string name() const override { return "slow"; }
  std::string description() const override { return "sleeps, and estimates 10 ms"; }
  Capability supports(const Scene&) const override { return {true, true, false, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override { return MeshFamily::single(Discretization::parse("4")); }
  ResourceEstimate estimate(const Scene&, const Discretization&, const Options&) const override {
    return {1e3, 0.010, "a fixed guess"};
  }

 protected:
  std::unique_ptr<Kernels> build(const Scene& s, const Discretization&, const Options&, Result&) const override {
    return testing::modes_kernel([this, &s](Result& r) {
      std::this_thread::sleep_for(std::chrono::duration<double>(seconds_));
      r.frequencies_rad_s.assign(static_cast<std::size_t>(s.request.modes), 1.0);
      r.mode_families.assign(static_cast<std::size_t>(s.request.modes), ModeFamily::BendingXZ);
    });
  }

 private:
  double seconds_;
};

std::size_t plan_warnings(const Result& r) {
  std::size_t n = 0;
  for (const auto& w : r.summary.warnings) n += w.find("times the estimate") != std::string::npos;
  return n;
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_run_far_past_its_plan_says_so) {
  const Scene s = testing::cantilever_scene("plan", 2);
  Options o;
  o.estimate_error = false;
  const Result slow = Slow(1.1).solve(s, Discretization::parse("4"), o);
  BOOST_TEST(slow.summary.diagnostic("estimated_time_planned_s") == 0.010);
  BOOST_TEST(plan_warnings(slow) == 1u);
  // Within the factor (and under a second, where a cost model's constant dominates): nothing said.
  const Result quick = Slow(0.02).solve(s, Discretization::parse("4"), o);
  BOOST_TEST(plan_warnings(quick) == 0u);
}
