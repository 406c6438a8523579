// Edge and corner reactions of a simply supported Kirchhoff plate (Navier's plate), by Levy
// single series whose strip problems are solved in closed form through influence functions.
//
// Write the deflection as w = sum_n w_n(x) sin(beta_n y), beta_n = n pi / b. Each w_n solves
//   D (w'''' - 2 beta^2 w'' + beta^4 w) = q_n(x),   w = w'' = 0 at x = 0, a,
// with q_n = (2 / b) int_0^b q(x, y) sin(beta_n y) dy. Green's identity for this operator against
// a solution eta of the homogeneous equation gives every end quantity as a load integral
// (Maxwell-Betti for the strip):
//   R(0) = -int q eta_0,  eta_0(0) = 1, eta_0''(0) = nu beta^2, eta_0 = eta_0'' = 0 at a
//     (R(0) = D [w''' - (2 - nu) beta^2 w'](0): the Kirchhoff effective shear the support exerts);
//   w'(0) = -(1 / D) int q chi_0,  chi_0''(0) = 1, chi_0(0) = chi_0(a) = chi_0''(a) = 0;
// and the mirror images at x = a (R(a) = -int q eta_a, w'(a) = (1 / D) int q chi_a). On the basis
// e^{-beta x}, x e^{-beta x}, e^{-beta (a - x)}, (a - x) e^{-beta (a - x)} (no overflow at any n)
// these are closed forms, and so are their integrals over a pressure patch: the cost per term is
// a 4 x 4 solve, whatever n. The Navier double series of the edge shear, by contrast, converges
// like 1/terms.
//
// The edges y = 0, b come from the same strips in the other direction; the corner forces
// 2 D (1 - nu) |w_xy| from w_xy = sum_n beta_n w_n'(x) cos(beta_n y) at the corners, computed by
// both directions (their difference is part of the error estimate).

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "modalbench/exact/plates.hpp"

namespace modalbench::exact {

namespace {

constexpr double pi = std::numbers::pi;

/// A load in the frame of one strip family: along the strip [s1, s2] (s1 == s2: a point force),
/// across it [t1, t2] (t1 == t2: a point), `value` N (point) or Pa (patch).
struct StripLoad {
  double s1 = 0, s2 = 0, t1 = 0, t2 = 0, value = 0;
  bool point = false;
};

/// Four influence functions of one strip (eta_0, eta_a, chi_0, chi_a) on the decaying basis.
class StripInfluence {
 public:
  StripInfluence(double beta, double a, double nu) : beta_(beta), a_(a) {
    const double E = std::exp(-beta * a), c2 = beta * beta * a - 2 * beta;
    Eigen::Matrix4d B;  // rows: f(0), f''(0), f(a), f''(a) of the basis
    B << 1, 0, E, a * E,
        beta * beta, -2 * beta, beta * beta * E, c2 * E,
        E, a * E, 1, 0,
        beta * beta * E, c2 * E, beta * beta, -2 * beta;
    Eigen::Matrix4d rhs = Eigen::Matrix4d::Zero();
    rhs(0, 0) = 1;                  // eta_0
    rhs(1, 0) = nu * beta * beta;
    rhs(2, 1) = 1;                  // eta_a
    rhs(3, 1) = nu * beta * beta;
    rhs(1, 2) = 1;                  // chi_0
    rhs(3, 3) = 1;                  // chi_a
    coef_ = B.fullPivLu().solve(rhs);
  }
  /// The four functions at s.
  Eigen::Vector4d value(double s) const {
    const double l = std::exp(-beta_ * s), r = std::exp(-beta_ * (a_ - s));
    const Eigen::Vector4d basis(l, s * l, r, (a_ - s) * r);
    return coef_.transpose() * basis;
  }
  /// Their integrals over [s1, s2].
  Eigen::Vector4d integral(double s1, double s2) const {
    const Eigen::Vector4d basis(decay(s1, s2), decay_linear(s1, s2), decay(a_ - s2, a_ - s1),
                                decay_linear(a_ - s2, a_ - s1));
    return coef_.transpose() * basis;
  }

