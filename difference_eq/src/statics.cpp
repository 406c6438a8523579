#include "modalbench/difference_eq/statics.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "modalbench/difference_eq/lasecka.hpp"

namespace modalbench::difference_eq {

std::string to_string(StaticMethod m) {
  return m == StaticMethod::PiecewiseCubic ? "piecewise-cubic Green's function" : "eigenfunction expansion";
}

namespace {

// Hermite cubics on [0, 1] (xi, eta = 1 - xi) in forms without cancellation, and d/dxi.
struct Hermite {
  double h[4], dh[4];
  Hermite(double xi, double eta) {
    h[0] = eta * eta * (1.0 + 2.0 * xi);
    h[1] = xi * eta * eta;
    h[2] = xi * xi * (1.0 + 2.0 * eta);
    h[3] = -xi * xi * eta;
    dh[0] = -6.0 * xi * eta;
    dh[1] = eta * (1.0 - 3.0 * xi);
    dh[2] = 6.0 * xi * eta;
    dh[3] = xi * (3.0 * xi - 2.0);
  }
};

// The whole-beam stiffness K_L in dimensionless form (w / L, psi; forces L^2/EI, moments L/EI).
constexpr double kKhat[4][4] = {{12, 6, -12, 6}, {6, 4, -6, 2}, {-12, -6, 12, -6}, {6, 2, -6, 4}};

// Exact determinant of a small integer matrix (entries of K_L are integers: exact in double).
double small_det(const double* A, int n, int stride) {
  if (n == 0) return 1.0;
  if (n == 1) return A[0];
  double sub[16];
  double det = 0;
  for (int c = 0; c < n; ++c) {
    int k = 0;
    for (int i = 1; i < n; ++i)
      for (int j = 0; j < n; ++j)
        if (j != c) sub[k++] = A[i * stride + j];
    const double s = (c % 2 == 0) ? 1.0 : -1.0;
    det += s * A[c] * small_det(sub, n - 1, n - 1);
  }
  return det;
}

// Minors of K_L for every subset S of {w0, psi0, wL, psiL}: det(K_S) and the cofactors
// cof[S][j][i] = (-1)^{pos(j)+pos(i)} det(K_S without row j and column i).
struct MinorTables {
  double det[16];
  double cof[16][4][4];
  MinorTables() {
    for (int S = 0; S < 16; ++S) {
      int idx[4], n = 0;
      for (int i = 0; i < 4; ++i)
        if (S & (1 << i)) idx[n++] = i;
      double A[16];
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) A[i * n + j] = kKhat[idx[i]][idx[j]];
      det[S] = small_det(A, n, n);
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) cof[S][a][b] = 0;
      for (int pj = 0; pj < n; ++pj)
        for (int pi = 0; pi < n; ++pi) {
          double B[16];
          int k = 0;
          for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c)
              if (r != pj && c != pi) B[k++] = A[r * n + c];
          const double s = ((pj + pi) % 2 == 0) ? 1.0 : -1.0;
          cof[S][idx[pj]][idx[pi]] = s * small_det(B, n - 1, n - 1);
        }
    }
  }
};
const MinorTables& minors() {
  static const MinorTables t;
  return t;
}

// Dimensionless springs above this are treated as held (their effect is below 1e-60 relative).
constexpr double kRigidSpring = 1e60;

struct SupportSolution {
  double G[4][4] = {};  // flexibility on the free DOFs, d = G f (dimensionless)
  double Q[4][4] = {};  // the same for q = (w0/L, rho, psi0, psiL) = S d, rho = (wL - w0)/L the
                        // chord rotation, with its own exact polynomial row
  double flexibility = 0, condition = 0;
};

// q = S d: (w0/L, (wL - w0)/L, psi0, psiL).
constexpr int kS[4][4] = {{1, 0, 0, 0}, {-1, 0, 1, 0}, {0, 1, 0, 0}, {0, 0, 0, 1}};

