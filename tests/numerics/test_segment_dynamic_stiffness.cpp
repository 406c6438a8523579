// Segment dynamic stiffness, short (one exp) and long (doubling, with J0 and det Tdf), real and
// damped. References: the Hermite beam element (exact for statics), closed forms of the bar.
#define BOOST_TEST_MODULE segment_dynamic_stiffness
#include <boost/test/unit_test.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <cstdlib>
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
/// A Hamiltonian state matrix of m fields that is symmetric end for end under the signs p:
/// A11 couples fields of opposite sign, A12 and A21 (symmetric) fields of equal sign.
Eigen::MatrixXd reflected_state(const Eigen::VectorXd& p, double lambda, unsigned seed) {
  const Eigen::Index m = p.size();
  std::srand(seed);
  Eigen::MatrixXd A11 = Eigen::MatrixXd::Random(m, m), G = Eigen::MatrixXd::Random(m, m),
                  K = Eigen::MatrixXd::Random(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j) {
      if (p[i] * p[j] > 0) A11(i, j) = 0;
      else G(i, j) = K(i, j) = 0;
    }
  // A12 = C^-1 (positive definite: the field's compliance), A21 = stiffness - lambda mass.
  Eigen::MatrixXd A12 = G * G.transpose() + Eigen::MatrixXd::Identity(m, m);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j < m; ++j)
      if (p[i] * p[j] < 0) A12(i, j) = 0;
  const Eigen::MatrixXd A21 = 0.5 * (K + K.transpose()) - lambda * Eigen::MatrixXd::Identity(m, m);
  Eigen::MatrixXd A(2 * m, 2 * m);
  A << A11, A12, A21, -A11.transpose();
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

BOOST_AUTO_TEST_SUITE(reflection)

// The wavenumbers from the half-size block of A^2 against the eigenvalues of the whole state
// (Eigen's EigenSolver): the same set, each +-p pair, to rounding of the largest.
BOOST_AUTO_TEST_CASE(wavenumbers_from_the_half_size_block) {
  Eigen::VectorXd p(9);
  p << 1, -1, -1, 1, 1, -1, 1, 1, -1;
  for (double lambda : {0.5, 40.0}) {
    const Eigen::MatrixXd A = reflected_state(p, lambda, 11);
    const Eigen::VectorXcd got = state_wavenumbers(A);
    const Eigen::VectorXcd ref = Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
    BOOST_REQUIRE(got.size() == ref.size());
    const double scale = ref.cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < ref.size(); ++i) {
      double nearest = std::numeric_limits<double>::infinity();
      for (Eigen::Index j = 0; j < got.size(); ++j) nearest = std::min(nearest, std::abs(got[j] - ref[i]));
      BOOST_TEST(nearest < 1e-10 * scale, "lambda " << lambda << ", wavenumber " << ref[i]);
    }
  }
}


// An Euler-Bernoulli span's fields: w is even end for end, w' odd. A field coupled to its own
// derivative (A11 diagonal) has no such parity.
BOOST_AUTO_TEST_CASE(signs_of_the_euler_bernoulli_fields) {
  const auto p = reflection_signs(eb_state(30.0));
  BOOST_REQUIRE(p.has_value());
  BOOST_TEST((*p)[0] == 1.0);
  BOOST_TEST((*p)[1] == -1.0);
  Eigen::MatrixXd bad = eb_state(10.0);
  bad(0, 0) = 0.7;
  BOOST_TEST(!reflection_signs(bad).has_value());
  // An odd cycle: fields 0, 1 and 2 coupled pairwise through A11 (each pair of opposite parity).
  Eigen::MatrixXd odd = Eigen::MatrixXd::Zero(6, 6);
  odd(0, 1) = odd(0, 2) = odd(1, 2) = 1.0;
  BOOST_TEST(!reflection_signs(odd).has_value());
}

