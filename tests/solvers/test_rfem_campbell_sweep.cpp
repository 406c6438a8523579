// rfem's two ways to a Campbell diagram in the stationary frame, on the same discrete model: the
// projection (campbell_method = projected, rotor_sweep.cpp) against shift-invert Arnoldi on the
// companion form at every spin (campbell_method = arnoldi, rotor_whirl.cpp). The closed-form
// cases every back-end meets are in test_rotor.cpp.
#define BOOST_TEST_MODULE rfem_campbell_sweep
#include <boost/test/unit_test.hpp>

#include <string>

#include "solver_tests.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

/// rfem's projected sweep against its Arnoldi sweep on the same model: root by root within the
/// sweep's own bound (campbell_solve_error_bound) plus Arnoldi's tolerance, the senses alike.
void projected_against_arnoldi(const Scene& s, int segments, double largest_bound) {
  const Solver& rfem = registry().get("rfem");
  Options o;
  o.estimate_error = false;
  o.backend = {{"campbell_method", "projected"}};
  const Result p = rfem.solve(s, Discretization{{segments}}, o);
  o.backend = {{"campbell_method", "arnoldi"}};
  const Result a = rfem.solve(s, Discretization{{segments}}, o);
  BOOST_TEST_INFO(p.summary.message << " / " << a.summary.message);
  BOOST_TEST_REQUIRE((p.summary.status == Status::Success && a.summary.status == Status::Success));
  BOOST_TEST(p.summary.diagnostic("campbell_arnoldi_spins") == 0);
  const double bound = p.summary.diagnostic("campbell_solve_error_bound");
  BOOST_TEST(bound <= largest_bound);
  BOOST_TEST(p.campbell.note.find("count of whirl frequencies") != std::string::npos);
  BOOST_TEST(a.campbell.note.find("shift-invert Arnoldi") != std::string::npos);
  const std::size_t k = static_cast<std::size_t>(s.request.modes);
  for (std::size_t i = 0; i < s.rotor->spin.size(); ++i) {
    const CampbellPoint &x = p.campbell.points[i], &y = a.campbell.points[i];
    BOOST_TEST_REQUIRE(x.frequencies_rad_s.size() == k);
    BOOST_TEST_REQUIRE(y.frequencies_rad_s.size() == k);
    for (std::size_t j = 0; j < k; ++j) {
      BOOST_TEST_INFO("spin " << x.spin_rad_s << " root " << j);
      BOOST_TEST(rel(x.frequencies_rad_s[j], y.frequencies_rad_s[j]) <= bound + 1e-10);
      if (x.spin_rad_s > 0) BOOST_TEST((x.whirl[j] == y.whirl[j]));
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(rfem_s_projected_sweep_agrees_with_its_arnoldi_sweep_root_by_root) {
  // The stationary frame's projection (campbell_method = projected, auto's choice for few roots:
  // one factorization of K, the projected gyroscopic problem per spin, each root's frequency proven
  // within 1e-9 of a true one by its residual in the K^-1 norm, or within its reported bound (at
  // most 1e-7) where rounding stops the residual falling, and the count at the top spin) against
  // shift-invert Arnoldi on the
  // companion form at every spin (Spectra, 1e-12): the same discrete model, so the two agree to the
  // projection's bound plus Arnoldi's tolerance. Friswell's rotor over 61 spins, including the
  // repeated pairs at spin 0: 10 roots on 200 Timoshenko segments (every bound 1e-9), and 12 roots on
  // 300 Euler-Bernoulli segments, whose residuals stop at 1e-9 to 1e-8 (rounding).
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/rotor_friswell_two_discs.toml");
  s.rotor->spin.clear();
  constexpr double kPi = 3.14159265358979323846;
  for (int i = 0; i <= 60; ++i) s.rotor->spin.push_back(4000.0 * kPi / 30.0 * i / 60.0);
  s.request.modes = 10;
  projected_against_arnoldi(s, 200, 1e-9);
  s.theory = Theory::EulerBernoulli;
  s.request.modes = 12;
  projected_against_arnoldi(s, 300, 1e-7);
}
