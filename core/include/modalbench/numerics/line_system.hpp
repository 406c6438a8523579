#pragma once
// A one-dimensional Hamiltonian field on [0, 1] cut into segments, assembled into a
// block-tridiagonal dynamic stiffness K(lambda), and its spectrum by the Wittrick-Williams count.
//
// The line is cut into segments short enough that |p| h <= 1 for every wavenumber p of the
// state matrix A(lambda) (so exp(A h) is well conditioned and no segment has a clamped-clamped
// natural frequency below omega: the Wittrick-Williams J0 term vanishes); the segment matrices
// (segment_dynamic_stiffness.hpp) are assembled into K(lambda). End springs (per DOF, [0, inf],
// inf = the DOF is held) are added at xi = 0 and xi = 1; the strain-energy boundary terms are
// [f . delta d] from 0 to 1. Then
//   J(lambda) = number of negative eigenvalues of K(lambda)
// is exactly the number of natural frequencies below sqrt(lambda) (Wittrick & Williams 1971).
//
// Usage:
//   LineSystem sys;  sys.m = 2;  sys.state_matrix = [](double lam) { ... };
//   sys.max_wavenumber = [](double lam) { ... };  sys.left_spring = {inf, 0}; ...
//   LineSpectrum s = lowest_eigenvalues(sys, 6, /*lambda_hint=*/1.0);

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "modalbench/numerics/block_tridiagonal.hpp"
#include "modalbench/numerics/spectrum_slicing.hpp"

namespace modalbench {

/// A line field problem in dimensionless form on [0, 1].
struct LineSystem {
  int m = 0;
  std::function<Eigen::MatrixXd(double lambda)> state_matrix;  ///< A(lambda), 2m x 2m
  /// An upper bound on |p| over the eigenvalues p of A(lambda) (sets the segment length).
  std::function<double(double lambda)> max_wavenumber;
  std::vector<double> left_spring, right_spring;  ///< per DOF, dimensionless, [0, inf]
  std::vector<double> nodes_at;  ///< interior positions in (0, 1) that must be nodes (loads, probes)
};

/// The assembled K(lambda) with its node positions.
struct AssembledLine {
  BlockTridiagonal K;
  std::vector<double> xi;  ///< position of every node
  int node_at(double x) const;  ///< index of the node at x (exact match required)
};
AssembledLine assemble(const LineSystem& sys, double lambda);

/// Number of natural frequencies with omega^2 < lambda (Wittrick-Williams).
int count_below(const LineSystem& sys, double lambda);

/// Eigenvalues below kRigidThreshold * lambda_hint are rigid-body modes (exactly 0).
inline constexpr double kRigidThreshold = 1e-10;

struct LineSpectrum {
  std::vector<double> lambdas;  ///< lowest k values of omega^2, ascending; rigid ones are 0
  int rigid = 0;                ///< how many of them are rigid-body modes
};
/// The lowest k eigenvalues lambda = omega^2 of a line system. `lambda_hint` sets the
/// scale (e.g. the lambda at which the dimensionless frequency is 1).
LineSpectrum lowest_eigenvalues(const LineSystem& sys, int k, double lambda_hint, SliceStats* stats = nullptr);

}  // namespace modalbench