// The structured way (half-size Pade polynomials, half the doubling work) against the general
// one (Eigen's exponential of the whole state, doubling both ends), on a state of 9 fields with
// mixed parities, below and above clamped frequencies of the pieces: the same K to rounding
// (relative to the condensations' condition), the same J0 and log |det Tdf|.
BOOST_AUTO_TEST_CASE(structured_and_general_ways_agree) {
  Eigen::VectorXd p(9);
  p << 1, -1, -1, 1, 1, -1, 1, 1, -1;
  for (double lambda : {0.0, 3.0, 40.0, 400.0})
    for (int levels : {0, 2, 6}) {
      const Eigen::MatrixXd A = reflected_state(p, lambda, 7);
      BOOST_REQUIRE(reflection_signs(A).has_value());
      const double h = 0.2 * std::ldexp(1.0, levels);
      const LongSegment a = long_segment_dynamic_stiffness(A, h, levels, EndReflection::Use);
      const LongSegment b = long_segment_dynamic_stiffness(A, h, levels, EndReflection::Ignore);
      BOOST_TEST_CONTEXT("lambda " << lambda << " levels " << levels) {
        // Two roundings of a chain of condensations differ by eps times its condition: a few eps
        // per level over 1 / min_pivot_rel (seen: 3e-16 to 1.4e-14 times it, the most with FMA
        // kernels, 6 levels at a pivot ratio of 1.4e-3).
        const double tol = 64 * std::numeric_limits<double>::epsilon() * (levels + 1) / b.min_pivot_rel;
        BOOST_TEST(std::abs(a.min_pivot_rel - b.min_pivot_rel) < 1e-10 * b.min_pivot_rel);
        BOOST_TEST((a.K - b.K).norm() < tol * b.K.norm());
        BOOST_TEST(a.clamped_below == b.clamped_below);
        BOOST_TEST(std::abs(a.log_abs_det_tdf - b.log_abs_det_tdf) < 1e-10 * (1 + std::abs(b.log_abs_det_tdf)));
        // The reflection itself: K22 = P K11 P, K21 = P K12 P (by construction on the structured
        // way; to rounding on the general one).
        const Eigen::MatrixXd P = p.asDiagonal();
        const Eigen::Index m = p.size();
        BOOST_TEST((b.K.bottomRightCorner(m, m) - P * b.K.topLeftCorner(m, m) * P).norm() < 1e-12 * b.K.norm());
        BOOST_TEST((b.K.bottomLeftCorner(m, m) - P * b.K.topRightCorner(m, m) * P).norm() < 1e-12 * b.K.norm());
      }
      // Damped: the complex state (lambda with a loss factor) the same way.
      Eigen::MatrixXcd Ac = reflected_state(p, 0.0, 7).cast<std::complex<double>>();
      Ac.bottomLeftCorner(p.size(), p.size()).diagonal().array() -= std::complex<double>(lambda, -0.02 * lambda);
      const LongSegmentC ac = long_segment_dynamic_stiffness(Ac, h, levels, EndReflection::Use);
      const LongSegmentC bc = long_segment_dynamic_stiffness(Ac, h, levels, EndReflection::Ignore);
      BOOST_TEST((ac.K - bc.K).norm() <
                     64 * std::numeric_limits<double>::epsilon() * (levels + 1) / bc.min_pivot_rel * bc.K.norm(),
                 "complex, lambda " << lambda << " levels " << levels);
    }
}


// One exponential (no doubling) over pieces whose 1-norm selects each Pade degree (3, 5, 7, 9,
// and 13 with and without squarings): the structured way against Eigen's exponential.
BOOST_AUTO_TEST_CASE(every_pade_degree) {
  Eigen::VectorXd p(9);
  p << 1, -1, -1, 1, 1, -1, 1, 1, -1;
  const Eigen::MatrixXd A = reflected_state(p, 3.0, 5);
  for (double h : {1e-3, 1e-2, 5e-2, 0.15, 0.3, 0.6, 2.0}) {
    const LongSegment a = long_segment_dynamic_stiffness(A, h, 0, EndReflection::Use);
    const LongSegment b = long_segment_dynamic_stiffness(A, h, 0, EndReflection::Ignore);
    BOOST_TEST((a.K - b.K).norm() < 1e-13 * b.K.norm(), "h " << h);
    BOOST_TEST(std::abs(a.log_abs_det_tdf - b.log_abs_det_tdf) < 1e-12 * (1 + std::abs(b.log_abs_det_tdf)), "h " << h);
  }
}

BOOST_AUTO_TEST_SUITE_END()