// (K_L + S)^-1 on the free DOFs as ratios of multilinear polynomials in the springs:
//   det(K_F + S_F) = sum_{T subset F} prod_{t in T} k_t det(K_{F\T}),
//   cof_ji(K_F + S_F) = sum_{T subset F\{i,j}} prod_{t in T} k_t cof_ji(K_{F\T})
// (the Taylor expansion of a multilinear function). The monomial coefficients are integer
// minors of K_L, so they and their integer combinations (the rows of S G) are exact: near a
// translation mechanism the huge common part of w0 and wL cancels exactly in the coefficients
// of the chord-rotation row instead of in floating point. Zero springs drop out; held DOFs are not in F.
SupportSolution solve_supports(const double k[4]) {
  const MinorTables& mt = minors();
  SupportSolution s;
  int F = 0;
  for (int i = 0; i < 4; ++i)
    if (!std::isinf(k[i])) F |= 1 << i;
  double prod[16];
  for (int T = 0; T < 16; ++T) {
    prod[T] = 1.0;
    for (int t = 0; t < 4; ++t)
      if (T & (1 << t)) prod[T] *= k[t];
  }
  double den = 0;
  for (int T = F;; T = (T - 1) & F) {
    if (prod[T] != 0.0) den += prod[T] * mt.det[F & ~T];
    if (T == 0) break;
  }
  if (!(den > 0)) throw Mechanism("the supports do not restrain rigid-body motion (singular support system)");
  // Numerator coefficients N[i][j][T].
  double N[4][4][16] = {};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      if (!(F & (1 << i)) || !(F & (1 << j))) continue;
      const int rest = F & ~((1 << i) | (1 << j));
      for (int T = rest;; T = (T - 1) & rest) {
        N[i][j][T] = mt.cof[F & ~T][j][i];
        if (T == 0) break;
      }
    }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double g = 0, q = 0;
      for (int T = 0; T < 16; ++T) {
        if ((T & ~F) != 0 || prod[T] == 0.0) continue;
        double c = 0;
        for (int m = 0; m < 4; ++m) c += kS[i][m] * N[m][j][T];
        g += N[i][j][T] * prod[T];
        q += c * prod[T];
      }
      s.G[i][j] = g / den;
      s.Q[i][j] = q / den;
    }
  // Extreme eigenvalues: the largest of the flexibility G (accurate) and of K_F + S_F.
  int idx[4], n = 0;
  for (int i = 0; i < 4; ++i)
    if (F & (1 << i)) idx[n++] = i;
  if (n > 0) {
    Eigen::MatrixXd G(n, n), M(n, n);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        G(a, b) = 0.5 * (s.G[idx[a]][idx[b]] + s.G[idx[b]][idx[a]]);
        M(a, b) = kKhat[idx[a]][idx[b]] + (a == b ? k[idx[a]] : 0.0);
      }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eg(G, Eigen::EigenvaluesOnly), em(M, Eigen::EigenvaluesOnly);
    if (eg.info() != Eigen::Success || em.info() != Eigen::Success)
      throw std::runtime_error("difference_eq: the 4x4 eigenproblem of the support conditioning did not converge");
    s.flexibility = eg.eigenvalues().maxCoeff();
    s.condition = em.eigenvalues().maxCoeff() * s.flexibility;
  }
  return s;
}

std::string mechanism_message(const RegularBeam& b) {
  const int rigid = rigid_body_modes(b);
  const bool rot = b.r0 > 0 || b.rL > 0;
  std::string what = rigid == 2 ? "rigid translation and rotation are" : (rot ? "rigid translation is" : "rigid rotation is");
  return "mechanism: " + what +
         " not restrained by the end supports (a static solve needs translational springs at both ends, "
         "or a translational and a rotational one)";
}

