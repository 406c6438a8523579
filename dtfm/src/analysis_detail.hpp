#pragma once
// Internal to the dtfm line analysis: a symmetry class as a scaled line problem, the assembled system.

#include <Eigen/Dense>
#include <vector>

#include "modalbench/dtfm/analysis.hpp"
#include "modalbench/numerics/block_tridiagonal.hpp"

namespace modalbench::dtfm {

/// One symmetry class of the model as a line problem in scaled coordinates: translations
/// divided by a length (so that K's translation and rotation entries are comparable), energy
/// divided by sigma. q = W q_c, f_c = W^T f / sigma.
struct LineAnalysis::ClassLine {
  int index = 0, mc = 0;
  ModeFamily family = ModeFamily::Unknown;
  Eigen::MatrixXd W, Winv;
  Eigen::MatrixXd St, C, Qt, M;
  double sigma = 1;
  struct End {
    Eigen::MatrixXd B;  // mc x mc orthogonal; the first n_free columns are the admissible motions
    int n_free = 0;
    Eigen::MatrixXd K;  // springs on those coordinates
  } ends[2];
  Eigen::MatrixXd family_motions;  // physical, m x r (beams)
  double re0 = -1, im0 = -1;       // wavenumber bounds at lambda = 0 (cached)

  template <class Scalar>
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> state(Scalar lambda) const {
    using Mat = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
    Mat A(2 * mc, 2 * mc);
    A.topLeftCorner(mc, mc) = (-St).template cast<Scalar>();
    A.topRightCorner(mc, mc) = C.template cast<Scalar>();
    A.bottomLeftCorner(mc, mc) = Qt.template cast<Scalar>() - lambda * M.template cast<Scalar>();
    A.bottomRightCorner(mc, mc) = St.transpose().template cast<Scalar>();
    return A;
  }
};

namespace detail {

struct AssemblyInfo {
  int clamped_below = 0;   // sum of the segments' J0
  double log_poles = 0;    // sum of the segments' log |det Tdf|
  double min_pivot_rel = 1;
};

/// Field values (physical) at every node from a class solution d (nodes x mc, end nodes in B coordinates).
template <class Vec>
std::vector<Vec> to_fields(const LineAnalysis::ClassLine& c, const Vec& d, int nn) {
  using Scalar = typename Vec::Scalar;
  std::vector<Vec> q(nn);
  for (int i = 0; i < nn; ++i) {
    Vec dc = d.segment(static_cast<Eigen::Index>(i) * c.mc, c.mc);
    if (i == 0) dc = c.ends[0].B.template cast<Scalar>() * dc;
    if (i == nn - 1) dc = c.ends[1].B.template cast<Scalar>() * dc;
    q[i] = c.W.template cast<Scalar>() * dc;
  }
  return q;
}

}  // namespace detail

struct LineAnalysis::Assembled {
  BlockTridiagonal K;
  detail::AssemblyInfo info;
};

}  // namespace modalbench::dtfm
