#pragma once
// Internal to the dtfm prism model: the operator assembly shared by the beam and plate builders.

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "modalbench/numerics/checked_inverse.hpp"
#include "modalbench/dtfm/prism_model.hpp"
#include "modalbench/rigid_kinematics.hpp"

namespace modalbench::dtfm::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
using dofs::Rx;
using dofs::Ry;
using dofs::Rz;
using dofs::Ux;
using dofs::Uy;
using dofs::Uz;

/// Collects the operator over the active fields; matrices over two prisms use the 6-slot
/// (u, v, w, theta_x, theta_y, theta_z) layout of rigid_kinematics and are scattered here.
struct Assembly {
  PrismModel& mdl;
  std::vector<std::array<int, 6>> index;  // per prism and slot: field index or -1

  explicit Assembly(PrismModel& m) : mdl(m) {}

  void add_prism(const PrismGeometry& g, const std::vector<int>& active) {
    std::array<int, 6> idx;
    idx.fill(-1);
    const int p = static_cast<int>(mdl.prisms.size());
    for (int d : active) {
      idx[d] = static_cast<int>(mdl.field_prism.size());
      mdl.field_prism.push_back(p);
      mdl.field_dof.push_back(d);
    }
    index.push_back(idx);
    mdl.prisms.push_back(g);
  }

  Eigen::MatrixXd P;       // stiffness of the deformable strains (rows/columns: strain of field k)
  std::vector<char> rigid; // strains held at zero (Euler-Bernoulli / Kirchhoff shear)

  void allocate() {
    const int m = static_cast<int>(mdl.field_prism.size());
    mdl.m = m;
    mdl.M = mdl.C = mdl.S = mdl.X = mdl.Q1 = Eigen::MatrixXd::Zero(m, m);
    mdl.section_weights = Eigen::MatrixXd::Zero(m, m);
    P = Eigen::MatrixXd::Zero(m, m);
    rigid.assign(m, 0);
  }

  /// C = P^-1 over the deformable strains, 0 on the rigid ones.
  void finish_compliance() {
    std::vector<int> f;
    for (int k = 0; k < mdl.m; ++k)
      if (!rigid[k]) f.push_back(k);
    Eigen::MatrixXd Pf(f.size(), f.size());
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t j = 0; j < f.size(); ++j) Pf(i, j) = P(f[i], f[j]);
    const Eigen::MatrixXd Cf = checked_symmetric_solve(Pf, Eigen::MatrixXd::Identity(Pf.rows(), Pf.cols()),
                                                       "dtfm: the prism stiffness on its deformable strains");
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t j = 0; j < f.size(); ++j) mdl.C(f[i], f[j]) = 0.5 * (Cf(i, j) + Cf(j, i));
  }

  int at(int prism, int slot) const { return index[prism][slot]; }

  /// x-strains of one prism: e_k = q_k' + S q with S(v, theta_z) = -1, S(w, theta_y) = +1;
  /// `stiffness` per slot (inf: rigid), `mass` per slot.
  void prism_operator(int p, const std::array<double, 6>& stiffness, const std::array<double, 6>& mass) {
    for (int d = 0; d < 6; ++d) {
      const int k = at(p, d);
      if (k < 0) continue;
      if (std::isinf(stiffness[d])) rigid[k] = 1;
      else P(k, k) += stiffness[d];
      mdl.M(k, k) = mass[d];
    }
    if (at(p, Uy) >= 0 && at(p, Rz) >= 0) mdl.S(at(p, Uy), at(p, Rz)) = -1.0;
    if (at(p, Uz) >= 0 && at(p, Ry) >= 0) mdl.S(at(p, Uz), at(p, Ry)) = 1.0;
  }

  /// Adds a 12 x 12 matrix over [prism a slots; prism b slots] to `target` (rows and columns
  /// both fields, or rows = strains of the same slots for X).
  void scatter(Eigen::MatrixXd& target, int a, int b, const Eigen::MatrixXd& K12) {
    int ids[12];
    for (int d = 0; d < 6; ++d) {
      ids[d] = at(a, d);
      ids[6 + d] = at(b, d);
    }
    for (int i = 0; i < 12; ++i) {
      if (ids[i] < 0) continue;
      for (int j = 0; j < 12; ++j)
        if (ids[j] >= 0) target(ids[i], ids[j]) += K12(i, j);
    }
  }
};

// End conditions (prism_ends.cpp).
EndCondition make_end(const Eigen::MatrixXd& T, const std::vector<double>& k, bool hold_rest, int m,
                      std::string text);

// Symmetry classes (prism_symmetry.cpp).
void build_classes(PrismModel& mdl, const std::vector<ModeFamily>& families_by_class,
                   const std::vector<std::vector<int>>& family_rigid_columns);
bool reflections_commute(const PrismModel& mdl);

// The builders (prism_beam.cpp, prism_plate.cpp).
PrismModel build_beam(const Scene& s, int ny_req, int nz, const ModelOptions& opt);
PrismModel build_plate(const Scene& s, int n, const ModelOptions& opt);

// Steps, supports between the ends and point masses of beams (prism_points.cpp).
/// The scene as a uniform beam of one piece's section and material, without points.
Scene piece_scene(const Scene& s, const Segment& piece);
/// The operators of a stepped beam's pieces after the first (mdl built from the first).
void add_steps(PrismModel& mdl, const Scene& s, int ny, int nz, const ModelOptions& opt);
/// The scene's supports between the ends and point masses (those at an end into the end).
void add_points(PrismModel& mdl, const Scene& s);
/// A whirl line's discs (after add_points): each mass's polar inertia Jx on the section's theta_y
/// there (EndCondition::gyro).
void add_disc_gyro(PrismModel& mdl, const Scene& s);

}  // namespace modalbench::dtfm::detail