void check_loads(const RegularBeam& b, const std::vector<NodalLoad>& loads) {
  for (std::size_t i = 0; i < loads.size(); ++i) {
    const auto& l = loads[i];
    if (l.node < 0 || l.node > b.R)
      throw std::invalid_argument("load " + std::to_string(i) + ": node " + std::to_string(l.node) +
                                  " outside 0..R = " + std::to_string(b.R));
    if (!std::isfinite(l.force) || !std::isfinite(l.moment))
      throw std::invalid_argument("load " + std::to_string(i) + ": values must be finite");
  }
}

// Clamped-clamped response by the piecewise-cubic discrete Green's function, and the
// equivalent end loads f_eq = -(its support reactions) = sum of N(s) P, N'(s) C.
void clamped_clamped_cubic(const RegularBeam& b, const std::vector<NodalLoad>& loads, std::vector<double>& w,
                           std::vector<double>& slope, double feq[4]) {
  const long R = b.R;
  const double L = b.L, Rd = static_cast<double>(R);
  const double cf = L * L * L / b.EI, cm = L * L / b.EI;
  std::vector<std::size_t> order(loads.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](auto x, auto y) { return loads[x].node < loads[y].node; });
  w.assign(R + 1, 0.0);
  slope.assign(R + 1, 0.0);
  for (int i = 0; i < 4; ++i) feq[i] = 0;
  // Left branch (xi <= s): w = A2 xi^2 + A3 xi^3; swept from x = L down, loads at or right of r.
  {
    long double A2 = 0, A3 = 0;
    std::size_t q = order.size();
    for (long r = R; r >= 0; --r) {
      while (q > 0 && loads[order[q - 1]].node >= r) {
        const auto& l = loads[order[--q]];
        const double s = static_cast<double>(l.node) / Rd, t = static_cast<double>(R - l.node) / Rd;
        A2 += l.force * cf * (t * t * s / 2.0) + l.moment * cm * (t * (1.0 - 3.0 * s) / 2.0);
        A3 += -l.force * cf * (t * t * (1.0 + 2.0 * s) / 6.0) + l.moment * cm * (s * t);
        const Hermite H(s, t);
        feq[0] += l.force * H.h[0] + l.moment * H.dh[0] / L;
        feq[1] += l.force * L * H.h[1] + l.moment * H.dh[1];
        feq[2] += l.force * H.h[2] + l.moment * H.dh[2] / L;
        feq[3] += l.force * L * H.h[3] + l.moment * H.dh[3];
      }
      const double xi = static_cast<double>(r) / Rd;
      w[r] = static_cast<double>(A2 * xi * xi + A3 * xi * xi * xi);
      slope[r] = static_cast<double>((2.0L * A2 * xi + 3.0L * A3 * xi * xi) / L);
    }
  }
  // Right branch (xi >= s): w = B2 eta^2 + B3 eta^3, eta = 1 - xi; loads strictly left of r.
  {
    long double B2 = 0, B3 = 0;
    std::size_t q = 0;
    for (long r = 0; r <= R; ++r) {
      while (q < order.size() && loads[order[q]].node < r) {
        const auto& l = loads[order[q++]];
        const double s = static_cast<double>(l.node) / Rd, t = static_cast<double>(R - l.node) / Rd;
        B2 += l.force * cf * (s * s * t / 2.0) + l.moment * cm * (s * (2.0 - 3.0 * s) / 2.0);
        B3 += -l.force * cf * (s * s * (1.0 + 2.0 * t) / 6.0) - l.moment * cm * (s * t);
      }
      const double eta = static_cast<double>(R - r) / Rd;
      w[r] += static_cast<double>(B2 * eta * eta + B3 * eta * eta * eta);
      slope[r] -= static_cast<double>((2.0L * B2 * eta + 3.0L * B3 * eta * eta) / L);
    }
  }
}

