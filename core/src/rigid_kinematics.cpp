#include "modalbench/rigid_kinematics.hpp"

#include <stdexcept>

namespace modalbench {

Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d S;
  S << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return S;
}

Matrix6d attachment(const Eigen::Vector3d& r) {
  Matrix6d D = Matrix6d::Identity();
  D.topRightCorner<3, 3>() = -skew(r);
  return D;
}

Vector6d attached_motion(const Eigen::Vector3d& r, const Vector6d& q) {
  Vector6d out;
  out.head<3>() = q.head<3>() + q.tail<3>().cross(r);
  out.tail<3>() = q.tail<3>();
  return out;
}

Vector6d sde_deformation(const Eigen::Vector3d& r_aP, const Vector6d& q_a, const Eigen::Vector3d& r_bP,
                         const Vector6d& q_b, const Eigen::Matrix3d& R) {
  const Vector6d d = attached_motion(r_bP, q_b) - attached_motion(r_aP, q_a);
  Vector6d local;
  local.head<3>() = R.transpose() * d.head<3>();
  local.tail<3>() = R.transpose() * d.tail<3>();
  return local;
}

namespace {
Matrix6d local_stiffness_global(const Eigen::Matrix3d& R, const Vector6d& k) {
  Matrix6d Rb = Matrix6d::Zero();
  Rb.topLeftCorner<3, 3>() = R;
  Rb.bottomRightCorner<3, 3>() = R;
  return Rb * k.asDiagonal() * Rb.transpose();
}
}  // namespace

Matrix12d sde_stiffness(const Eigen::Vector3d& r_aP, const Eigen::Vector3d& r_bP, const Eigen::Matrix3d& R,
                        const Vector6d& k) {
  Eigen::Matrix<double, 6, 12> G;
  G.leftCols<6>() = -attachment(r_aP);
  G.rightCols<6>() = attachment(r_bP);
  return G.transpose() * local_stiffness_global(R, k) * G;
}

Matrix6d sde_to_ground(const Eigen::Vector3d& r_aP, const Eigen::Matrix3d& R, const Vector6d& k) {
  const Matrix6d D = attachment(r_aP);
  return D.transpose() * local_stiffness_global(R, k) * D;
}

Eigen::MatrixXd restrict_dofs(const Eigen::MatrixXd& full, const std::vector<int>& active) {
  if (full.rows() != full.cols() || full.rows() % 6 != 0)
    throw std::invalid_argument("restrict_dofs: expects a square matrix over 6-DOF bodies");
  const Eigen::Index bodies = full.rows() / 6, a = static_cast<Eigen::Index>(active.size());
  std::vector<Eigen::Index> idx;
  for (Eigen::Index b = 0; b < bodies; ++b)
    for (int d : active) idx.push_back(6 * b + d);
  Eigen::MatrixXd out(bodies * a, bodies * a);
  for (std::size_t i = 0; i < idx.size(); ++i)
    for (std::size_t j = 0; j < idx.size(); ++j) out(i, j) = full(idx[i], idx[j]);
  return out;
}

}  // namespace modalbench