 private:
  /// int_u^v e^{-beta t} dt and int_u^v t e^{-beta t} dt, 0 <= u <= v.
  double decay(double u, double v) const { return -std::exp(-beta_ * u) * std::expm1(-beta_ * (v - u)) / beta_; }
  double decay_linear(double u, double v) const {
    const double b2 = beta_ * beta_;
    return std::exp(-beta_ * u) * (u / beta_ + 1 / b2) - std::exp(-beta_ * v) * (v / beta_ + 1 / b2);
  }
  double beta_, a_;
  Eigen::Matrix4d coef_;
};

/// The end quantities of one strip family, summed over n <= N and n <= N / 2.
struct FamilySums {
  // [0]: n <= N, [1]: n <= N / 2. Edge s = 0 and s = a: force and first moment about the edge's
  // middle (int (t - len / 2) R dt); twist w_st at the four corners (s = 0 | a) x (t = 0 | len).
  std::array<std::array<double, 4>, 2> force_moment{};
  std::array<std::array<double, 4>, 2> twist{};
};

FamilySums family_sums(double a, double len, double D, double nu, const std::vector<StripLoad>& loads, int N) {
  FamilySums out;
  for (int n = 1; n <= N; ++n) {
    const double beta = n * pi / len, sign = (n % 2 == 0) ? 1.0 : -1.0;  // cos(n pi)
    const StripInfluence inf(beta, a, nu);
    Eigen::Vector4d acc = Eigen::Vector4d::Zero();  // int q_n f for the four functions
    for (const StripLoad& l : loads) {
      const double across = l.point ? (2 / len) * l.value * std::sin(beta * l.t1)
                                    : (2 / len) * l.value * (std::cos(beta * l.t1) - std::cos(beta * l.t2)) / beta;
      acc += across * (l.point ? inf.value(l.s1) : inf.integral(l.s1, l.s2));
    }
    const double R0 = -acc[0], Ra = -acc[1], slope0 = -acc[2] / D, slopea = acc[3] / D;
    const double total = (1 - sign) / beta, first = -(len / 2) * (1 + sign) / beta;  // int sin, int (t - len/2) sin
    const std::array<double, 4> fm = {R0 * total, R0 * first, Ra * total, Ra * first};
    const std::array<double, 4> tw = {beta * slope0, beta * sign * slope0, beta * slopea, beta * sign * slopea};
    for (int h = 0; h < 2; ++h) {
      if (h == 1 && 2 * n > N) break;
      for (int k = 0; k < 4; ++k) {
        out.force_moment[h][k] += fm[k];
        out.twist[h][k] += tw[k];
      }
    }
  }
  return out;
}

std::vector<StripLoad> along_x(const std::vector<std::array<double, 3>>& forces, const std::vector<PressurePatch>& patches) {
  std::vector<StripLoad> out;
  for (const auto& f : forces) out.push_back({f[0], f[0], f[1], f[1], f[2], true});
  for (const auto& p : patches) out.push_back({p.x1, p.x2, p.y1, p.y2, p.p, false});
  return out;
}

std::vector<StripLoad> transposed(std::vector<StripLoad> loads) {
  for (auto& l : loads) {
    std::swap(l.s1, l.t1);
    std::swap(l.s2, l.t2);
  }
  return loads;
}

}  // namespace

NavierReactions navier_reactions(double a, double b, double D, double nu, const std::vector<std::array<double, 3>>& forces,
                                 const std::vector<PressurePatch>& patches, double tolerance, int max_terms) {
  const std::vector<StripLoad> lx = along_x(forces, patches), ly = transposed(lx);
  double load = 0;
  for (const auto& f : forces) load += std::abs(f[2]);
  for (const auto& p : patches) load += std::abs(p.p) * (p.x2 - p.x1) * (p.y2 - p.y1);
  NavierReactions r;
  for (int N = 64;; N *= 2) {
    const FamilySums fx = family_sums(a, b, D, nu, lx, N), fy = family_sums(b, a, D, nu, ly, N);
    // Corners (0,0), (a,0), (0,b), (a,b): w_xy from the x strips ...
    const std::array<double, 4> tx = {fx.twist[0][0], fx.twist[0][2], fx.twist[0][1], fx.twist[0][3]};
    // ... and from the y strips (their s is y: corners (0,0), (0,b), (a,0), (a,b) in their order).
    const std::array<double, 4> ty = {fy.twist[0][0], fy.twist[0][1], fy.twist[0][2], fy.twist[0][3]};
    const std::array<double, 4> tx_half = {fx.twist[1][0], fx.twist[1][2], fx.twist[1][1], fx.twist[1][3]};
    // The support holds a corner down where the plate would lift it: (0,0) and (a,b) with +w_xy.
    const std::array<double, 4> orient = {1, -1, -1, 1};
    double tail = 0;
    for (int c = 0; c < 4; ++c) {
      r.corner[c] = orient[c] * 2 * D * (1 - nu) * tx[c];
      tail = std::max({tail, 2 * D * (1 - nu) * std::abs(tx[c] - ty[c]), 2 * D * (1 - nu) * std::abs(tx[c] - tx_half[c])});
    }
    // Edges x0, xL (from the x strips) and y0, yB (from the y strips): force and first moment.
    r.edge_force = {fx.force_moment[0][0], fx.force_moment[0][2], fy.force_moment[0][0], fy.force_moment[0][2]};
    r.edge_first_moment = {fx.force_moment[0][1], fx.force_moment[0][3], fy.force_moment[0][1], fy.force_moment[0][3]};
    const std::array<double, 4> half = {fx.force_moment[1][0], fx.force_moment[1][2], fy.force_moment[1][0],
                                        fy.force_moment[1][2]};
    const std::array<double, 4> half_moment = {fx.force_moment[1][1], fx.force_moment[1][3], fy.force_moment[1][1],
                                               fy.force_moment[1][3]};
    const std::array<double, 4> arm = {b, b, a, a};
    for (int e = 0; e < 4; ++e)
      tail = std::max({tail, std::abs(r.edge_force[e] - half[e]),
                       std::abs(r.edge_first_moment[e] - half_moment[e]) / arm[e]});
    r.terms = N;
    r.tail = tail;
    r.tail_relative = load > 0 ? tail / load : 0.0;
    if (r.tail_relative <= 0.1 * tolerance || 2 * N > max_terms) return r;
  }
}

}  // namespace modalbench::exact
