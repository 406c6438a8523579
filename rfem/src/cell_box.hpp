#pragma once
// Private to rfem's builders: the axis-aligned cell a rigid element stands for.
#include <Eigen/Geometry>

namespace modalbench::rfem {

inline Eigen::AlignedBox3d box(double x0, double x1, double y0, double y1, double z0, double z1) {
  return Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
}

}  // namespace modalbench::rfem
