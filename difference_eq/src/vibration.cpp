// Free vibration of the regular discrete beam: the mode count, natural frequencies, mode shapes, residuals.
#include "modalbench/numerics/root_finding.hpp"
#include "modalbench/difference_eq/vibration.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <stdexcept>

#include "chain.hpp"

namespace modalbench::difference_eq {

namespace {

using detail::Chain;
using detail::MassCoeffs;

struct Problem {
  long R;
  const MassCoeffs* mc;
  std::array<double, 4> k;  // element units, inf = held
  double lam_to_Omega;      // Omega = lambda * this
};

Problem make_problem(const RegularBeam& b, MassModel mass) {
  b.validate(true);
  Problem p;
  p.R = b.R;
  p.mc = &detail::coeffs(mass);
  const double a = b.a();
  auto sc = [](double v, double f) { return std::isinf(v) ? kInf : v * f; };
  p.k = {sc(b.k0, a * a * a / b.EI), sc(b.r0, a / b.EI), sc(b.kL, a * a * a / b.EI), sc(b.rL, a / b.EI)};
  p.lam_to_Omega = b.rhoA * a * a * a * a / (p.mc->den * b.EI);
  return p;
}

Chain chain_at(const Problem& p, double Om) {
  Chain c(p.R, *p.mc, Om);
  // A root exactly at a band edge (sigma or kappa = 0) makes the column normalisation 0/0;
  // the functions are smooth there, so step off by one ulp.
  for (int i = 0; c.degenerate && i < 4; ++i) {
    Om = std::nextafter(Om, kInf);
    c = Chain(p.R, *p.mc, Om);
  }
  return c;
}

long count_omega(const Problem& p, double Om) {
  // At a pinned-pinned eigenvalue N_pp jumps exactly while an eigenvalue of D_phiphi crosses zero
  // with a rounding-sized sign: the two jumps cancel in exact arithmetic but not within ~1e-15
  // of the crossing. The count is piecewise constant, so evaluate it just above such a point
  // (1e-10 relative); Brent on the pole-free det C then places the root exactly.
  for (double shift = 1e-10; shift < 1e-3; shift *= 10.0) {
    const long lo = detail::pinned_pinned_count(p.R, *p.mc, Om * (1.0 - 1e-12));
    const long hi = detail::pinned_pinned_count(p.R, *p.mc, Om * (1.0 + 1e-12));
    if (lo == hi) break;
    Om *= 1.0 + shift;
  }
  Chain c = chain_at(p, Om);
  // Likewise at a clamped-clamped eigenvalue (a pole of D): there D is a huge rank-one term
  // whose rounding hides the signs of the rest. Step off until the pole no longer dominates.
  for (double shift = 1e-12; c.pole_closeness() < 1e-11 && shift < 1e-3; shift *= 10.0)
    c = chain_at(p, Om * (1.0 + shift));
  const Eigen::Matrix4d D = c.end_stiffness();
  Eigen::Matrix2d Dpp;
  Dpp << D(1, 1), D(1, 3), D(3, 1), D(3, 3);
  std::vector<int> fr;
  for (int i = 0; i < 4; ++i)
    if (!std::isinf(p.k[i])) fr.push_back(i);
  Eigen::MatrixXd Df(fr.size(), fr.size());
  for (std::size_t i = 0; i < fr.size(); ++i)
    for (std::size_t j = 0; j < fr.size(); ++j) Df(i, j) = D(fr[i], fr[j]) + (i == j ? p.k[fr[i]] : 0.0);
  return detail::pinned_pinned_count(p.R, *p.mc, c.Omega) - detail::negative_eigenvalues(Dpp) +
         detail::negative_eigenvalues(Df);
}

double char_omega(const Problem& p, double Om) {
  const Chain c = chain_at(p, Om);
  return c.characteristic_matrix(p.k).partialPivLu().determinant();
}

}  // namespace

long count_below(const RegularBeam& beam, MassModel mass, double lambda) {
  const Problem p = make_problem(beam, mass);
  if (!(lambda > 0)) return 0;
  return count_omega(p, lambda * p.lam_to_Omega);
}

double characteristic_function(const RegularBeam& beam, MassModel mass, double lambda) {
  const Problem p = make_problem(beam, mass);
  return char_omega(p, lambda * p.lam_to_Omega);
}

std::vector<double> end_dynamic_stiffness(const RegularBeam& beam, MassModel mass, double lambda) {
  const Problem p = make_problem(beam, mass);
  const Eigen::Matrix4d D = chain_at(p, lambda * p.lam_to_Omega).end_stiffness();
  std::vector<double> out(16);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[4 * i + j] = D(i, j);
  return out;
}

Spectrum natural_frequencies(const RegularBeam& beam, MassModel mass, int k) {
  const Problem p = make_problem(beam, mass);
  if (k < 0) throw std::invalid_argument("number of modes must be >= 0");
  Spectrum out;
  const long R = beam.R;
  const int held_t = std::isinf(p.k[0]) + std::isinf(p.k[2]);
  const int held_r = std::isinf(p.k[1]) + std::isinf(p.k[3]);
  out.available = mass == MassModel::Consistent ? 2 * (R + 1) - held_t - held_r : (R + 1) - held_t;
  const long want = std::min<long>(k, out.available);
  out.rigid = static_cast<int>(std::min<long>(rigid_body_modes(beam), want));
  out.omega_rad_s.assign(out.rigid, 0.0);

  auto N = [&](double Om) {
    ++out.count_evaluations;
    return count_omega(p, Om);
  };
  auto f = [&](double Om) { return char_omega(p, Om); };

  double lo = 0.0;
  long nlo = rigid_body_modes(beam);
  double hi_prev = 0.0;
  for (long j = nlo + 1; j <= want;) {
    // Bracket from the structure: mode j lies below the (j+2)-th pinned-pinned frequency,
    // whose acoustic branch is closed-form; the exact count confirms or the bracket grows.
    double hi = 0;
    if (j + 2 <= R - 1) hi = detail::acoustic_estimate(R, *p.mc, j + 2) * (1.0 + 1e-9);
    if (!(hi > lo)) hi = std::max(2.0 * lo, hi_prev > lo ? hi_prev : 1.0);
    long nhi = N(hi);
    for (int grow = 0; nhi < j; ++grow) {
      if (grow > 200) throw std::runtime_error("difference_eq: could not bracket mode " + std::to_string(j));
      lo = hi;
      nlo = nhi;
      hi *= 2.0;
      nhi = N(hi);
    }
    // Isolate: N(lo) = j - 1, N(hi) = j.
    while (!(nlo == j - 1 && nhi == j)) {
      if (hi - lo <= 4e-16 * hi) break;
      const double mid = 0.5 * (lo + hi);
      const long nm = N(mid);
      if (nm < nlo || nm > nhi)
        throw std::runtime_error("difference_eq: the mode count is not monotonic (numerical breakdown)");
      if (nm >= j) {
        hi = mid;
        nhi = nm;
      } else {
        lo = mid;
        nlo = nm;
      }
    }
    double root;
    long mult = 1;
    if (nlo == j - 1 && nhi == j && lo == 0.0) {
      // Omega = 0 is the double root x = 0 where the solution basis degenerates: never
      // evaluate there; move lo up by halving (the count keeps the bracket honest).
      double t = 0.5 * hi;
      for (int h = 0; h < 2000; ++h, t *= 0.5) {
        if (N(t) < j) break;
        hi = t;
      }
      lo = t;
    }
    if (nlo == j - 1 && nhi == j) {
      const double flo = f(lo), fhi = f(hi);
      out.determinant_evaluations += 2;
      if (flo == 0.0) root = lo;
      else if (fhi == 0.0) root = hi;
      else if ((flo > 0) != (fhi > 0)) {
        const BracketedRoot br = bracketed_root(f, lo, hi, flo, fhi, 2e-300, detail::kRootRelTol);
        root = br.root;
        out.determinant_evaluations += br.evaluations;
      }
      else {
        // No sign change seen (should not happen for a simple root): bisect on the count.
        while (hi - lo > 4e-16 * hi) {
          const double mid = 0.5 * (lo + hi);
          if (N(mid) >= j) hi = mid;
          else lo = mid;
        }
        root = 0.5 * (lo + hi);
      }
      out.max_bracket = std::max(out.max_bracket, 4.0 * std::numeric_limits<double>::epsilon());
    } else {
      // A cluster narrower than rounding: a repeated frequency.
      root = 0.5 * (lo + hi);
      mult = nhi - (j - 1);
      out.max_bracket = std::max(out.max_bracket, (hi - lo) / hi);
    }
    for (long m = 0; m < mult && j <= want; ++m, ++j) out.omega_rad_s.push_back(std::sqrt(root / p.lam_to_Omega));
    hi_prev = 2.0 * hi;
    lo = hi;
    nlo = nhi;
  }
  return out;
}

ModeShape mode_shape(const RegularBeam& beam, MassModel mass, double omega) {
  const Problem p = make_problem(beam, mass);
  const Chain c = chain_at(p, omega * omega * p.lam_to_Omega);
  const Eigen::Matrix4d Cm = c.characteristic_matrix(p.k);
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(Cm, Eigen::ComputeFullV);
  if (svd.info() != Eigen::Success)
    throw std::runtime_error("difference_eq: SVD of the 4x4 characteristic matrix failed (non-finite entries)");
  const Eigen::Vector4d amp = svd.matrixV().col(3);
  const long R = beam.R;
  ModeShape u;
  u.w.assign(R + 1, 0.0);
  u.slope.assign(R + 1, 0.0);
  std::vector<double> phi(R + 1, 0.0);
  for (long r = 0; r <= R; ++r) {
    const double t = static_cast<double>(r) - c.T;
    const double sg = t < 0 ? -1.0 : 1.0;
    std::complex<double> w = 0, ph = 0;
    for (int j = 0; j < 2; ++j) {
      std::complex<double> C, S;
      c.root[j].ch_sh(std::abs(t), c.T, C, S);
      S *= sg;
      w += amp[j] * (c.root[j].W * C / c.norm[0][j]) + amp[2 + j] * (c.root[j].W * S / c.norm[1][j]);
      ph += amp[j] * (c.root[j].Phi * S / c.norm[0][j]) + amp[2 + j] * (c.root[j].Phi * C / c.norm[1][j]);
    }
    u.w[r] = w.real();
    phi[r] = ph.real();
  }
  double scale = 0;
  for (long r = 0; r <= R; ++r) scale = std::max({scale, std::abs(u.w[r]), std::abs(phi[r])});
  const double a = beam.a();
  for (long r = 0; r <= R; ++r) {
    u.w[r] /= scale;
    u.slope[r] = phi[r] / scale / a;
  }
  return u;
}

double eigen_residual(const RegularBeam& beam, MassModel mass, double omega, const ModeShape& u) {
  const Problem p = make_problem(beam, mass);
  const long R = beam.R;
  const double a = beam.a(), Om = omega * omega * p.lam_to_Omega;
  static const double ke[4][4] = {{12, 6, -12, 6}, {6, 4, -6, 2}, {-12, -6, 12, -6}, {6, 2, -6, 4}};
  static const double mc[4][4] = {{156, 22, 54, -13}, {22, 4, 13, -3}, {54, 13, 156, -22}, {-13, -3, -22, 4}};
  static const double ml[4][4] = {{1, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 0}};
  const auto& me = mass == MassModel::Consistent ? mc : ml;
  std::vector<double> Ku(2 * (R + 1), 0.0), Mu(2 * (R + 1), 0.0);
  for (long e = 0; e < R; ++e) {
    const double ue[4] = {u.w[e], a * u.slope[e], u.w[e + 1], a * u.slope[e + 1]};
    for (int i = 0; i < 4; ++i) {
      double ks = 0, ms = 0;
      for (int j = 0; j < 4; ++j) {
        ks += ke[i][j] * ue[j];
        ms += me[i][j] * ue[j];
      }
      Ku[2 * e + i] += ks;
      Mu[2 * e + i] += ms;
    }
  }
  const long end_dof[4] = {0, 1, 2 * R, 2 * R + 1};
  double held = 0;
  for (int i = 0; i < 4; ++i) {
    const long d = end_dof[i];
    const double v = (d % 2 == 0) ? u.w[d / 2] : a * u.slope[d / 2];
    if (std::isinf(p.k[i])) {
      held = std::max(held, std::abs(v));
      Ku[d] = Mu[d] = 0;  // the reaction takes this row
    } else {
      Ku[d] += p.k[i] * v;
    }
  }
  // Normwise backward error: ||r|| / ((||K|| + Omega ||M||) ||u||) (infinity norms, element units).
  double res = 0, umax = 0;
  for (std::size_t i = 0; i < Ku.size(); ++i) res = std::max(res, std::abs(Ku[i] - Om * Mu[i]));
  for (long r = 0; r <= R; ++r) umax = std::max({umax, std::abs(u.w[r]), std::abs(a * u.slope[r])});
  double knorm = 60.0, mnorm = mass == MassModel::Consistent ? 446.0 : 2.0;
  for (int i = 0; i < 4; ++i)
    if (!std::isinf(p.k[i])) knorm = std::max(knorm, 60.0 + p.k[i]);
  const double den = (knorm + Om * mnorm) * umax;
  return std::max(den > 0 ? res / den : res, umax > 0 ? held / umax : held);
}

}  // namespace modalbench::difference_eq
