// Statics of the regular discrete beam with supports and springs at nodes (superposition of the
// closed forms) and with distributed loads (their exact nodal equivalents); see attachments.hpp.
#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "attachments.hpp"

namespace modalbench::difference_eq {

std::vector<NodalLoad> equivalent_nodal_loads(const RegularBeam& b, const std::vector<ElementLoad>& q) {
  // Hermite shape functions against q linear on the element (q0 at its left node, q1 at its right):
  // a (7 q0 + 3 q1) / 20, a^2 (3 q0 + 2 q1) / 60, a (3 q0 + 7 q1) / 20, -a^2 (2 q0 + 3 q1) / 60.
  const double a = b.a();
  std::vector<NodalLoad> out;
  for (const ElementLoad& l : q)
    for (long e = l.e0; e < l.e1; ++e) {
      const double x = static_cast<double>(e) * a, q0 = l.at(x), q1 = l.at(x + a);
      out.push_back({e, a * (7 * q0 + 3 * q1) / 20, a * a * (3 * q0 + 2 * q1) / 60});
      out.push_back({e + 1, a * (3 * q0 + 7 * q1) / 20, -a * a * (2 * q0 + 3 * q1) / 60});
    }
  return out;
}

namespace {

/// A restrained DOF of an attachment: which one (0: w, 1: slope) and its compliance 1 / k.
struct PointDof {
  std::size_t attachment;
  int dof;
  double compliance;
};

std::vector<PointDof> point_dofs(const std::vector<NodalAttachment>& at) {
  std::vector<PointDof> out;
  for (std::size_t i = 0; i < at.size(); ++i) {
    if (at[i].k > 0) out.push_back({i, 0, std::isinf(at[i].k) ? 0.0 : 1.0 / at[i].k});
    if (at[i].r > 0) out.push_back({i, 1, std::isinf(at[i].r) ? 0.0 : 1.0 / at[i].r});
  }
  return out;
}

double value(const StaticSolution& s, long node, int dof) { return dof == 0 ? s.w[node] : s.slope[node]; }

}  // namespace

StaticSolution solve_static_attached(const RegularBeam& b, const std::vector<NodalLoad>& loads,
                                     const std::vector<NodalAttachment>& at, StaticMethod method,
                                     std::vector<std::array<double, 2>>& reactions) {
  StaticSolution u = solve_static(b, loads, method);
  reactions.assign(at.size(), {0.0, 0.0});
  const std::vector<PointDof> dofs = point_dofs(at);
  if (dofs.empty()) return u;
  const auto n = static_cast<Eigen::Index>(dofs.size());
  // Unit actions at the restrained DOFs and the flexibility G between them.
  std::vector<StaticSolution> unit(dofs.size());
  Eigen::MatrixXd G(n, n);
  Eigen::VectorXd rhs(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const PointDof& d = dofs[static_cast<std::size_t>(j)];
    NodalLoad one{at[d.attachment].node, d.dof == 0 ? 1.0 : 0.0, d.dof == 1 ? 1.0 : 0.0};
    unit[static_cast<std::size_t>(j)] = solve_static(b, {one}, method);
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    const PointDof& d = dofs[static_cast<std::size_t>(i)];
    rhs[i] = -value(u, at[d.attachment].node, d.dof);
    for (Eigen::Index j = 0; j < n; ++j) G(i, j) = value(unit[static_cast<std::size_t>(j)], at[d.attachment].node, d.dof);
    G(i, i) += d.compliance;
  }
  // G + C is symmetric positive definite (a flexibility plus compliances); full pivoting keeps
  // the graded scales of forces and moments.
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
  if (!lu.isInvertible())
    throw std::runtime_error("the point supports' flexibility matrix is singular: two supports restrain the same motion");
  const Eigen::VectorXd X = lu.solve(rhs);
  if (!X.allFinite()) throw std::runtime_error("the point reactions are not finite");
  for (Eigen::Index j = 0; j < n; ++j) {
    const StaticSolution& uj = unit[static_cast<std::size_t>(j)];
    for (std::size_t r = 0; r < u.w.size(); ++r) {
      u.w[r] += X[j] * uj.w[r];
      u.slope[r] += X[j] * uj.slope[r];
    }
    for (std::size_t i = 0; i < 4; ++i) u.reactions[i] += X[j] * uj.reactions[i];  // the ends' share
    const PointDof& d = dofs[static_cast<std::size_t>(j)];
    reactions[d.attachment][static_cast<std::size_t>(d.dof)] = X[j];
  }
  for (const PointDof& d : dofs)  // held exactly
    if (d.compliance == 0.0) (d.dof == 0 ? u.w : u.slope)[static_cast<std::size_t>(at[d.attachment].node)] = 0.0;
  return u;
}

double attached_static_residual(const RegularBeam& b, const std::vector<NodalLoad>& loads,
                                const std::vector<NodalAttachment>& at, const StaticSolution& s,
                                const std::vector<std::array<double, 2>>& reactions) {
  std::vector<NodalLoad> all = loads;
  for (std::size_t i = 0; i < at.size(); ++i) all.push_back({at[i].node, reactions[i][0], reactions[i][1]});
  double res = static_residual(b, all, s);
  // The attachments' laws, relative to the solution's and the reactions' own sizes.
  const double a = b.a();
  double umax = 0, xmax = 0;
  for (std::size_t r = 0; r < s.w.size(); ++r) umax = std::max({umax, std::abs(s.w[r]), std::abs(a * s.slope[r])});
  for (const auto& x : reactions) xmax = std::max({xmax, std::abs(x[0]), std::abs(x[1]) / a});
  for (std::size_t i = 0; i < at.size(); ++i) {
    const double u[2] = {s.w[static_cast<std::size_t>(at[i].node)], s.slope[static_cast<std::size_t>(at[i].node)]};
    const double k[2] = {at[i].k, at[i].r}, scale[2] = {1.0, a};
    for (int d = 0; d < 2; ++d) {
      if (!(k[d] > 0)) continue;
      if (std::isinf(k[d])) {
        if (umax > 0) res = std::max(res, std::abs(u[d]) * scale[d] / umax);
      } else {
        // A reaction at the rounding of the largest one (a spring nothing loads) is not judged by itself.
        const double x = reactions[i][static_cast<std::size_t>(d)], ku = k[d] * u[d];
        const double den = std::abs(x) + std::abs(ku) + 1e-14 * xmax * (d == 0 ? 1.0 : a);
        if (den > 0) res = std::max(res, std::abs(x + ku) / den);
      }
    }
  }
  return res;
}

std::array<double, 2> interpolate_loaded(const RegularBeam& b, const StaticSolution& s, const std::vector<ElementLoad>& q,
                                         double x) {
  std::array<double, 2> v = interpolate(b, s, x);
  const double a = b.a();
  const long e = std::clamp<long>(static_cast<long>(std::floor(x / a)), 0, b.R - 1);
  const double xl = static_cast<double>(e) * a, xi = std::clamp((x - xl) / a, 0.0, 1.0);
  for (const ElementLoad& l : q) {
    if (e < l.e0 || e >= l.e1) continue;
    // The element clamped at both nodes under q0 + (q1 - q0) xi:
    // w = a^4 xi^2 (1 - xi)^2 ((3 - xi) q0 + (2 + xi) q1) / (120 EI).
    const double q0 = l.at(xl), q1 = l.at(xl + a);
    v[0] += std::pow(a, 4) * xi * xi * (1 - xi) * (1 - xi) * ((3 - xi) * q0 + (2 + xi) * q1) / (120 * b.EI);
    v[1] += -std::pow(a, 3) * xi * (xi - 1) *
            (5 * q0 * xi * xi - 15 * q0 * xi + 6 * q0 - 5 * q1 * xi * xi - 5 * q1 * xi + 4 * q1) / (120 * b.EI);
  }
  return v;
}

}  // namespace modalbench::difference_eq