// Rotation Green's function of the clamped-pinned chain with every w held:
// 2 phi_{r-1} + 8 phi_r + 2 phi_{r+1} = delta_rs (r < R), 2 phi_{R-1} + 4 phi_R = delta_Rs,
// phi_0 = 0. With z = sqrt(3) - 2 (|z| < 1): G = C0 z^|r-s| + alpha z^r + beta z^(R-r).
struct RotationGreen {
  double C0 = 1.0 / (4.0 * std::sqrt(3.0)), z = std::sqrt(3.0) - 2.0;
  long R, s;
  double alpha, beta;
  double zp(long n) const { return std::pow(z, static_cast<double>(n)); }
  RotationGreen(long R_, long s_) : R(R_), s(s_) {
    alpha = -C0 * (zp(s) + zp(2 * R - s)) / (1.0 + zp(2 * R));
    beta = C0 * zp(R - s) + alpha * zp(R);
  }
  double operator()(long r) const { return C0 * zp(std::abs(r - s)) + alpha * zp(r) + beta * zp(R - r); }
};

// Clamped-clamped response through the paper's clamped-pinned eigenfunction expansion (7),
// nodal moments included, and the settlement (15) of the end rotation at r = R.
void clamped_clamped_eigen(const RegularBeam& b, const std::vector<NodalLoad>& loads, std::vector<double>& w,
                           std::vector<double>& slope, double feq[4]) {
  const long R = b.R;
  const double a = b.a(), EI = b.EI, L = b.L, Bc = a * a * a / (24.0 * EI);
  std::vector<double> P(R + 1, 0.0), C(R + 1, 0.0);
  for (const auto& l : loads) {
    P[l.node] += l.force;
    C[l.node] += l.moment;
  }
  w.assign(R + 1, 0.0);
  std::vector<double> phi(R + 1, 0.0);
  // End-element rows of each eigenfunction, from the identities (paper, (10) applied to W_k with
  // its load alpha_k^2 W_k / B) -12 W_1 + 6 Phi_1 = (E - 1) Delta^2 W_0 - 4 alpha^2 W_1,
  // -6 W_1 + 2 Phi_1 = -Delta^2 W_0, -12 W_{R-1} - 6 Phi_{R-1} - 6 Phi_R = -(E - 1) Delta^2 W_{R-1}
  // - 4 alpha^2 W_{R-1}, with the differences taken analytically: nodal differences would cost
  // ~R^3 eps in the reactions, which the support springs amplify near a mechanism.
  double rows[3] = {0, 0, 0};
  const std::vector<double> alpha2 = lasecka::eigenvalues(R);
  for (double a2 : alpha2) {
    const lasecka::Eigenfunction ef = lasecka::eigenfunction(R, a2);
    double nrm = 0;
    for (long r = 0; r <= R; ++r) nrm += ef.W[r + 1] * ef.W[r + 1];
    nrm = std::sqrt(nrm);
    double Pk = 0, Mk = 0;
    for (long r = 0; r <= R; ++r) {
      Pk += P[r] * ef.W[r + 1];
      Mk += C[r] / a * ef.Phi[r + 1];
    }
    const double c = Bc * (Pk + Mk) / (a2 * nrm * nrm);
    for (long r = 0; r <= R; ++r) {
      w[r] += c * ef.W[r + 1];
      phi[r] += c * ef.Phi[r + 1];
    }
    rows[0] += c * (ef.D3[0] - 4.0 * a2 * ef.W[2]);
    rows[1] += c * (-ef.D2[0]);
    rows[2] += c * (-ef.D3[R - 1] - 4.0 * a2 * ef.W[R]);
  }
  std::vector<double> philoc(R + 1, 0.0);  // rotations with every w held (local moment response)
  for (long s = 1; s <= R; ++s) {
    if (C[s] == 0.0) continue;
    const RotationGreen G(R, s);
    for (long r = 1; r <= R; ++r) philoc[r] += a * a / EI * G(r) * C[s];
  }
  for (long r = 0; r <= R; ++r) phi[r] += philoc[r];
  // Support actions of the clamped-pinned beam (element units EI/a^3 on w, phi = a psi).
  const double ke = EI / (a * a * a);
  double react[4];
  react[0] = ke * (rows[0] + 6.0 * philoc[1]) - P[0];
  react[1] = a * ke * (rows[1] + 2.0 * philoc[1]) - C[0];
  react[2] = ke * (rows[2] - 6.0 * (R >= 2 ? philoc[R - 1] : 0.0) - 6.0 * philoc[R]) - P[R];
  react[3] = 0.0;
  // Clamp the end rotation: the cubic field with psi(L) = -psi_R (w0 = psi0 = wL = 0) and its end forces.
  const double pbar = -phi[R] / a;
  slope.assign(R + 1, 0.0);
  const double Rd = static_cast<double>(R);
  for (long r = 0; r <= R; ++r) {
    const Hermite H(static_cast<double>(r) / Rd, static_cast<double>(R - r) / Rd);
    w[r] += L * pbar * H.h[3];
    slope[r] = phi[r] / a + pbar * H.dh[3];
  }
  const double kl = EI / (L * L * L);
  react[0] += kl * 6.0 * L * pbar;
  react[1] += kl * 2.0 * L * L * pbar;
  react[2] += -kl * 6.0 * L * pbar;
  react[3] += kl * 4.0 * L * L * pbar;
  for (int i = 0; i < 4; ++i) feq[i] = -react[i];
}

}  // namespace

