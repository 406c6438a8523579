#pragma once
// The assembled banded FE system of the regular discrete beam, solved directly: the
// independent check of every closed form (and the baseline the benchmarks compare with).
//
// DOFs (w_0, phi_0, w_1, phi_1, ..., w_R, phi_R), phi = a psi, element units EI/a^3, so the
// matrix is symmetric banded with half-bandwidth 3. Held DOFs become identity rows. LDL^T
// without pivoting: exact for the SPD static matrix; for K - lambda M its pivot signs give
// the Sylvester inertia, i.e. a Sturm count. Templated on the scalar so tests can run it in
// binary128 (`__float128`) where the data of near-mechanisms needs more than double.

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "modalbench/difference_eq/regular_beam.hpp"
#include "modalbench/difference_eq/vibration.hpp"

namespace modalbench::difference_eq::assembled {

/// Symmetric banded matrix, half-bandwidth 3 (upper band stored by rows).
template <class S>
struct Banded {
  long n = 0;
  std::vector<std::array<S, 4>> a;  ///< a[i][j] = A(i, i + j)
  explicit Banded(long n_) : n(n_), a(n_, std::array<S, 4>{S(0), S(0), S(0), S(0)}) {}
  void add(long i, long j, S v) {
    if (j < i) std::swap(i, j);
    a[i][j - i] += v;
  }
  /// Replace row and column i by the identity.
  void hold(long i) {
    for (long k = std::max(0L, i - 3); k < i; ++k) a[k][i - k] = S(0);
    a[i] = {S(1), S(0), S(0), S(0)};
  }
  /// In-place LDL^T; returns the number of negative pivots. Throws on an exactly zero pivot
  /// (no pivoting: the inertia is then undetermined, not "+tiny").
  long factor() {
    long neg = 0;
    for (long k = 0; k < n; ++k) {
      if (a[k][0] == S(0)) throw std::runtime_error("assembled: zero pivot");
      const S d = a[k][0];
      if (d < S(0)) ++neg;
      const long last = std::min(n - 1, k + 3);
      for (long i = k + 1; i <= last; ++i) {
        const S l = a[k][i - k] / d;
        for (long j = i; j <= last; ++j) a[i][j - i] -= l * a[k][j - k];
        a[k][i - k] = l;
      }
    }
    return neg;
  }
  /// y = A x with the (unfactored) symmetric band.
  std::vector<S> multiply(const std::vector<S>& x) const {
    std::vector<S> y(n, S(0));
    for (long i = 0; i < n; ++i)
      for (long j = i; j <= std::min(n - 1, i + 3); ++j) {
        y[i] += a[i][j - i] * x[j];
        if (j != i) y[j] += a[i][j - i] * x[i];
      }
    return y;
  }
  /// Solves with the factored matrix.
  void solve(std::vector<S>& b) const {
    for (long k = 0; k < n; ++k)
      for (long i = k + 1; i <= std::min(n - 1, k + 3); ++i) b[i] -= a[k][i - k] * b[k];
    for (long k = 0; k < n; ++k) b[k] /= a[k][0];
    for (long k = n - 1; k >= 0; --k)
      for (long i = k + 1; i <= std::min(n - 1, k + 3); ++i) b[k] -= a[k][i - k] * b[i];
  }
};

inline constexpr double kStiff[4][4] = {{12, 6, -12, 6}, {6, 4, -6, 2}, {-12, -6, 12, -6}, {6, 2, -6, 4}};
inline constexpr double kMassConsistent[4][4] = {
    {156, 22, 54, -13}, {22, 4, 13, -3}, {54, 13, 156, -22}, {-13, -3, -22, 4}};
inline constexpr double kMassLumped[4][4] = {{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 0}};

/// K - Omega M in element units (Omega = omega^2 rhoA a^4 / (c EI), c = 420 or 2), springs added,
/// held DOFs replaced by identity rows.
template <class S>
Banded<S> dynamic_matrix(const RegularBeam& b, MassModel mass, S Omega) {
  const long R = b.R, n = 2 * (R + 1);
  Banded<S> A(n);
  const auto& me = mass == MassModel::Consistent ? kMassConsistent : kMassLumped;
  for (long e = 0; e < R; ++e)
    for (int i = 0; i < 4; ++i)
      for (int j = i; j < 4; ++j) A.add(2 * e + i, 2 * e + j, S(kStiff[i][j]) - Omega * S(me[i][j]));
  const S a = S(b.L) / S(static_cast<double>(R)), EI = S(b.EI);
  const double k[4] = {b.k0, b.r0, b.kL, b.rL};
  const S f[4] = {a * a * a / EI, a / EI, a * a * a / EI, a / EI};
  const long dof[4] = {0, 1, 2 * R, 2 * R + 1};
  for (int i = 0; i < 4; ++i)
    if (!std::isinf(k[i])) A.add(dof[i], dof[i], S(k[i]) * f[i]);
  for (int i = 0; i < 4; ++i)
    if (std::isinf(k[i])) A.hold(dof[i]);
  return A;
}

/// Omega per lambda = omega^2, in S.
template <class S>
S omega_scale(const RegularBeam& b, MassModel mass) {
  const S a = S(b.L) / S(static_cast<double>(b.R));
  return S(b.rhoA) * a * a * a * a / (S(mass == MassModel::Consistent ? 420.0 : 2.0) * S(b.EI));
}

/// Sturm count: natural frequencies with omega^2 < lambda. An exactly zero pivot (integer
/// element matrices make that happen at round lambda) moves lambda up by a relative 2^-90, then
/// 2^-70, 2^-50: the count is piecewise constant, so this is the count just above lambda.
template <class S>
long count_below(const RegularBeam& b, MassModel mass, S lambda) {
  for (int e = 90;; e -= 20) {
    Banded<S> A = dynamic_matrix<S>(b, mass, lambda * omega_scale<S>(b, mass));
    try {
      return A.factor();
    } catch (const std::runtime_error&) {
      if (e < 50) throw;
      lambda = lambda + lambda * S(std::ldexp(1.0, -e));
    }
  }
}

/// Static solve: nodal w (m) and slope dw/dx; `refine` steps of iterative refinement with the
/// residual in S (the system's condition grows like R^4: at R = 1e6 even binary128 needs them).
template <class S>
void static_solve(const RegularBeam& b, const std::vector<NodalLoad>& loads, std::vector<S>& w,
                  std::vector<S>& slope, int refine = 0) {
  Banded<S> A = dynamic_matrix<S>(b, MassModel::Consistent, S(0));
  const Banded<S> A0 = refine > 0 ? A : Banded<S>(0);
  const long R = b.R;
  const S a = S(b.L) / S(static_cast<double>(R)), EI = S(b.EI);
  std::vector<S> f(2 * (R + 1), S(0));
  for (const auto& l : loads) {
    f[2 * l.node] += S(l.force) * a * a * a / EI;
    f[2 * l.node + 1] += S(l.moment) * a * a / EI;
  }
  const double k[4] = {b.k0, b.r0, b.kL, b.rL};
  const long dof[4] = {0, 1, 2 * R, 2 * R + 1};
  for (int i = 0; i < 4; ++i)
    if (std::isinf(k[i])) f[dof[i]] = S(0);
  A.factor();
  std::vector<S> x = f;
  A.solve(x);
  for (int it = 0; it < refine; ++it) {
    std::vector<S> r = A0.multiply(x);
    for (std::size_t i = 0; i < r.size(); ++i) r[i] = f[i] - r[i];
    A.solve(r);
    for (std::size_t i = 0; i < r.size(); ++i) x[i] += r[i];
  }
  f.swap(x);
  w.resize(R + 1);
  slope.resize(R + 1);
  for (long r = 0; r <= R; ++r) {
    w[r] = f[2 * r];
    slope[r] = f[2 * r + 1] / a;
  }
}

/// Eigenvalue j (1-based, counting rigid modes) by bisection on the Sturm count, in S.
template <class S>
S eigenvalue(const RegularBeam& b, MassModel mass, long j, S lambda_hint, int steps = 200) {
  S lo = S(0), hi = lambda_hint;
  while (count_below<S>(b, mass, hi) < j) hi = hi * S(2);
  for (int i = 0; i < steps; ++i) {
    const S mid = (lo + hi) / S(2);
    if (count_below<S>(b, mass, mid) >= j) hi = mid;
    else lo = mid;
  }
  return (lo + hi) / S(2);
}

}  // namespace modalbench::difference_eq::assembled
