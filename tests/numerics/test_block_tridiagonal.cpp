// Block-tridiagonal LDL^T (inertia, solve) and the complex block LU, against dense Eigen.
#define BOOST_TEST_MODULE block_tridiagonal
#include <boost/test/unit_test.hpp>

#include <Eigen/Eigenvalues>
#include <complex>
#include <random>

#include "modalbench/numerics/block_tridiagonal.hpp"
#include "modalbench/numerics/complex_block_tridiagonal.hpp"

using namespace modalbench;

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
