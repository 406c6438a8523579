// The line_dsm extensions dtfm relies on (core/line_dsm.hpp): long segments by doubling (with
// their Wittrick-Williams J0 and det Tdf), the determinant-polished slicer, and the complex
// (damped) path. References: closed forms of the bar and dense linear algebra.
#define BOOST_TEST_MODULE dtfm_line_dsm
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>

#include "modalbench/line_dsm.hpp"

using namespace modalbench;

namespace {
constexpr double pi = std::numbers::pi;
Eigen::MatrixXd bar(double k) {
  Eigen::MatrixXd A(2, 2);
  A << 0, 1, -k * k, 0;
  return A;
}
}  // namespace

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

BOOST_AUTO_TEST_SUITE(polished_slicing)

// A manufactured characteristic function with known roots (one double): the polished slicer
// returns every root to the tolerance, the double one twice, and uses few evaluations per root.
BOOST_AUTO_TEST_CASE(roots_of_a_manufactured_determinant) {
  const std::vector<double> roots = {0.7, 1.9, 2.05, 3.3, 3.3, 5.0, 8.25};
  long calls = 0;
  auto eval = [&](double lam) {
    ++calls;
    CountDet cd;
    for (double r : roots) {
      cd.count += r < lam;
      cd.log_abs_det += std::log(std::abs(lam - r));
    }
    cd.log_abs_det += 0.3 * lam;  // a smooth positive factor
    return cd;
  };
  SliceStats st;
  const auto got = slice_interval_polished(eval, 0.0, 9.0, 1e-12, 1e-14, &st);
  BOOST_REQUIRE(got.size() == roots.size());
  for (std::size_t i = 0; i < roots.size(); ++i) BOOST_TEST(std::abs(got[i] - roots[i]) < 1e-10 * roots[i]);
  BOOST_TEST(st.count_evaluations == calls);
  BOOST_TEST(calls < 25 * static_cast<long>(roots.size()));
}

BOOST_AUTO_TEST_CASE(non_monotonic_count_is_an_error) {
  int n = 0;
  auto bad = [&](double lam) {
    CountDet cd;
    cd.count = lam <= 0 ? 0 : ((++n % 2) ? 3 : 1);
    cd.log_abs_det = 0.0;
    return cd;
  };
  BOOST_CHECK_THROW(slice_interval_polished(bad, 0.0, 1.0, 1e-12, 1e-14), std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(complex_solve)

// Complex symmetric block-tridiagonal solve against a dense LU (random blocks, held DOFs).
BOOST_AUTO_TEST_CASE(matches_dense) {
  std::mt19937 gen(11);
  std::normal_distribution<double> N(0.0, 1.0);
  const int nodes = 7, m = 3;
  ComplexBlockTridiagonal K(nodes, m);
  for (int i = 0; i + 1 < nodes; ++i) {
    Eigen::MatrixXcd S(2 * m, 2 * m);
    for (int r = 0; r < 2 * m; ++r)
      for (int c = 0; c < 2 * m; ++c) S(r, c) = {N(gen), N(gen)};
    K.add_segment(i, S + S.transpose());
  }
  K.hold(0, 0);
  K.hold(nodes - 1, 2);
  const Eigen::MatrixXcd D = K.dense_free();
  Eigen::VectorXcd f = Eigen::VectorXcd::Zero(nodes * m), ff(D.rows());
  for (int i = 0, j = 0; i < nodes * m; ++i) {
    if (K.held(i / m, i % m)) continue;
    f[i] = {N(gen), N(gen)};
    ff[j++] = f[i];
  }
  const Eigen::VectorXcd d = K.solve(f);
  const Eigen::VectorXcd ref = D.fullPivLu().solve(ff);
  Eigen::VectorXcd df(D.rows());
  for (int i = 0, j = 0; i < nodes * m; ++i)
    if (!K.held(i / m, i % m)) df[j++] = d[i];
  BOOST_TEST((df - ref).norm() < 1e-10 * ref.norm());
  BOOST_TEST(std::abs(d[0]) == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()
