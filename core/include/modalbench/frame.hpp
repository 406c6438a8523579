#pragma once
// A frame: members joined at nodes, in the x-z plane (physics planar: u, w, theta_y per node) or in
// space (physics spatial: six per node), read from a scene of kind "frame" (docs/scene-format.md,
// "Frames").
//
// Axes. Nodes, supports, masses and loads are in global axes (x, y, z; rotations right-handed about
// them). Each member has its own axes: local x from its first node to its second, local z in the
// plane of local x and the member's `up` vector (default: global z; global x for a member along z),
// local y = z cross x. A member's section has its `height` along local z and its `width` along
// local y, and its stress resultants (N, Qy, Qz, T, My, Mz) are a beam's (result.hpp,
// InternalForces) in the member's axes. In a planar frame every member's local y is +global y or
// -global y, so its in-plane bending is the bending about local y.
//
// Node DOFs, in global axes: ux, uy, uz, rx, ry, rz (dofs indices 0..5); a planar frame carries
// ux, uz, ry (0, 2, 4).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench {

struct FrameNode {
  std::string id;
  std::array<double, 3> x{};  ///< position, m
};

/// A member's axes: rows local x, y, z as unit vectors in global axes.
using MemberAxes = std::array<std::array<double, 3>, 3>;

struct FrameMember {
  std::string id;
  std::array<int, 2> nodes{};  ///< indices into Frame::nodes; local x runs from nodes[0] to nodes[1]
  SectionSpec section;         ///< as a beam's
  double width = 0, height = 0;  ///< the section's extent (Segment's meaning)
  Material material;           ///< the scene's, with the member's overrides
  /// At each end (0: nodes[0], 1: nodes[1]): the bending moments released (a hinge); the member's
  /// bending rotations there are its own, not the node's. Torsion and translations stay joined.
  std::array<bool, 2> released{};
  MemberAxes axes{};           ///< from the nodes and `up` (resolved when read)
  double length = 0;           ///< m
  Section properties() const { return section_properties({length, width, height}, section); }
};

/// Springs at a node, per global DOF (ux, uy, uz, rx, ry, rz), each in [0, inf] (inf: held).
struct FrameSupport {
  int node = 0;
  std::string kind;  ///< free | pinned | clamped | springs
  std::array<double, 6> springs{};
};

/// A point mass at a node, rigidly attached: mass (kg) and rotary inertias about global axes
/// through the node (kg m^2).
struct FrameMass {
  int node = 0;
  double mass = 0, Jx = 0, Jy = 0, Jz = 0;
};

/// A static load at a node, global axes: Fx, Fy, Fz (N), Mx, My, Mz (N m).
struct FrameLoad {
  int node = 0;
  std::array<double, 6> F{};
};

/// A distributed load on a member, per unit length of the member, in global axes (N/m), each
/// component varying linearly from its value at the first node (index 0) to the second (1).
struct FrameLineLoad {
  int member = 0;
  std::array<double, 2> qx{}, qy{}, qz{};
};

/// Where the static response is reported: a node (its displacements), or a member at s in [0, 1]
/// of its length from its first node (displacements and the member's stress resultants).
struct FrameProbe {
  int node = -1;    ///< >= 0: a node probe
  int member = -1;  ///< >= 0: a member probe
  double s = 0;
  std::string label;  ///< "B" or "BC@0.5"
};

struct Frame {
  std::vector<FrameNode> nodes;
  std::vector<FrameMember> members;
  std::vector<FrameSupport> supports;  ///< one per supported node, in the order written
  std::vector<FrameMass> masses;
  std::vector<FrameLoad> loads;
  std::vector<FrameLineLoad> line_loads;
  std::vector<FrameProbe> probes;
  bool spatial = false;  ///< physics spatial (else planar, in the x-z plane)

  /// The global DOFs a node carries: {0, 2, 4} planar, {0, ..., 5} spatial.
  std::vector<int> node_dofs() const;
  /// A point of a member at s in [0, 1] of its length, global axes, m.
  std::array<double, 3> point_on(const FrameMember& m, double s) const;
  /// The global position of a probe, m.
  std::array<double, 3> probe_point(const FrameProbe& p) const;
  /// Every line load on the members: line_loads and, under gravity g, each member's weight
  /// rho A g per length.
  std::vector<FrameLineLoad> all_line_loads(const std::optional<std::array<double, 3>>& gravity) const;
  /// Every node load: loads and, under gravity, each mass's weight m g at its node.
  std::vector<FrameLoad> all_node_loads(const std::optional<std::array<double, 3>>& gravity) const;
  double total_mass() const;  ///< members' rho A L and the point masses, kg
};

/// A frame probe's static response: its label and point, the displacements v (u, v, w, theta_x,
/// theta_y, theta_z, global axes; a planar frame's v, theta_x, theta_z left 0).
Deflection frame_deflection(const Frame& frame, const FrameProbe& probe, const std::array<double, 6>& v);

/// A member's axes from its end points and `up` (a vector in its local x-z plane; nullopt: global z,
/// or global x for a member along z). Throws std::invalid_argument when up is parallel to the member.
MemberAxes member_axes(const std::array<double, 3>& from, const std::array<double, 3>& to,
                       const std::optional<std::array<double, 3>>& up);

}  // namespace modalbench