StaticSolution solve_static(const RegularBeam& b, const std::vector<NodalLoad>& loads, StaticMethod method) {
  StaticSolution out;
  solve_static(b, loads, method, out);
  return out;
}

void solve_static(const RegularBeam& b, const std::vector<NodalLoad>& loads, StaticMethod method,
                  StaticSolution& out) {
  b.validate(false);
  check_loads(b, loads);
  if (rigid_body_modes(b) > 0) throw Mechanism(mechanism_message(b));
  if (method == StaticMethod::EigenfunctionExpansion && b.R > kMaxEigenfunctionR)
    throw std::invalid_argument("the eigenfunction expansion costs O(R^2): R must be <= " +
                                std::to_string(kMaxEigenfunctionR) + " (use the piecewise-cubic closed form)");
  out.warnings.clear();
  out.reactions = {};
  double k[4];
  for (int i = 0; i < 4; ++i) {
    k[i] = b.dimensionless_spring(i);
    if (!std::isinf(k[i]) && k[i] > kRigidSpring) {
      out.warnings.push_back("an end spring above 1e60 (dimensionless) is treated as rigid");
      k[i] = kInf;
    }
  }
  double feq[4];
  if (method == StaticMethod::PiecewiseCubic) clamped_clamped_cubic(b, loads, out.w, out.slope, feq);
  else clamped_clamped_eigen(b, loads, out.w, out.slope, feq);

  const SupportSolution sup = solve_supports(k);
  out.support_flexibility = sup.flexibility;
  out.support_condition = sup.condition;
  const double L = b.L, EI = b.EI;
  const double fhat[4] = {feq[0] * L * L / EI, feq[1] * L / EI, feq[2] * L * L / EI, feq[3] * L / EI};
  double d[4] = {0, 0, 0, 0}, q[4] = {0, 0, 0, 0};  // (w0/L, psi0, wL/L, psiL); (w0/L, rho, psi0, psiL)
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      d[i] += sup.G[i][j] * fhat[j];
      q[i] += sup.Q[i][j] * fhat[j];
    }
  // Settlement field w0 H1 + L psi0 H2 + wL H3 + L psiL H4 written with H1 = 1 - H3, so that a
  // near-rigid translation (w0 ~ wL large) never enters as the difference wL - w0.
  const long R = b.R;
  const double Rd = static_cast<double>(R);
  for (long r = 0; r <= R; ++r) {
    const Hermite H(static_cast<double>(r) / Rd, static_cast<double>(R - r) / Rd);
    out.w[r] += L * (q[0] + q[1] * H.h[2] + q[2] * H.h[1] + q[3] * H.h[3]);
    out.slope[r] += q[1] * H.dh[2] + q[2] * H.dh[1] + q[3] * H.dh[3];
  }
  // End DOFs held exactly where the support is rigid.
  if (std::isinf(k[0])) out.w[0] = 0.0;
  if (std::isinf(k[1])) out.slope[0] = 0.0;
  if (std::isinf(k[2])) out.w[R] = 0.0;
  if (std::isinf(k[3])) out.slope[R] = 0.0;
  // Support actions on the beam: -k d for springs; K_L d - f_eq for held DOFs.
  const double scale[4] = {EI / (L * L), EI / L, EI / (L * L), EI / L};
  for (int i = 0; i < 4; ++i) {
    if (!std::isinf(k[i])) {
      out.reactions[i] = -k[i] * d[i] * scale[i];
    } else {
      double kd = 0;
      for (int j = 0; j < 4; ++j) kd += kKhat[i][j] * d[j];
      out.reactions[i] = kd * scale[i] - feq[i];
    }
  }
  // Physics, not a doubt about the digits (the closed form keeps them however soft the springs):
  // reported as a flag and the flexibility itself, not as a warning.
  out.near_mechanism = sup.flexibility > kNearMechanismFlexibility;
}

