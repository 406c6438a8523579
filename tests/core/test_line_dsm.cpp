// The shared dynamic-stiffness engine: segment matrices, block LDL^T inertia and solve,
// spectrum slicing. References: the Hermite beam element (exact for statics), dense Eigen.
#define BOOST_TEST_MODULE line_dsm
#include <boost/test/unit_test.hpp>

#include <Eigen/Eigenvalues>
#include <random>

#include "modalbench/line_dsm.hpp"

using namespace modalbench;

namespace {
Eigen::MatrixXd eb_state(double O2) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
  A(0, 1) = 1; A(1, 3) = 1; A(2, 0) = -O2; A(3, 2) = -1;
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

BOOST_AUTO_TEST_SUITE(block_tridiagonal)

BOOST_AUTO_TEST_CASE(inertia_and_solve_match_dense) {
  std::mt19937 gen(7);
  std::normal_distribution<double> N(0.0, 1.0);
  const int nodes = 9, m = 3;
  BlockTridiagonal K(nodes, m);
  for (int i = 0; i + 1 < nodes; ++i) {
    Eigen::MatrixXd S(2 * m, 2 * m);
    for (int r = 0; r < 2 * m; ++r)
      for (int c = 0; c < 2 * m; ++c) S(r, c) = N(gen);
    K.add_segment(i, S + S.transpose());
  }
  K.hold(0, 1);
  K.hold(nodes - 1, 2);
  const Eigen::MatrixXd D = K.dense_free();
  BOOST_TEST(D.rows() == nodes * m - 2);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(D);
  int neg = 0;
  for (int i = 0; i < D.rows(); ++i) neg += es.eigenvalues()[i] < 0;
  BOOST_TEST(K.inertia().negative == neg);

  Eigen::VectorXd f = Eigen::VectorXd::Zero(nodes * m), f_free(D.rows());
  for (int i = 0, j = 0; i < nodes * m; ++i) {
    if (K.held(i / m, i % m)) continue;
    f[i] = N(gen);
    f_free[j++] = f[i];
  }
  const Eigen::VectorXd d = K.solve(f);
  const Eigen::VectorXd d_ref = D.fullPivLu().solve(f_free);
  Eigen::VectorXd d_free(D.rows());
  for (int i = 0, j = 0; i < nodes * m; ++i)
    if (!K.held(i / m, i % m)) d_free[j++] = d[i];
  BOOST_TEST((d_free - d_ref).norm() / d_ref.norm() < 1e-10);
  BOOST_TEST(d[1] == 0.0);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(slicing)

// A manufactured spectrum with a double and a triple eigenvalue: slicing returns each with
// its multiplicity, and values to the requested tolerance.
BOOST_AUTO_TEST_CASE(repeated_eigenvalues_keep_multiplicity) {
  const std::vector<double> spectrum = {0.5, 2.0, 2.0, 3.25, 7.0, 7.0, 7.0, 11.0};
  auto count = [&](double lam) {
    int n = 0;
    for (double s : spectrum) n += s < lam;
    return n;
  };
  SliceStats st;
  const auto got = slice_spectrum(count, 7, 0.0, 1.0, 1e-13, &st);
  BOOST_TEST(got.size() == 7u);
  for (std::size_t i = 0; i < got.size(); ++i) BOOST_TEST(std::abs(got[i] - spectrum[i]) < 1e-11);
  BOOST_TEST(st.count_evaluations > 0);
}

BOOST_AUTO_TEST_CASE(non_monotonic_count_is_an_error) {
  int calls = 0;
  auto bad = [&](double lam) { return lam <= 0 ? 0 : ((++calls % 2) ? 3 : 1); };
  BOOST_CHECK_THROW(slice_spectrum(bad, 2, 0.0, 1.0), std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()
