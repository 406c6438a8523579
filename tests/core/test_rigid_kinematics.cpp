// Attachment kinematics: rigid motions cost no energy; a beam SDE reproduces the rfem
// bending stiffness EI/Delta for a relative rotation and shear for a relative translation.
#define BOOST_TEST_MODULE rigid_kinematics
#include <boost/test/unit_test.hpp>

#include "modalbench/rigid_kinematics.hpp"

using namespace modalbench;

BOOST_AUTO_TEST_CASE(rigid_motion_is_free_of_energy) {
  const Eigen::Vector3d ca(0, 0, 0), cb(1.0, 0.2, -0.1), P(0.5, 0.3, 0.05);
  Vector6d k;
  k << 1e3, 2e3, 3e3, 4e3, 5e3, 6e3;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Matrix12d K = sde_stiffness(P - ca, P - cb, R, k);
  BOOST_TEST((K - K.transpose()).norm() < 1e-12 * K.norm());
  // A small rigid motion of the whole pair: translation t and rotation w about the origin.
  const Eigen::Vector3d t(0.1, -0.2, 0.3), w(0.01, 0.02, -0.03);
  // Fixed-size segments (the comma initializer's run-time-sized blocks draw a false
  // -Warray-bounds from GCC 12 under AVX: a 4-wide load it never executes on a 3-vector).
  Eigen::Matrix<double, 12, 1> q;
  q.segment<3>(0) = t + w.cross(ca);
  q.segment<3>(3) = w;
  q.segment<3>(6) = t + w.cross(cb);
  q.segment<3>(9) = w;
  BOOST_TEST((K * q).norm() < 1e-10 * K.norm() * q.norm());
  Eigen::SelfAdjointEigenSolver<Matrix12d> es(K);
  BOOST_TEST(es.eigenvalues().minCoeff() > -1e-9 * K.norm());
}

BOOST_AUTO_TEST_CASE(beam_segment_stiffness) {
  // Two bodies at x = 0 and x = d joined at the midpoint P by a spring k3 along z and a
  // rotational spring k5 about y (the rfem beam's shear and bending springs). Rotate body b
  // by th about y: P on b (r_b = (-d/2, 0, 0)) moves by theta x r_b = (0, 0, th d/2), so the
  // springs store k5 th^2 / 2 + k3 (th d/2)^2 / 2.
  const double d = 0.4, th = 1e-3;
  Vector6d k = Vector6d::Zero();
  k[2] = 7.0;
  k[4] = 11.0;
  const Matrix12d K = sde_stiffness(Eigen::Vector3d(d / 2, 0, 0), Eigen::Vector3d(-d / 2, 0, 0),
                                    Eigen::Matrix3d::Identity(), k);
  const Eigen::MatrixXd Kr = restrict_dofs(K, dofs::kBendingXZ);  // [w_a, th_a, w_b, th_b]
  BOOST_TEST(Kr.rows() == 4);
  const Eigen::Vector4d q(0, 0, 0, th);
  const double energy = 0.5 * q.dot(Kr * q);
  const double expected = 0.5 * (11.0 * th * th + 7.0 * std::pow(th * d / 2, 2));
  BOOST_TEST(std::abs(energy - expected) < 1e-12 * expected);
}
