// Frames on every back-end that models them: rfem's rigid elements within their own error estimate
// of the exact frame on every built-in frame it builds, converging at second order; the others
// refuse with a reason.
#define BOOST_TEST_MODULE frames
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "solve_options.hpp"
#include "solver_tests.hpp"
#include "modalbench/frame.hpp"

using namespace modalbench;
using solver_tests::registry;
using solver_tests::rel;

namespace {

std::vector<Scene> builtin_frames() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(MODALBENCH_SCENES_DIR))
    if (e.path().extension() == ".toml") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::vector<Scene> out;
  for (const auto& f : files)
    if (Scene s = load_scene(f); s.is_frame()) out.push_back(s);
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(rfem_is_within_its_estimate_of_exact_on_every_builtin_frame) {
  const Solver& exact = registry().get("exact");
  const Solver& rfem = registry().get("rfem");
  const std::vector<Scene> frames = builtin_frames();
  BOOST_TEST_REQUIRE(frames.size() >= 6u);
  for (const Scene& sc : frames) {
    BOOST_TEST_CONTEXT(sc.name) {
      const Result ref = exact.solve(sc, {}, {});
      BOOST_TEST_REQUIRE(ref.ok(), ref.summary.message);
      const Result r = rfem.solve_default(sc, {});
      BOOST_TEST((r.summary.status == Status::Success), r.summary.message);
      BOOST_REQUIRE(r.frequencies_rad_s.size() == ref.frequencies_rad_s.size());
      const double estimate = r.frequency_estimate();
      BOOST_TEST(estimate <= sc.request.tolerance);
      for (std::size_t i = 0; i < ref.frequencies_rad_s.size(); ++i)
        BOOST_TEST(rel(r.frequencies_rad_s[i], ref.frequencies_rad_s[i]) <= estimate,
                   "mode " << i + 1 << ": " << r.frequencies_rad_s[i] << " vs exact " << ref.frequencies_rad_s[i]
                           << " (estimate " << estimate << ")");
      // Statics: the displacements at the probes within their estimate (relative to the largest
      // translation), the reactions within it too (relative to the largest reaction force, moments
      // over the longest member).
      BOOST_REQUIRE(r.deflections.size() == ref.deflections.size());
      if (ref.deflections.empty()) continue;
      const double dest = r.extrapolated.deflections_reported ? r.extrapolated.deflection_error
                                                              : r.summary.error_estimate.deflections;
      BOOST_TEST(dest <= sc.request.tolerance);
      double scale = 0;
      for (const Deflection& d : ref.deflections) scale = std::max({scale, std::abs(d.u), std::abs(d.v), std::abs(d.w)});
      for (std::size_t p = 0; p < ref.deflections.size(); ++p) {
        const Deflection &a = r.deflections[p], &b = ref.deflections[p];
        BOOST_TEST(a.probe == b.probe);
        for (auto [x, y] : {std::pair{a.u, b.u}, {a.v, b.v}, {a.w, b.w}})
          BOOST_TEST(std::abs(x - y) <= dest * scale, b.probe << ": " << x << " vs exact " << y);
      }
      // The reactions: within their own two-mesh estimate (Roache's 3 |R_h - R_2h| / (2^2 - 1), the
      // mesh's and its halving's), plus the rounding of the balance (1e-10 of the largest).
      BOOST_REQUIRE(r.reactions.size() == ref.reactions.size());
      Discretization half = Discretization::parse(r.summary.mesh);
      half.counts[0] /= 2;
      const Result h = rfem.solve(sc, half, testing::own_error_study());
      BOOST_REQUIRE(h.reactions.size() == ref.reactions.size());
      double size = 0;
      for (const Reaction& rc : ref.reactions)
        for (std::size_t c = 0; c < 3; ++c) size = std::max({size, std::abs(rc.force[c]), std::abs(rc.moment[c])});
      for (std::size_t i = 0; i < ref.reactions.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
          for (auto [a, b, e] : {std::tuple{r.reactions[i].force[c], h.reactions[i].force[c], ref.reactions[i].force[c]},
                                 {r.reactions[i].moment[c], h.reactions[i].moment[c], ref.reactions[i].moment[c]}})
            BOOST_TEST(std::abs(a - e) <= std::abs(a - b) + 1e-10 * size,
                       ref.reactions[i].support << ": " << a << " vs exact " << e << " (coarser mesh " << b << ")");
    }
  }
}

BOOST_AUTO_TEST_CASE(rfem_frames_converge_at_second_order) {
  // The portal and the L-shaped space frame: errors against exact on meshes 8, 16, 32, 64; the
  // observed order log2(e(h) / e(h/2)) of each of the first four modes tends to 2.
  const Solver& exact = registry().get("exact");
  const Solver& rfem = registry().get("rfem");
  for (const char* name : {"frame_portal.toml", "frame_l_space.toml"}) {
    BOOST_TEST_CONTEXT(name) {
      Scene sc = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + name);
      sc.request.modes = 4;
      const Result ref = exact.solve(sc, {}, {});
      BOOST_TEST_REQUIRE(ref.ok(), ref.summary.message);
      std::vector<std::vector<double>> err;
      for (int n : {8, 16, 32, 64}) {
        const Result r = rfem.solve(sc, Discretization{{n}}, testing::own_error_study());
        BOOST_TEST_REQUIRE(r.frequencies_rad_s.size() == 4u, r.summary.message);
        std::vector<double> e;
        for (std::size_t i = 0; i < 4; ++i) e.push_back(rel(r.frequencies_rad_s[i], ref.frequencies_rad_s[i]));
        err.push_back(e);
      }
      for (std::size_t i = 0; i < 4; ++i) {
        const double order = std::log2(err[2][i] / err[3][i]);
        BOOST_TEST(std::abs(order - 2.0) < 0.1, "mode " << i + 1 << ": observed order " << order);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(the_other_back_ends_refuse_frames_with_a_reason) {
  const Scene sc = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/frame_portal.toml");
  for (const char* name : {"dtfm", "difference_eq"}) {
    const Capability c = registry().get(name).supports(sc);
    BOOST_TEST(!c.any());
    BOOST_TEST(!c.reason.empty());
  }
  const Capability c = registry().get("rfem").supports(sc);
  BOOST_TEST((c.modes && c.statics));
}
