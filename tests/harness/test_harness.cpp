// The comparison harness itself: errors, Richardson, mode matching, failing back-ends, report.
#define BOOST_TEST_MODULE harness
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "modalbench/exact/exact.hpp"
#include "modalbench/harness/comparison.hpp"
#include "modalbench/harness/files.hpp"
#include "modalbench/harness/report.hpp"
#include "temp_dir.hpp"
#include "fake_kernels.hpp"

using namespace modalbench;
using F = ModeFamily;

namespace {

Scene beam_scene() { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml"); }

/// A back-end whose frequencies are the exact ones times (1 + c / n^2) for mesh n: a
/// manufactured second-order method, so errors and Richardson are known in closed form.
class Manufactured final : public Solver {
 public:
  std::string name() const override { return "manufactured"; }
  std::string description() const override { return "exact * (1 + c/n^2)"; }
  Capability supports(const Scene&) const override { return {true, false, false, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override {
    MeshFamily f = MeshFamily::single(Discretization::parse("4"));
    f.ladder = {Discretization::parse("4"), Discretization::parse("8"), Discretization::parse("16")};
    f.stress = {f.ladder.back()};
    return f;
  }

 protected:
  std::unique_ptr<Kernels> build(const Scene& s, const Discretization& mesh, const Options& o, Result&) const override {
    return testing::modes_kernel([&s, mesh, &o](Result& r) {
      exact::ExactSolver ex;
      Result x = ex.solve(s, {}, o);
      const double n = mesh.counts.at(0);
      for (std::size_t i = 0; i < x.frequencies_rad_s.size(); ++i) {
        r.frequencies_rad_s.push_back(x.frequencies_rad_s[i] * (1 + 0.5 * static_cast<double>(i + 1) / (n * n)));
        r.mode_families.push_back(x.mode_families[i]);
      }
      r.summary.unknowns = static_cast<long>(2 * n);
    });
  }
};

class Throwing final : public Solver {
 public:
  std::string name() const override { return "throwing"; }
  std::string description() const override { return "always fails"; }
  Capability supports(const Scene&) const override { return {true, false, false, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override { return MeshFamily::single(Discretization::parse("2")); }

 protected:
  std::unique_ptr<Kernels> build(const Scene&, const Discretization&, const Options&, Result&) const override {
    return testing::modes_kernel([](Result&) { throw std::runtime_error("deliberate failure"); });
  }
};

class NaNSolver final : public Solver {
 public:
  std::string name() const override { return "nan"; }
  std::string description() const override { return "returns NaN"; }
  Capability supports(const Scene&) const override { return {true, false, false, ""}; }
  MeshFamily meshes(const Scene&, const Options&) const override { return MeshFamily::single(Discretization::parse("2")); }

 protected:
  std::unique_ptr<Kernels> build(const Scene&, const Discretization&, const Options&, Result&) const override {
    return testing::modes_kernel([](Result& r) { r.frequencies_rad_s = {1.0, std::nan("")}; });
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(relative_errors) {
  BOOST_TEST(relative_error(101.0, 100.0) == 0.01, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(relative_error(99.0, 100.0) == 0.01, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(std::isnan(relative_error(1.0, 0.0)));
  BOOST_TEST(std::isnan(relative_error(std::nan(""), 1.0)));
}

// f(h) = 3 + 2 h^2 sampled at h = 1, 1/2, 1/4 (and an uneven ladder with p = 1.5).
BOOST_AUTO_TEST_CASE(richardson_recovers_manufactured_limit) {
  Richardson r = richardson({1.0, 0.5, 0.25}, {5.0, 3.5, 3.125});
  BOOST_TEST(r.ok);
  BOOST_TEST(r.value == 3.0, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(r.order == 2.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(r.uncertainty == 0.125, boost::test_tools::tolerance(1e-9));
  const std::vector<double> h = {1.0 / 4, 1.0 / 7, 1.0 / 10};
  std::vector<double> f;
  for (double x : h) f.push_back(-1.0 + 0.3 * std::pow(x, 1.5));
  r = richardson(h, f);
  BOOST_TEST(r.ok);
  BOOST_TEST(r.value == -1.0, boost::test_tools::tolerance(1e-10));
  BOOST_TEST(r.order == 1.5, boost::test_tools::tolerance(1e-8));
  // An oscillating sequence is not extrapolated.
  r = richardson({1.0, 0.5, 0.25}, {5.0, 3.0, 3.5});
  BOOST_TEST(!r.ok);
  BOOST_TEST(r.value == 3.5);
}

// A square beam: bending x-z and x-y coincide; torsion and axial modes sit in between.
// A back-end that lists them in another order (coincident pair swapped, an extra axial mode
// early) must still be paired family by family.
BOOST_AUTO_TEST_CASE(mode_matching_by_family) {
  const std::vector<F> ref = {F::Rigid, F::BendingXZ, F::BendingXY, F::Torsion, F::BendingXZ, F::BendingXY, F::Axial};
  const std::vector<F> run = {F::BendingXY, F::BendingXZ, F::Axial, F::Torsion, F::BendingXY, F::BendingXZ};
  const auto m = match_modes(ref, run);
  BOOST_TEST(m[0] == -1);  // rigid never compared
  BOOST_TEST(m[1] == 1);
  BOOST_TEST(m[2] == 0);
  BOOST_TEST(m[3] == 3);
  BOOST_TEST(m[4] == 5);
  BOOST_TEST(m[5] == 4);
  BOOST_TEST(m[6] == 2);
  // Missing modes are unmatched, not paired with another family.
  const auto m2 = match_modes({F::Torsion, F::BendingXZ}, {F::BendingXZ});
  BOOST_TEST(m2[0] == -1);
  BOOST_TEST(m2[1] == 0);
  // Unlabelled runs fall back to order among elastic modes.
  const auto m3 = match_modes({F::Rigid, F::Plate, F::Plate}, {F::Rigid, F::Unknown, F::Unknown});
  BOOST_TEST(m3[1] == 1);
  BOOST_TEST(m3[2] == 2);
}

BOOST_AUTO_TEST_CASE(errors_against_exact_and_failures_become_rows) {
  Registry reg;
  reg.add(std::make_unique<exact::ExactSolver>());
  reg.add(std::make_unique<Manufactured>());
  reg.add(std::make_unique<Throwing>());
  reg.add(std::make_unique<NaNSolver>());
  CompareOptions opt;
  opt.quick = true;
  const auto all = run_comparison({beam_scene()}, reg, opt);
  BOOST_REQUIRE(all.size() == 1u);
  const auto& c = all[0];
  BOOST_TEST(c.reference.source == "exact");
  int manufactured = 0, throwing = 0, nan = 0;
  for (const auto& r : c.runs) {
    if (r.backend == "manufactured") {
      const double n = r.mesh.counts[0];
      // Mode i has relative error 0.5 i / n^2; the worst of the first 6 is mode 6.
      BOOST_TEST(r.max_frequency_error == 3.0 / (n * n), boost::test_tools::tolerance(1e-9));
      BOOST_TEST(r.frequency_errors[0] == 0.5 / (n * n), boost::test_tools::tolerance(1e-9));
      ++manufactured;
    }
    if (r.backend == "throwing") {
      BOOST_TEST(r.failed());
      BOOST_TEST((r.result.summary.status == Status::NumericalIssue));
      BOOST_TEST(r.result.summary.message.find("deliberate failure") != std::string::npos);
      BOOST_TEST(std::isnan(r.max_frequency_error));
      ++throwing;
    }
    if (r.backend == "nan") {
      BOOST_TEST(r.failed());  // a NaN never passes as success
      BOOST_TEST(r.result.summary.message.find("non-finite") != std::string::npos);
      ++nan;
    }
  }
  // Every back-end has its rows: a missing row fails here instead of skipping its checks.
  BOOST_TEST(manufactured == 3);
  BOOST_TEST(throwing >= 1);
  BOOST_TEST(nan >= 1);
  // Errors 3/n^2: 0.19, 0.047, 0.0117 for n = 4, 8, 16. 1 % is never reached; 2 % is, at n = 16.
  BOOST_TEST(std::isnan(time_to_accuracy(c, "manufactured", 1e-2)));
  BOOST_TEST(std::isfinite(time_to_accuracy(c, "manufactured", 2e-2)));
}

// Without an exact reference the harness extrapolates the manufactured back-end and finds
// the exact values back (second order, uniform ladder).
BOOST_AUTO_TEST_CASE(richardson_reference_when_no_exact) {
  Registry reg;
  reg.add(std::make_unique<Manufactured>());
  CompareOptions opt;
  opt.quick = true;
  const auto all = run_comparison({beam_scene()}, reg, opt);
  const auto& c = all[0];
  BOOST_TEST(c.reference.source == "richardson(manufactured)");
  const double exact1 = 6211.15;
  BOOST_TEST(std::abs(c.reference.frequencies_rad_s[0] / exact1 - 1) < 1e-6);
}

BOOST_AUTO_TEST_CASE(report_files_agree_with_the_runs) {
  Registry reg;
  reg.add(std::make_unique<exact::ExactSolver>());
  reg.add(std::make_unique<Manufactured>());
  reg.add(std::make_unique<Throwing>());
  CompareOptions opt;
  opt.quick = true;
  const auto all = run_comparison({beam_scene()}, reg, opt);
  const modalbench_test::TempDir tmp("modalbench_test_report");
  const auto dir = tmp.path();
  write_report(all, dir.string(), ReportOptions{});
  for (const char* f : {"index.html", "report.md", "runs.csv", "frequencies.csv", "results.json"})
    BOOST_TEST(std::filesystem::exists(dir / f), f);
  std::ifstream js(dir / "results.json");
  const auto j = nlohmann::json::parse(js);
  BOOST_TEST(j["environment"].contains("compiler"));
  const auto& runs = j["scenes"][0]["runs"];
  BOOST_TEST(runs.size() == all[0].runs.size());
  BOOST_REQUIRE(runs.size() >= 4u);  // exact, three manufactured rungs, the failure
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& rec = all[0].runs[i];
    BOOST_TEST(runs[i]["backend"] == rec.backend);
    // The manufactured runs have an error, the reference none against itself, the failed run
    // none at all (null).
    if (rec.backend == "throwing") {
      BOOST_TEST(runs[i]["max_frequency_error"].is_null());
    } else {
      BOOST_REQUIRE(std::isfinite(rec.max_frequency_error));
      BOOST_TEST(runs[i]["max_frequency_error"].get<double>() == rec.max_frequency_error);
      if (rec.backend == "exact") BOOST_TEST(rec.max_frequency_error == 0.0);
    }
  }
  std::ifstream md(dir / "report.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  BOOST_TEST(text.find("deliberate failure") != std::string::npos);  // the failed row says why
  BOOST_TEST(text.find("Table 1 of the prism paper") != std::string::npos);
  // The summary times each quantity a method measured to 1e-2 ... 1e-5: frequencies always, the
  // statics where any run has a deflection error against its limit.
  BOOST_TEST(text.find("| 0.001 % [s] |") != std::string::npos);
  bool statics = false;
  for (const auto& r : all[0].runs) statics = statics || std::isfinite(r.disc_error(Quantity::Deflections));
  BOOST_TEST((text.find("Static deflections at the probes") != std::string::npos) == statics);
}

// A folder that cannot be written is an error naming the path and the reason, never "written".
BOOST_AUTO_TEST_CASE(unwritable_output_is_an_error_with_the_path) {
  const modalbench_test::TempDir tmp("modalbench_test_unwritable");
  const auto blocker = tmp / "a_file";
  write_text_file(blocker.string(), "x");
  try {
    write_report({}, (blocker / "report").string(), ReportOptions{});
    BOOST_ERROR("a report was written below a plain file");
  } catch (const std::runtime_error& e) {
    BOOST_TEST(std::string(e.what()).find(blocker.string()) != std::string::npos, e.what());
  }
  try {
    write_text_file((tmp / "no_such_folder" / "x.csv").string(), "x");
    BOOST_ERROR("a file was written into a missing folder");
  } catch (const std::runtime_error& e) {
    BOOST_TEST(std::string(e.what()).find("No such file or directory") != std::string::npos, e.what());
  }
  // A full disk: /dev/full accepts the open and fails the write.
  if (std::filesystem::exists("/dev/full"))
    BOOST_CHECK_THROW(write_text_file("/dev/full", std::string(1 << 16, 'x')), std::runtime_error);
}