double static_residual(const RegularBeam& b, const std::vector<NodalLoad>& loads, const StaticSolution& s) {
  const long R = b.R;
  const double a = b.a(), EI = b.EI;
  static const double ke[4][4] = {{12, 6, -12, 6}, {6, 4, -6, 2}, {-12, -6, 12, -6}, {6, 2, -6, 4}};
  std::vector<double> Ku(2 * (R + 1), 0.0), f(2 * (R + 1), 0.0);
  double umax = 0;
  for (long e = 0; e < R; ++e) {
    const double ue[4] = {s.w[e], a * s.slope[e], s.w[e + 1], a * s.slope[e + 1]};
    for (int i = 0; i < 4; ++i) {
      double acc = 0;
      for (int j = 0; j < 4; ++j) acc += ke[i][j] * ue[j];
      Ku[2 * e + i] += acc;
    }
  }
  for (long r = 0; r <= R; ++r) umax = std::max({umax, std::abs(s.w[r]), std::abs(a * s.slope[r])});
  for (const auto& l : loads) {
    f[2 * l.node] += l.force * a * a * a / EI;
    f[2 * l.node + 1] += l.moment * a * a / EI;
  }
  const double kel[4] = {b.k0 * a * a * a / EI, b.r0 * a / EI, b.kL * a * a * a / EI, b.rL * a / EI};
  const long dof[4] = {0, 1, 2 * R, 2 * R + 1};
  double kmax = 60.0;
  for (int i = 0; i < 4; ++i) {
    if (std::isinf(kel[i])) {
      Ku[dof[i]] = f[dof[i]] = 0.0;
    } else {
      const double v = (dof[i] % 2 == 0) ? s.w[dof[i] / 2] : a * s.slope[dof[i] / 2];
      Ku[dof[i]] += kel[i] * v;
      kmax = std::max(kmax, 60.0 + kel[i]);
    }
  }
  double res = 0, fmax = 0;
  for (std::size_t i = 0; i < Ku.size(); ++i) {
    res = std::max(res, std::abs(Ku[i] - f[i]));
    fmax = std::max(fmax, std::abs(f[i]));
  }
  const double den = kmax * umax + fmax;
  return den > 0 ? res / den : res;
}

std::array<double, 2> interpolate(const RegularBeam& b, const StaticSolution& s, double x) {
  const double a = b.a();
  long e = static_cast<long>(std::floor(x / a));
  e = std::clamp<long>(e, 0, b.R - 1);
  const double xi = std::clamp((x - static_cast<double>(e) * a) / a, 0.0, 1.0);
  const Hermite H(xi, 1.0 - xi);
  const double v[4] = {s.w[e], a * s.slope[e], s.w[e + 1], a * s.slope[e + 1]};
  double w = 0, dw = 0;
  for (int i = 0; i < 4; ++i) {
    w += v[i] * H.h[i];
    dw += v[i] * H.dh[i];
  }
  return {w, dw / a};
}

}  // namespace modalbench::difference_eq
