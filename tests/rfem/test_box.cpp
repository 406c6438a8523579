// A box of rigid cubes: the six rigid modes of a free box, and a one-cube-thick cantilever
// whose axial and bending frequencies converge to the exact bar and Timoshenko beam as the
// column gets more (and so relatively smaller) cubes.
#define BOOST_TEST_MODULE rfem_box
#include <boost/test/unit_test.hpp>

#include <numbers>

#include "rfem_test_helpers.hpp"

using namespace modalbench;
using namespace modalbench::rfem;
using namespace rfem_test;

namespace {
Material steel() {
  Material m;
  m.E = 2.1e11;
  m.nu = 0.3;
  m.G = m.E / (2 * (1 + m.nu));
  m.rho = 7850;
  m.kappa = 5.0 / 6.0;
  return m;
}
}  // namespace

BOOST_AUTO_TEST_CASE(free_box_has_six_rigid_modes) {
  BoxSpec b;
  b.nx = 3;
  b.ny = 2;
  b.nz = 2;
  b.edge = 0.1;
  b.material = steel();
  Modes md;
  const auto w = frequencies(build_box(b), 10, EigenMethod::Auto, &md);
  for (int i = 0; i < 6; ++i) {
    BOOST_TEST(w[static_cast<std::size_t>(i)] == 0.0);
    BOOST_TEST((md.family[static_cast<std::size_t>(i)] == ModeFamily::Rigid));
  }
  BOOST_TEST(w[6] > 1000.0);
  BOOST_TEST((md.family[6] == ModeFamily::Unknown));  // a 3D body: no beam family is claimed
  BOOST_TEST(md.max_backward_error < 1e-13);
  // The same with the Lanczos path: the rigid modes are deflated, the flexible ones agree.
  Modes ml;
  const auto wl = frequencies(build_box(b), 10, EigenMethod::ShiftInvert, &ml);
  BOOST_TEST(ml.sturm_count >= 10);  // 11 when mode 10 has an equal partner (y-z symmetry)
  BOOST_TEST(ml.method.find("agrees") != std::string::npos);
  for (int i = 6; i < 10; ++i) BOOST_TEST(rel(wl[static_cast<std::size_t>(i)], w[static_cast<std::size_t>(i)]) < 1e-9);
}

BOOST_AUTO_TEST_CASE(cube_column_converges_to_bar_and_beam) {
  const double d = 0.05;
  std::vector<double> e_axial, e_bend;
  for (int n : {8, 16, 32}) {
    BoxSpec b;
    b.nx = n;
    b.edge = d;
    b.material = steel();
    b.clamp_x0 = true;
    const Model m = build_box(b);
    const System sys = assemble(m);
    BOOST_TEST(sys.held == 0);  // held through the half cube: elastic, nothing eliminated
    const auto w = frequencies(m, 12);
    const double L = n * d;
    const Section sec = rectangular_section(d, d);
    const auto& mat = b.material;
    const double bar = 0.5 * std::numbers::pi / L * std::sqrt(mat.E / mat.rho);
    const auto beam = exact::beam_bending_frequencies({mat.E * sec.Iy, mat.kappa * mat.G * sec.A, mat.rho * sec.A,
                                                       mat.rho * sec.Iy, L},
                                                      {inf, inf}, {0, 0}, 1);
    auto nearest = [&](double target) {
      double best = w[0];
      for (double x : w)
        if (std::abs(x - target) < std::abs(best - target)) best = x;
      return best / target - 1;
    };
    e_axial.push_back(nearest(bar));
    e_bend.push_back(nearest(beam.omega_rad_s[0]));
    BOOST_TEST_MESSAGE("n = " << n << ": axial error " << e_axial.back() << ", bending error " << e_bend.back());
  }
  for (std::size_t l = 1; l < 3; ++l) {
    BOOST_TEST(std::abs(e_axial[l]) < std::abs(e_axial[l - 1]));
    BOOST_TEST(std::abs(e_bend[l]) < std::abs(e_bend[l - 1]));
  }
  BOOST_TEST(order(e_axial[1], e_axial[2]) > 1.7);
  BOOST_TEST(order(e_bend[1], e_bend[2]) > 1.7);
}
