// Segment dynamic stiffness, short (one exp) and long (doubling, with J0 and det Tdf), real and
// damped. References: the Hermite beam element (exact for statics), closed forms of the bar.
#define BOOST_TEST_MODULE segment_dynamic_stiffness
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <complex>
#include <numbers>

#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

using namespace modalbench;

namespace {
constexpr double pi = std::numbers::pi;
Eigen::MatrixXd eb_state(double O2) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
  A(0, 1) = 1; A(1, 3) = 1; A(2, 0) = -O2; A(3, 2) = -1;
  return A;
}
Eigen::MatrixXd bar(double k) {
  Eigen::MatrixXd A(2, 2);
  A << 0, 1, -k * k, 0;
  return A;
}
}  // namespace

BOOST_AUTO_TEST_SUITE(segment)

// At omega = 0 the segment dynamic stiffness of an Euler-Bernoulli piece is the Hermite
// element stiffness (EI = 1, length 1): Przemieniecki's matrix, rotations as slopes.
BOOST_AUTO_TEST_CASE(static_euler_bernoulli_is_hermite_element) {
  Eigen::Matrix4d ref;
  ref << 12, 6, -12, 6, 6, 4, -6, 2, -12, -6, 12, -6, 6, 2, -6, 4;
  const Eigen::MatrixXd K = segment_dynamic_stiffness(eb_state(0.0), 1.0);
  BOOST_TEST((K - ref).norm() / ref.norm() < 1e-13);
  // Length h scales the blocks as h^-3, h^-2, h^-1.
  const double h = 0.3;
  const Eigen::MatrixXd Kh = segment_dynamic_stiffness(eb_state(0.0), h);
  BOOST_TEST(std::abs(Kh(0, 0) - 12 / (h * h * h)) < 1e-10 * Kh(0, 0));
  BOOST_TEST(std::abs(Kh(1, 1) - 4 / h) < 1e-12 * Kh(1, 1));
}

BOOST_AUTO_TEST_CASE(dynamic_segment_is_symmetric) {
  for (double O2 : {1.0, 50.0, 2000.0}) {
    double asym = 1.0;
    segment_dynamic_stiffness(eb_state(O2), 0.1, &asym);
    BOOST_TEST(asym < 1e-12);
  }
  // A state matrix that is not Hamiltonian gives a visibly unsymmetric K.
  Eigen::MatrixXd bad = eb_state(10.0);
  bad(0, 0) = 0.7;
  double asym = 0.0;
  segment_dynamic_stiffness(bad, 0.1, &asym);
  BOOST_TEST(asym > 1e-3);
  // A bar: the exact 2x2 dynamic stiffness is (k / sin kh) [[cos kh, -1], [-1, cos kh]].
  const double k = 3.0, h = 0.4;
  Eigen::MatrixXd A(2, 2);
  A << 0, 1, -k * k, 0;
  const Eigen::MatrixXd K = segment_dynamic_stiffness(A, h);
  const double c = k / std::sin(k * h);
  BOOST_TEST(std::abs(K(0, 0) - c * std::cos(k * h)) < 1e-12 * std::abs(c));
  BOOST_TEST(std::abs(K(0, 1) + c) < 1e-12 * std::abs(c));
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(long_segments)

// A bar of length L at wavenumber k: K = k / sin(kL) [[cos kL, -1], [-1, cos kL]], its
// clamped frequencies k_n = n pi / L (J0 = floor(kL / pi)) and Tdf = sin(kL) / k.
BOOST_AUTO_TEST_CASE(doubling_matches_the_closed_form_bar) {
  const double L = 1.3;
  for (double kL : {0.4, 2.0, 4.0, 7.5, 20.3}) {
    const double k = kL / L;
    for (int levels : {0, 3, 8}) {
      if (levels == 0 && kL > 1) continue;  // one exp over the whole span is only meant for short pieces
      const LongSegment s = long_segment_dynamic_stiffness(bar(k), L, levels);
      const double c = k / std::sin(kL);
      BOOST_TEST_CONTEXT("kL " << kL << " levels " << levels) {
        BOOST_TEST(std::abs(s.K(0, 0) - c * std::cos(kL)) < 1e-10 * std::abs(c));
        BOOST_TEST(std::abs(s.K(0, 1) + c) < 1e-10 * std::abs(c));
        BOOST_TEST(std::abs(s.K(1, 1) - c * std::cos(kL)) < 1e-10 * std::abs(c));
        BOOST_TEST(s.clamped_below == static_cast<int>(std::floor(kL / pi)));
        BOOST_TEST(std::abs(s.log_abs_det_tdf - std::log(std::abs(std::sin(kL) / k))) < 1e-9);
      }
    }
  }
}

// Damped: the complex bar (k complex) against the same closed form.
BOOST_AUTO_TEST_CASE(complex_doubling_matches_the_closed_form_bar) {
  const double L = 0.9;
  const std::complex<double> k(6.0, -0.3);
  Eigen::MatrixXcd A(2, 2);
  A << 0.0, 1.0, -k * k, 0.0;
  const LongSegmentC s = long_segment_dynamic_stiffness(A, L, 6);
  const std::complex<double> c = k / std::sin(k * L);
  BOOST_TEST(std::abs(s.K(0, 0) - c * std::cos(k * L)) < 1e-10 * std::abs(c));
  BOOST_TEST(std::abs(s.K(1, 0) + c) < 1e-10 * std::abs(c));
}

BOOST_AUTO_TEST_SUITE_END()
