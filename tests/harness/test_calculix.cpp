// The optional CalculiX 3D reference on the paper's beam: C3D20R bricks must land near the
// converged 3D bending values of ERRATA 8, with torsion and axial modes labelled as such.
#define BOOST_TEST_MODULE calculix
#include <boost/test/unit_test.hpp>

#include <filesystem>

#include "modalbench/harness/calculix.hpp"
#include "temp_dir.hpp"

using namespace modalbench;

namespace {
// Without ccx the 3D reference is skipped by the report (and said so); so is this test.
boost::test_tools::assertion_result ccx_installed(boost::unit_test::test_unit_id) {
  boost::test_tools::assertion_result r(!calculix_version("ccx").empty());
  r.message() << "skipped: ccx not installed (Debian: calculix-ccx)";
  return r;
}
}  // namespace

BOOST_AUTO_TEST_CASE(paper_beam_3d, *boost::unit_test::precondition(ccx_installed)) {
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  const modalbench_test::TempDir dir("modalbench_test_ccx");
  const RunRecord r = calculix_run(s, {20, 4, 4}, "ccx", dir.str());
  BOOST_TEST_REQUIRE(!r.failed(), r.result.summary.message);
  const double converged[] = {6079.75, 13380.23, 21900.37, 30888.10};  // ERRATA 8
  std::vector<double> xz, xy;
  int torsion = 0, axial = 0;
  for (std::size_t i = 0; i < r.result.frequencies_rad_s.size(); ++i) {
    const auto f = r.result.mode_families[i];
    if (f == ModeFamily::BendingXZ) xz.push_back(r.result.frequencies_rad_s[i]);
    if (f == ModeFamily::BendingXY) xy.push_back(r.result.frequencies_rad_s[i]);
    torsion += f == ModeFamily::Torsion;
    axial += f == ModeFamily::Axial;
  }
  BOOST_REQUIRE(xz.size() >= 4u);
  for (int i = 0; i < 4; ++i) BOOST_TEST(std::abs(xz[i] / converged[i] - 1) < 0.005, "mode " << i + 1 << ": " << xz[i]);
  BOOST_TEST(torsion >= 1);
  BOOST_TEST(axial >= 1);
  // A square section: each x-z bending mode has an x-y twin at the same frequency.
  BOOST_REQUIRE(xy.size() >= 4u);
  for (int i = 0; i < 4; ++i) BOOST_TEST(std::abs(xy[i] / xz[i] - 1) < 1e-6, "pair " << i + 1);
}

BOOST_AUTO_TEST_CASE(unsupported_supports_are_refused) {
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/lasecka_elastic_beam.toml");
  BOOST_TEST(!calculix_unsupported_reason(s).empty());
  const modalbench_test::TempDir dir("modalbench_test_ccx");
  const RunRecord r = calculix_run(s, {4, 2, 2}, "ccx", dir.str());
  BOOST_TEST((r.result.summary.status == Status::Unsupported));
}
