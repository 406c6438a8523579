// Critical speeds as a symmetric generalized eigenproblem (rotor.hpp): K x = Omega^2 B x with K
// positive definite and B indefinite (a disc whose polar inertia exceeds its diametral one makes
// J_t - J_p < 0), solved as the largest mu = 1 / Omega^2 of L^-1 P B P^-1 L^-T (K = P^-1 L L' P).
#include "rotor.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Spectra/SymEigsSolver.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace modalbench::rfem::detail {

namespace {

/// x -> L^-1 P B P^-1 L^-T x.
class CongruentOp {
 public:
  using Scalar = double;
  CongruentOp(const Eigen::SimplicialLLT<SpMat>& llt, const SpMat& B) : llt_(llt), B_(B) {}
  Eigen::Index rows() const { return B_.rows(); }
  Eigen::Index cols() const { return B_.rows(); }
  void perform_op(const double* in, double* out) const {
    Eigen::Map<const Eigen::VectorXd> x(in, B_.rows());
    Eigen::Map<Eigen::VectorXd> y(out, B_.rows());
    const Eigen::VectorXd u = llt_.permutationPinv() * Eigen::VectorXd(llt_.matrixU().solve(x));
    const Eigen::VectorXd v = llt_.permutationP() * (B_ * u);
    y = llt_.matrixL().solve(v);
  }

 private:
  const Eigen::SimplicialLLT<SpMat>& llt_;
  const SpMat& B_;
};

/// The `nev` largest mu, descending.
Eigen::VectorXd largest(const CongruentOp& op, Eigen::Index nev) {
  const Eigen::Index n = op.rows();
  if (n <= std::max<Eigen::Index>(60, 2 * nev + 2)) {
    Eigen::MatrixXd A(n, n);
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      e[j] = 1.0;
      op.perform_op(e.data(), A.col(j).data());
      e[j] = 0.0;
    }
    const Eigen::VectorXd all = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (A + A.transpose()), Eigen::EigenvaluesOnly).eigenvalues();
    return all.reverse().head(std::min(nev, n));
  }
  const Eigen::Index ncv = std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * nev + 1, 30));
  Spectra::SymEigsSolver<CongruentOp> eigs(const_cast<CongruentOp&>(op), nev, ncv);
  eigs.init();
  eigs.compute(Spectra::SortRule::LargestAlge, 10000, 1e-12);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw std::runtime_error("rfem rotor: the critical speeds' Lanczos iteration did not converge");
  return eigs.eigenvalues();
}

}  // namespace

std::vector<double> synchronous_speeds(const SpMat& K, const SpMat& B, double top) {
  Eigen::SimplicialLLT<SpMat> llt(K);
  if (llt.info() != Eigen::Success)
    throw std::runtime_error("rfem rotor: the stiffness is not positive definite (a free rotor?): no critical speeds");
  const CongruentOp op(llt, B);
  const Eigen::Index n = K.rows();
  for (Eigen::Index nev = std::min<Eigen::Index>(n - 1, 6);; nev = std::min<Eigen::Index>(n - 1, 2 * nev)) {
    const Eigen::VectorXd mu = largest(op, std::max<Eigen::Index>(nev, 1));
    std::vector<double> speeds;
    for (Eigen::Index i = 0; i < mu.size(); ++i)
      if (mu[i] > 0) speeds.push_back(1.0 / std::sqrt(mu[i]));
    std::sort(speeds.begin(), speeds.end());
    const bool beyond = !speeds.empty() && speeds.back() > top;
    // Done where one lies above the top, or where the operator has no more positive mu.
    if (beyond || static_cast<Eigen::Index>(speeds.size()) < mu.size() || nev >= n - 1) {
      auto above = std::upper_bound(speeds.begin(), speeds.end(), top);
      if (above != speeds.end()) ++above;
      speeds.erase(above, speeds.end());
      return speeds;
    }
  }
}

}  // namespace modalbench::rfem::detail
