#include "frame_members.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

namespace modalbench::exact::detail {

namespace {

MemberField bar(FieldKind kind, int dof, double L, double stiff, double inertia, double d_scale, double f_scale) {
  MemberField f;
  f.kind = kind;
  f.m = 1;
  f.dofs = {dof, -1};
  f.d_scale = {d_scale, 0};
  f.f_scale = {f_scale, 0};
  f.stiff = stiff;
  f.inertia = inertia;
  f.L = L;
  return f;
}

MemberField bending(FieldKind kind, std::array<int, 2> dofs, double L, double EI, double rhoA, double rhoI, double kGA) {
  MemberField f;
  f.kind = kind;
  f.m = 2;
  f.dofs = dofs;
  f.d_scale = {L, 1.0};
  f.f_scale = {EI / (L * L), EI / L};
  f.stiff = EI;
  f.inertia = rhoA;
  f.rot_inertia = rhoI;
  f.shear = std::isinf(kGA) ? 0.0 : EI / (kGA * L * L);
  f.L = L;
  return f;
}

/// exp(A t) of a nilpotent A (a field's state matrix at lambda = 0: A^(2m) = 0), by its finite series.
Eigen::MatrixXd nilpotent_exp(const Eigen::MatrixXd& A, double t) {
  const Eigen::Index n = A.rows();
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(n, n), term = T;
  for (Eigen::Index k = 1; k < n; ++k) {
    term = term * A * (t / static_cast<double>(k));
    T += term;
  }
  return T;
}

/// The field's distributed load term b(xi) of y' = A y + b (dimensionless), from local intensities.
Eigen::VectorXd load_term(const MemberField& f, const LocalLineLoad& q, double xi) {
  const auto at = [xi](const std::array<double, 2>& v) { return v[0] + (v[1] - v[0]) * xi; };
  Eigen::VectorXd b = Eigen::VectorXd::Zero(2 * f.m);
  switch (f.kind) {
    case FieldKind::Axial: b(1) = -at(q.qx) * f.L / f.stiff; break;
    case FieldKind::Torsion: break;
    case FieldKind::BendingXZ: b(2) = -at(q.qz) * f.L * f.L * f.L / f.stiff; break;
    case FieldKind::BendingXY: b(2) = -at(q.qy) * f.L * f.L * f.L / f.stiff; break;
  }
  return b;
}

/// y_p(xi) = int_0^xi exp(A0 (xi - t)) b(t) dt with y_p(0) = 0: a polynomial of degree <= 2m in t
/// under the integral, so 4-point Gauss-Legendre is exact.
Eigen::VectorXd particular(const MemberField& f, const Eigen::MatrixXd& A0, const LocalLineLoad& q, double xi) {
  static const double x4[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static const double w4[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * f.m);
  for (int k = 0; k < 4; ++k) {
    const double t = 0.5 * xi * (1.0 + x4[k]);
    y += 0.5 * xi * w4[k] * nilpotent_exp(A0, xi - t) * load_term(f, q, t);
  }
  return y;
}

}  // namespace

Eigen::MatrixXd MemberField::state(double lambda) const {
  if (m == 1) {
    Eigen::MatrixXd A(2, 2);
    A << 0, 1, -lambda * inertia * L * L / stiff, 0;
    return A;
  }
  const double c = lambda * inertia * L * L * L * L / stiff, r = lambda * rot_inertia * L * L / stiff;
  const double sign = kind == FieldKind::BendingXZ ? -1.0 : 1.0;  // theta_y = -w', theta_z = +v'
  Eigen::MatrixXd A(4, 4);
  A << 0, sign, shear, 0,
       0, 0, 0, 1,
       -c, 0, 0, 0,
       0, -r, -sign, 0;
  return A;
}

std::vector<MemberField> member_fields(const FrameMember& member, bool spatial, Theory theory, double length) {
  const Section p = member.properties();
  const Material& mt = member.material;
  const double L = length, EA = mt.E * p.A, rhoA = mt.rho * p.A;
  const bool timo = theory == Theory::Timoshenko;
  const double kGA = timo ? mt.kappa * mt.G * p.A : INFINITY;
  std::vector<MemberField> out;
  out.push_back(bar(FieldKind::Axial, 0, L, EA, rhoA, L, EA));
  out.push_back(bending(FieldKind::BendingXZ, {2, 4}, L, mt.E * p.Iy, rhoA, timo ? mt.rho * p.Iy : 0.0, kGA));
  if (spatial) {
    out.push_back(bar(FieldKind::Torsion, 3, L, mt.G * p.J, mt.rho * p.Ip, 1.0, mt.G * p.J / L));
    out.push_back(bending(FieldKind::BendingXY, {1, 5}, L, mt.E * p.Iz, rhoA, timo ? mt.rho * p.Iz : 0.0, kGA));
  }
  return out;
}

namespace {

/// A bar's dimensionless dynamic stiffness in closed form, k = sqrt(c) > 0 (u'' = -c u):
/// k / sin k [[cos k, -1], [-1, cos k]]; J0 = floor(k / pi) (clamped at both ends: k = n pi).
LongSegment bar_closed_form(double c) {
  const double k = std::sqrt(c), s = std::sin(k), co = std::cos(k);
  LongSegment out;
  out.K.resize(2, 2);
  out.K << k * co / s, -k / s, -k / s, k * co / s;
  out.clamped_below = static_cast<int>(std::floor(k / std::numbers::pi));
  out.min_pivot_scale = std::abs(s);  // 0 at the clamped frequencies, K's poles
  return out;
}

/// An Euler-Bernoulli beam's dimensionless dynamic stiffness in closed form, b = c^(1/4) (w'''' = c w),
/// from the general solution w = C1 cos b xi + C2 sin b xi + C3 exp(-b xi) + C4 exp(-b (1 - xi)),
/// whose basis stays well conditioned however large b is (no cosh, no sinh): K = F B^-1 with B the
/// end displacements (w, theta = sign w') and F the end forces (-V, -M at xi = 0; V, M at 1) of the
/// basis, M = sign w'', V = -w''' (the state's relations, MemberField::state). J0 counts the
/// clamped-clamped roots of cos b cosh b = 1 below b (Williams & Wittrick):
/// i - (1 - (-1)^i s) / 2 with i = floor(b / pi), s = sign(1 - cosh b cos b) = sign(sech b - cos b).
LongSegment bending_closed_form(double c, double sign) {
  const double b = std::pow(c, 0.25);
  const auto derivative = [b](int n, double xi) {
    const double bn = std::pow(b, n), shift = n * std::numbers::pi / 2;
    return Eigen::Vector4d(bn * std::cos(b * xi + shift), bn * std::sin(b * xi + shift),
                           std::pow(-b, n) * std::exp(-b * xi), bn * std::exp(-b * (1 - xi)));
  };
  Eigen::Matrix4d B, F;
  B.row(0) = derivative(0, 0).transpose();
  B.row(1) = sign * derivative(1, 0).transpose();
  B.row(2) = derivative(0, 1).transpose();
  B.row(3) = sign * derivative(1, 1).transpose();
  F.row(0) = derivative(3, 0).transpose();          // -V(0) = w'''(0)
  F.row(1) = -sign * derivative(2, 0).transpose();  // -M(0)
  F.row(2) = -derivative(3, 1).transpose();         // V(1)
  F.row(3) = sign * derivative(2, 1).transpose();   // M(1)
  LongSegment out;
  // K B = F, so B^T K^T = F^T: one LU of B^T.
  const Eigen::Matrix4d K = B.transpose().fullPivLu().solve(F.transpose()).transpose();
  out.K = 0.5 * (K + K.transpose());
  out.asymmetry = (K - K.transpose()).norm() / K.norm();
  const int i = static_cast<int>(std::floor(b / std::numbers::pi));
  const double sech = b > 700 ? 0.0 : 1.0 / std::cosh(b), s = sech - std::cos(b) > 0 ? 1.0 : -1.0;
  out.clamped_below = i - static_cast<int>((1 - (i % 2 == 0 ? 1 : -1) * s) / 2);
  out.min_pivot_scale = std::abs(sech - std::cos(b));  // 0 at the clamped frequencies, K's poles
  return out;
}

}  // namespace

MemberStiffness member_stiffness(const std::vector<MemberField>& fields, double lambda) {
  MemberStiffness out;
  out.K = Eigen::MatrixXd::Zero(kMemberDofs, kMemberDofs);
  for (const MemberField& f : fields) {
    const Eigen::MatrixXd A = f.state(lambda);
    // Bars and Euler-Bernoulli bending in closed form (exact to rounding at any frequency); a
    // Timoshenko member by doubling, from a base piece with |p| h <= 1 (no clamped frequency below
    // omega there: J0 = 0). At low frequency (|p| <= 1) one exponential of the whole member.
    const double c = f.m == 1 ? -A(1, 0) : -A(2, 0);
    const bool closed = f.m == 1 || (f.shear == 0.0 && f.rot_inertia == 0.0);
    const double p = closed ? (f.m == 1 ? std::sqrt(std::max(c, 0.0)) : std::pow(std::max(c, 0.0), 0.25))
                            : state_wavenumbers(A).cwiseAbs().maxCoeff();
    const int levels = p > 1.0 ? static_cast<int>(std::ceil(std::log2(p))) : 0;
    const LongSegment seg = p <= 1.0 || !closed ? long_segment_dynamic_stiffness(A, 1.0, levels)
                            : f.m == 1          ? bar_closed_form(c)
                                                : bending_closed_form(c, f.kind == FieldKind::BendingXZ ? -1.0 : 1.0);
    out.clamped_below += seg.clamped_below;
    out.log_abs_det_tdf += seg.log_abs_det_tdf;
    out.min_pivot_scale = std::min(out.min_pivot_scale, seg.min_pivot_scale);
    out.doubled = out.doubled || levels > 0;
    for (int a = 0; a < 2 * f.m; ++a)
      for (int b = 0; b < 2 * f.m; ++b) {
        const int ia = a % f.m, ib = b % f.m;
        const int ra = (a / f.m) * 6 + f.dofs[static_cast<std::size_t>(ia)];
        const int rb = (b / f.m) * 6 + f.dofs[static_cast<std::size_t>(ib)];
        out.K(ra, rb) += f.f_scale[static_cast<std::size_t>(ia)] * seg.K(a, b) / f.d_scale[static_cast<std::size_t>(ib)];
      }
  }
  return out;
}

Eigen::VectorXd fixed_end_forces(const std::vector<MemberField>& fields, const std::vector<LocalLineLoad>& loads) {
  Eigen::VectorXd P = Eigen::VectorXd::Zero(kMemberDofs);
  for (const MemberField& f : fields) {
    const Eigen::MatrixXd A0 = f.state(0.0), T = nilpotent_exp(A0, 1.0);
    const int m = f.m;
    Eigen::VectorXd yp = Eigen::VectorXd::Zero(2 * m);
    for (const LocalLineLoad& q : loads) yp += particular(f, A0, q, 1.0);
    if (yp.isZero(0.0)) continue;
    // Held ends: d(0) = 0 and d(1) = Tdf f(0) + yp_d(1) = 0.
    const Eigen::VectorXd f0 = -T.topRightCorner(m, m).fullPivLu().solve(yp.head(m));
    const Eigen::VectorXd f1 = T.bottomRightCorner(m, m) * f0 + yp.tail(m);
    for (int i = 0; i < m; ++i) {
      const double fs = f.f_scale[static_cast<std::size_t>(i)];
      P(f.dofs[static_cast<std::size_t>(i)]) += -fs * f0(i);
      P(6 + f.dofs[static_cast<std::size_t>(i)]) += fs * f1(i);
    }
  }
  return P;
}

MemberState member_state(const std::vector<MemberField>& fields, const std::vector<LocalLineLoad>& loads,
                         const Eigen::VectorXd& d, const Eigen::VectorXd& P, double xi) {
  MemberState out;
  for (const MemberField& f : fields) {
    const int m = f.m;
    const Eigen::MatrixXd A0 = f.state(0.0);
    Eigen::VectorXd y0(2 * m);
    for (int i = 0; i < m; ++i) {
      const auto k = static_cast<std::size_t>(i);
      y0(i) = d(f.dofs[k]) / f.d_scale[k];
      y0(m + i) = -P(f.dofs[k]) / f.f_scale[k];  // the node's force on the first end is -f(0)
    }
    Eigen::VectorXd y = nilpotent_exp(A0, xi) * y0;
    for (const LocalLineLoad& q : loads) y += particular(f, A0, q, xi);
    for (int i = 0; i < m; ++i) out.d[static_cast<std::size_t>(f.dofs[static_cast<std::size_t>(i)])] = f.d_scale[static_cast<std::size_t>(i)] * y(i);
    const double f0 = f.f_scale[0] * y(m), f1 = m == 2 ? f.f_scale[1] * y(m + 1) : 0.0;
    switch (f.kind) {
      case FieldKind::Axial: out.forces.N = f0; break;
      case FieldKind::Torsion: out.forces.T = f0; break;
      // My = EI w'' = -(the face moment about +y); Qz = dMy/dx = -Vz (statics).
      case FieldKind::BendingXZ: out.forces.My = -f1; out.forces.Qz = -f0; break;
      // Mz = EI v'' = the face moment about +z; Qy = dMz/dx = -Vy.
      case FieldKind::BendingXY: out.forces.Mz = f1; out.forces.Qy = -f0; break;
    }
  }
  return out;
}

}  // namespace modalbench::exact::detail
