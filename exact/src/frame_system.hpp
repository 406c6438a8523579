#pragma once
// Private to the exact frames: the members' exact dynamic stiffness assembled at the nodes.
//
// Unknowns. Each node carries its global DOFs (frame.hpp), less those its support holds. A member
// end whose bending moments are released (a hinge) has its own bending rotation(s), in the
// member's axes, as unknowns of their own. A node rotation that nothing turns (every member hinged
// there and no rotational spring or inertia: no stiffness and no mass) is not an unknown; a node
// that some members' torsion turns about their axes keeps only those directions.
//
// Count. With K(lambda) the assembled matrix over the unknowns,
//   J(lambda) = sum over members of J0 (their clamped-clamped frequencies below omega) + s{K(lambda)}
// (Wittrick & Williams 1971) is the number of natural frequencies below omega, exactly; log |det K|
// plus the members' log |det Tdf| has no poles (segment_dynamic_stiffness.hpp).

#include <Eigen/Dense>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "frame_members.hpp"
#include "modalbench/frame.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::exact::detail {

/// The eigenvalues of a symmetric K below 1e-12 of the largest after diagonal scaling (the rigid
/// motions K(0) leaves free).
int scaled_nullity(const Eigen::MatrixXd& K);

class FrameSystem {
 public:
  explicit FrameSystem(const Scene& scene);

  int unknowns() const { return n_; }
  /// K(lambda) over the unknowns (and the nodes of any cut a member needed at this lambda: see
  /// member_pieces), with the members' J0 and log |det Tdf| summed.
  Eigen::MatrixXd assemble(double lambda, int* clamped_below = nullptr, double* log_abs_det_tdf = nullptr) const;
  /// The number of natural frequencies below sqrt(lambda) and the pole-free log |det|.
  std::pair<int, double> count_det(double lambda) const;
  /// The rigid-body motions K(0) leaves free (the nullity of the diagonally scaled K(0), with
  /// eigenvalues below 1e-12 of the largest taken as zero).
  int rigid_motions() const;
  /// A scale of the frame's squared frequencies: min over members of EI / (L^3 (rho A L + the point
  /// masses)), 1/s^2.
  double lambda_scale() const { return lambda_scale_; }

  /// The static solution under every load (gravity included): displacements at the probes, the
  /// members' stress resultants at member probes, the support reactions. Throws
  /// std::runtime_error("mechanism: ...") where the supports leave a rigid motion free.
  struct Statics {
    std::vector<Deflection> probes;
    std::vector<Reaction> reactions;
    double backward_error = 0;
    double imbalance = 0;  ///< |sum of loads and reactions| (forces, moments about the origin) over the sum of their sizes
  };
  Statics statics() const;
  /// Nodes whose rotation is not an unknown in some direction (hinged all round), by id.
  const std::vector<std::string>& undefined_rotations() const { return undefined_rotations_; }

 private:
  /// One unknown's share of a DOF: index and coefficient.
  struct Term {
    int unknown = 0;
    double c = 0;
  };
  using Row = std::vector<Term>;
  /// A piece [a, b] of a member (fractions of its length) and its dynamic stiffness.
  struct Piece {
    double a = 0, b = 1;
    MemberStiffness ms;
  };
  std::vector<Piece> member_pieces(std::size_t member, double lambda) const;
  void number_nodes();
  void number_members();
  /// A member's local DOFs as combinations of unknowns (kMemberDofs rows).
  std::vector<Row> member_rows(std::size_t member) const;
  /// A node's global DOFs (6 rows) as combinations of unknowns.
  const std::vector<Row>& node_rows(int node) const { return node_rows_[static_cast<std::size_t>(node)]; }
  std::vector<std::vector<LocalLineLoad>> local_loads() const;

  const Scene& scene_;
  const Frame& frame_;
  int n_ = 0;
  std::vector<std::vector<Row>> node_rows_;
  std::vector<std::array<std::vector<Term>, 2>> own_rotations_;  ///< per member end: released rotations' unknowns
  std::vector<std::vector<MemberField>> fields_;
  std::vector<std::string> undefined_rotations_;
  double lambda_scale_ = INFINITY;
  std::vector<std::vector<Row>> member_rows_;
  std::vector<std::array<double, 6>> springs_, inertia_;  ///< per node and global DOF (the supports', the masses')
};

}  // namespace modalbench::exact::detail
