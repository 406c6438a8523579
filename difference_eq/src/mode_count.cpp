// Mode-count ingredients: inertia of small symmetric matrices, the closed-form pinned-pinned count and estimate.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "chain.hpp"

namespace modalbench::difference_eq::detail {

int negative_eigenvalues(const Eigen::MatrixXd& A) {
  const Eigen::Index n = A.rows();
  if (n == 0) return 0;
  // Congruence with s_i = 1/sqrt(max_j |A_ij|) keeps the inertia and bounds every entry by 1
  // (|A_ij| <= min(r_i, r_j)); scaling by the diagonal alone fails when a diagonal entry
  // passes through zero.
  Eigen::VectorXd s(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double r = A.row(i).cwiseAbs().maxCoeff();
    s[i] = r > 0 ? 1.0 / std::sqrt(r) : 1.0;
  }
  const Eigen::MatrixXd As = s.asDiagonal() * A * s.asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(As, Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) throw std::runtime_error("difference_eq: small eigenproblem failed");
  int neg = 0;
  for (Eigen::Index i = 0; i < n; ++i) neg += es.eigenvalues()[i] < 0.0;
  return neg;
}

long pinned_pinned_count(long R, const MassCoeffs& m, double Om) {
  const double A = 48.0 + Om * (24.0 * m.m22_1 - 4.0 * m.m11_1 + 24.0 * m.gm) +
                   Om * Om * (m.m11_1 * m.m22_1 + m.gm * m.gm);
  const double B = Om * (24.0 * m.m22_0 - 12.0 * m.m11_1 - 4.0 * m.m11_0 + 48.0 * m.gm) +
                   Om * Om * (m.m11_1 * m.m22_0 + m.m11_0 * m.m22_1 + 2.0 * m.gm * m.gm);
  const double C = -Om * m.m11_0 * (12.0 - Om * m.m22_0);
  auto Q = [&](double x) { return (A * x + B) * x + C; };
  auto trace = [&](double x) {
    return (12.0 - Om * (m.m11_0 + m.m22_0)) + x * (-20.0 - Om * (m.m11_1 + m.m22_1));
  };
  auto theta_of = [](double x) { return 2.0 * std::asin(std::min(1.0, std::sqrt(std::max(0.0, -0.5 * x)))); };
  std::vector<double> th = {0.0, pi};
  const double disc = B * B - 4.0 * A * C;
  if (disc >= 0) {
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    for (double x : {q / A, q != 0.0 ? C / q : 0.0})
      if (x > -2.0 && x < 0.0) th.push_back(theta_of(x));
  }
  const double tden = 20.0 + Om * (m.m11_1 + m.m22_1);
  if (tden != 0) {
    const double xt = (12.0 - Om * (m.m11_0 + m.m22_0)) / tden;
    if (xt > -2.0 && xt < 0.0) th.push_back(theta_of(xt));
  }
  std::sort(th.begin(), th.end());
  long count = 0;
  const double Rd = static_cast<double>(R);
  for (std::size_t i = 0; i + 1 < th.size(); ++i) {
    const double a = th[i], b = th[i + 1];
    long klo = std::max<long>(1, static_cast<long>(std::ceil(a * Rd / pi)));
    long khi = std::min<long>(R - 1, static_cast<long>(std::ceil(b * Rd / pi)) - 1);
    if (khi < klo) continue;
    const double tm = 0.5 * (a + b);
    const double sh = std::sin(0.5 * tm);
    const double x = -2.0 * sh * sh;
    const double det = Q(x), tr = trace(x);
    const int neg = det < 0 ? 1 : (tr < 0 ? 2 : 0);
    count += neg * (khi - klo + 1);
  }
  // k = 0 (phi = 1) and k = R (phi = (-1)^r): rotation only.
  if (12.0 - Om * m.m22_0 < 0) ++count;
  if (4.0 - Om * (m.m22_0 - 2.0 * m.m22_1) < 0) ++count;
  return count;
}

double acoustic_estimate(long R, const MassCoeffs& m, long k) {
  const double th = pi * static_cast<double>(k) / static_cast<double>(R);
  const double sh = std::sin(0.5 * th);
  const double x = -2.0 * sh * sh, s2 = -x * (2.0 + x);
  const double k11 = -24.0 * x, k22 = 12.0 + 4.0 * x;
  const double m11 = m.m11_0 + m.m11_1 * x, m22 = m.m22_0 + m.m22_1 * x;
  const double a = m11 * m22 - m.gm * m.gm * s2;
  const double b = -(k11 * m22 + k22 * m11) - 24.0 * m.gm * s2;
  const double c = 48.0 * x * x;
  if (a == 0.0) return -c / b;
  const double d = std::sqrt(std::max(0.0, b * b - 4.0 * a * c));
  return 2.0 * c / (-b + d);
}

}  // namespace modalbench::difference_eq::detail
