// The optional CalculiX 3D reference on the paper's beam: C3D20R bricks must land near the
// converged 3D bending values of docs/sources.md, P8, with torsion and axial modes labelled as such.
#define BOOST_TEST_MODULE calculix
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

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

/// A beam run's bending frequencies per plane and its counts of torsion and axial modes.
struct Families {
  std::vector<double> xz, xy;
  int torsion = 0, axial = 0;
};
Families families(const RunRecord& r) {
  Families out;
  for (std::size_t i = 0; i < r.result.frequencies_rad_s.size(); ++i) {
    const auto f = r.result.mode_families[i];
    if (f == ModeFamily::BendingXZ) out.xz.push_back(r.result.frequencies_rad_s[i]);
    if (f == ModeFamily::BendingXY) out.xy.push_back(r.result.frequencies_rad_s[i]);
    out.torsion += f == ModeFamily::Torsion;
    out.axial += f == ModeFamily::Axial;
  }
  return out;
}
}  // namespace

BOOST_AUTO_TEST_CASE(paper_beam_3d, *boost::unit_test::precondition(ccx_installed)) {
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  const modalbench_test::TempDir dir("modalbench_test_ccx");
  const RunRecord r = calculix_run(s, {20, 4, 4}, "ccx", dir.str());
  BOOST_TEST_REQUIRE(!r.failed(), r.result.summary.message);
  const double converged[] = {6079.75, 13380.23, 21900.37, 30888.10};  // P8
  const auto [xz, xy, torsion, axial] = families(r);
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

// The practitioner's peers. B32R beams on the paper's beam: modes labelled by family, the x-z
// bending ones within 1 % of the Timoshenko beam (ccx uses its own shear treatment, not the
// scene's kappa = 1: a sanity bound, not a convergence check), each with its x-y twin.
BOOST_AUTO_TEST_CASE(b32r_beams_label_their_modes, *boost::unit_test::precondition(ccx_installed)) {
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  BOOST_TEST(calculix_peer_element(s) == "B32R");
  const modalbench_test::TempDir dir("modalbench_test_ccx_b32r");
  const RunRecord r = calculix_peer_run(s, Discretization::parse("64"), "ccx", dir.str());
  BOOST_TEST_REQUIRE(!r.failed(), r.result.summary.message);
  BOOST_TEST(r.backend == "calculix-B32R");
  const double timoshenko[] = {6211.15, 13848.36, 22763.93, 32186.47};  // P1
  const auto [xz, xy, torsion, axial] = families(r);
  BOOST_REQUIRE(xz.size() >= 4u);
  BOOST_REQUIRE(xy.size() >= 4u);
  for (int i = 0; i < 4; ++i) {
    BOOST_TEST(std::abs(xz[i] / timoshenko[i] - 1) < 0.01, "mode " << i + 1 << ": " << xz[i]);
    BOOST_TEST(std::abs(xy[i] / xz[i] - 1) < 1e-6, "pair " << i + 1);
  }
  BOOST_TEST(torsion >= 1);
  BOOST_TEST(axial >= 1);
  // What stays in the work folder (issue 54: a report held 230 MB of ccx's working files): the
  // deck and the modes read, one line per mode, the first the first x-z bending frequency's pair.
  namespace fs = std::filesystem;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir.str())) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  BOOST_TEST((left == std::vector<std::string>{"paper_fixed_beam_B32R_64.inp", "paper_fixed_beam_B32R_64.modes.csv"}),
             left.size() << " files");
  std::ifstream csv(fs::path(dir.str()) / "paper_fixed_beam_B32R_64.modes.csv");
  std::string line;
  long lines = 0;
  while (std::getline(csv, line)) ++lines;
  BOOST_TEST(lines == static_cast<long>(r.result.frequencies_rad_s.size()) + 1);
  // Kept on request.
  const modalbench_test::TempDir kept("modalbench_test_ccx_b32r_kept");
  BOOST_TEST_REQUIRE(!calculix_peer_run(s, Discretization::parse("16"), "ccx", kept.str(), true).failed());
  BOOST_TEST(fs::exists(fs::path(kept.str()) / "paper_fixed_beam_B32R_16.dat"));
  BOOST_TEST(fs::exists(fs::path(kept.str()) / "paper_fixed_beam_B32R_16.frd"));
}

// S8R shells on the paper's plate: no membrane mode among the bending ones (the in-plane
// translations are held), every one labelled plate, within 2 % of the exact Mindlin plate
// (kappa = 5/6: 1682.09, 3003.40, 5178.09, 5321.88 rad/s, exact back-end) -- a sanity bound.
BOOST_AUTO_TEST_CASE(s8r_shells_have_no_spurious_membrane_modes, *boost::unit_test::precondition(ccx_installed)) {
  const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml");
  BOOST_TEST(calculix_peer_element(s) == "S8R");
  const modalbench_test::TempDir dir("modalbench_test_ccx_s8r");
  const RunRecord r = calculix_peer_run(s, Discretization::parse("13x8"), "ccx", dir.str());
  BOOST_TEST_REQUIRE(!r.failed(), r.result.summary.message);
  const double mindlin[] = {1682.09, 3003.40, 5178.09, 5321.88};
  BOOST_REQUIRE(r.result.frequencies_rad_s.size() >= 8u);
  for (std::size_t i = 0; i < 8; ++i) BOOST_TEST((r.result.mode_families[i] == ModeFamily::Plate), "mode " << i + 1);
  for (std::size_t i = 0; i < 4; ++i)
    BOOST_TEST(std::abs(r.result.frequencies_rad_s[i] / mindlin[i] - 1) < 0.02, "mode " << i + 1 << ": " << r.result.frequencies_rad_s[i]);
}
