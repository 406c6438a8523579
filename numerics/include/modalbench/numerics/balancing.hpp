#pragma once
// Parlett-Reinsch balancing: a diagonal similarity by powers of two that gives a matrix's
// rows and columns comparable size. State matrices span many orders of magnitude; exp() and
// eigensolvers lose digits (and a Hamiltonian's (p, -p) pairing) on them unbalanced.

#include <Eigen/Dense>

namespace modalbench {

/// B balanced: same eigenvalues, rows and columns of comparable size.
Eigen::MatrixXd balanced(Eigen::MatrixXd B, int max_sweeps = 50);

/// Balances B in place and returns the scaling d with B_balanced = D^-1 B D, D = diag(d)
/// (d_i powers of two, so the similarity is exact in floating point).
Eigen::VectorXd balance_in_place(Eigen::MatrixXd& B, int max_sweeps);
Eigen::VectorXd balance_in_place(Eigen::MatrixXcd& B, int max_sweeps);

}  // namespace modalbench
