#include "modalbench/exact/plates.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "modalbench/numerics/line_system.hpp"

namespace modalbench::exact {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double pi = std::numbers::pi;
}  // namespace

std::vector<double> navier_frequencies(double a, double b, double D, double rho_h, int k) {
  std::vector<double> out;
  if (k <= 0) return out;
  const double c = pi * pi * std::sqrt(D / rho_h);
  auto omega = [&](int m, int n) { return c * (std::pow(m / a, 2) + std::pow(n / b, 2)); };
  // The k lowest have m, n <= k (omega grows in each index).
  for (int m = 1; m <= k; ++m)
    for (int n = 1; n <= k; ++n) out.push_back(omega(m, n));
  std::sort(out.begin(), out.end());
  out.resize(k);
  return out;
}

std::complex<double> navier_receptance(double a, double b, double D, double rho_h, double eta, double xe, double ye,
                                       double xo, double yo, double omega, int terms, double* tail) {
  return navier_receptance(a, b, D, rho_h, eta, xe, ye, xo, yo, omega, terms, terms, tail);
}

std::complex<double> navier_receptance(double a, double b, double D, double rho_h, double eta, double xe, double ye,
                                       double xo, double yo, double omega, int M, int N, double* tail) {
  // w = sum phi_mn(xe, ye) phi_mn(xo, yo) / (M (omega_mn^2 (1 + i eta) - omega^2)),
  // phi_mn = sin(m pi x / a) sin(n pi y / b), modal mass M = rho h a b / 4.
  std::vector<double> sxe(M + 1), sxo(M + 1), sye(N + 1), syo(N + 1);
  for (int m = 1; m <= M; ++m) {
    sxe[m] = std::sin(m * pi * xe / a);
    sxo[m] = std::sin(m * pi * xo / a);
  }
  for (int n = 1; n <= N; ++n) {
    sye[n] = std::sin(n * pi * ye / b);
    syo[n] = std::sin(n * pi * yo / b);
  }
  const double modal_mass = rho_h * a * b / 4.0, c = pi * pi * pi * pi * D / rho_h;
  std::complex<double> sum = 0, half = 0;
  for (int m = 1; m <= M; ++m) {
    const double xm = sxe[m] * sxo[m];
    if (xm == 0) continue;
    for (int n = 1; n <= N; ++n) {
      const double q = std::pow(m / a, 2) + std::pow(n / b, 2);
      const double w2 = c * q * q;
      const std::complex<double> term = xm * sye[n] * syo[n] / (modal_mass * (w2 * std::complex<double>(1, eta) - omega * omega));
      sum += term;
      if (2 * m <= M && 2 * n <= N) half += term;
    }
  }
  if (tail) *tail = std::abs(sum - half);
  return sum;
}

std::pair<int, int> navier_balanced_terms(double a, double b, int terms) {
  const double r = std::sqrt(a / b);
  return {std::max(1, static_cast<int>(std::lround(terms * r))), std::max(1, static_cast<int>(std::lround(terms / r)))};
}

std::array<double, 3> navier_static(double a, double b, double D, const std::vector<std::array<double, 3>>& forces,
                                    double x, double y, int terms, double* tail, const std::vector<PressurePatch>& patches,
                                    std::array<double, 3>* curvature, double* curvature_tail) {
  return navier_static(a, b, D, forces, x, y, terms, terms, tail, patches, curvature, curvature_tail);
}

std::array<double, 3> navier_static(double a, double b, double D, const std::vector<std::array<double, 3>>& forces,
                                    double x, double y, int M, int N, double* tail,
                                    const std::vector<PressurePatch>& patches, std::array<double, 3>* curvature,
                                    double* curvature_tail) {
  // w = sum_mn W_mn sin(m pi x/a) sin(n pi y/b), W_mn = P_mn / (D pi^4 q^2), P_mn the load's
  // coefficient: 4 F sin sin / (a b) for a point force, the patch's closed form (header).
  std::array<double, 3> out{0, 0, 0}, half{0, 0, 0}, curv{0, 0, 0}, curv_half{0, 0, 0};
  std::vector<double> sx(M + 1), cx(M + 1), sy(N + 1), cy(N + 1);
  for (int m = 1; m <= M; ++m) {
    sx[m] = std::sin(m * pi * x / a);
    cx[m] = std::cos(m * pi * x / a);
  }
  for (int n = 1; n <= N; ++n) {
    sy[n] = std::sin(n * pi * y / b);
    cy[n] = std::cos(n * pi * y / b);
  }
  // Each load as a product of an x factor (by m) and a y factor (by n).
  struct Separable {
    std::vector<double> fx, fy;
  };
  std::vector<Separable> loads;
  for (const auto& f : forces) {
    Separable l{std::vector<double>(M + 1), std::vector<double>(N + 1)};
    for (int m = 1; m <= M; ++m) l.fx[m] = 4.0 * f[2] * std::sin(m * pi * f[0] / a) / (a * b);
    for (int n = 1; n <= N; ++n) l.fy[n] = std::sin(n * pi * f[1] / b);
    loads.push_back(std::move(l));
  }
  for (const auto& p : patches) {
    Separable l{std::vector<double>(M + 1), std::vector<double>(N + 1)};
    for (int m = 1; m <= M; ++m)
      l.fx[m] = 4.0 * p.p / (m * pi) * (std::cos(m * pi * p.x1 / a) - std::cos(m * pi * p.x2 / a));
    for (int n = 1; n <= N; ++n) l.fy[n] = (std::cos(n * pi * p.y1 / b) - std::cos(n * pi * p.y2 / b)) / (n * pi);
    loads.push_back(std::move(l));
  }
  for (const auto& l : loads)
    for (int m = 1; m <= M; ++m)
      for (int n = 1; n <= N; ++n) {
        const double q = std::pow(m / a, 2) + std::pow(n / b, 2);
        const double W = l.fx[m] * l.fy[n] / (D * std::pow(pi, 4) * q * q);
        const double km = m * pi / a, kn = n * pi / b;
        const std::array<double, 3> t = {W * sx[m] * sy[n], W * km * cx[m] * sy[n], W * kn * sx[m] * cy[n]};
        const std::array<double, 3> c = {-W * km * km * sx[m] * sy[n], -W * kn * kn * sx[m] * sy[n], W * km * kn * cx[m] * cy[n]};
        const bool in_half = 2 * m <= M && 2 * n <= N;
        for (int k = 0; k < 3; ++k) {
          out[k] += t[k];
          curv[k] += c[k];
          if (in_half) {
            half[k] += t[k];
            curv_half[k] += c[k];
          }
        }
      }
  if (tail) *tail = std::abs(out[0] - half[0]);
  if (curvature) *curvature = curv;
  if (curvature_tail)
    *curvature_tail = std::max({std::abs(curv[0] - curv_half[0]), std::abs(curv[1] - curv_half[1]), std::abs(curv[2] - curv_half[2])});
  return out;
}

std::vector<double> mindlin_ss_frequencies(double a, double b, double h, double E, double nu, double G, double kappa,
                                           double rho, int k) {
  std::vector<double> out;
  if (k <= 0) return out;
  const double D = E * h * h * h / (12.0 * (1.0 - nu * nu));
  const double kGh = kappa * G * h, J = rho * h * h * h / 12.0;
  auto branches = [&](int m, int n, std::vector<double>& sink) {
    const double al = m * pi / a, be = n * pi / b;
    if (m == 0 && n == 0) return;
    if (m == 0 || n == 0) {
      // Pure thickness-shear: w = 0, only the rotation along the non-zero wave survives.
      const double q = (m == 0) ? be : al;
      sink.push_back(std::sqrt((D * (1.0 - nu) / 2.0 * q * q + kGh) / J));
      return;
    }
    Eigen::Matrix3d K, M = Eigen::Matrix3d::Zero();
    K << kGh * (al * al + be * be), kGh * al, kGh * be,
        kGh * al, D * (al * al + (1 - nu) / 2 * be * be) + kGh, D * (1 + nu) / 2 * al * be,
        kGh * be, D * (1 + nu) / 2 * al * be, D * (be * be + (1 - nu) / 2 * al * al) + kGh;
    M(0, 0) = rho * h;
    M(1, 1) = M(2, 2) = J;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> es(K, M);
    if (es.info() != Eigen::Success) throw std::runtime_error("Mindlin 3x3 eigenproblem failed");
    for (int i = 0; i < 3; ++i) sink.push_back(std::sqrt(std::max(es.eigenvalues()[i], 0.0)));
  };
  // Enumerate a box of (m, n); confirm that every mode on the box's outer rim lies above the
  // k-th frequency found (all branches grow with m and n), else enlarge the box.
  for (int N = k + 2;; N *= 2) {
    std::vector<double> inside, rim;
    for (int m = 0; m <= N; ++m)
      for (int n = 0; n <= N; ++n) branches(m, n, (m == N || n == N) ? rim : inside);
    std::sort(inside.begin(), inside.end());
    if (static_cast<int>(inside.size()) >= k && *std::min_element(rim.begin(), rim.end()) > inside[k - 1]) {
      inside.resize(k);
      return inside;
    }
    if (N > 100000) throw std::runtime_error("Mindlin enumeration did not close");
  }
}

LineSystem levy_strip(double a, double b, double D, double nu, double rho_h, EndSprings y0, EndSprings yb, int m) {
  // Strip m: w = W(y) sin(m pi x / a). Dimensionless y_bar = y / b, W_bar = W / b,
  // lambda_bar = rho h omega^2 b^4 / D, k_bar = m pi b / a. State [W, W', F_w, F_theta] with
  // F_theta = W'' - nu k^2 W (= -M_y b / D) and F_w = -W''' + (2 - nu) k^2 W' (= V_y b^2 / D).
  const double lam_to_bar = rho_h * std::pow(b, 4) / D;
  const double kb = m * pi * b / a, k2 = kb * kb;
  LineSystem sys;
  sys.m = 2;
  auto sc = [](double v, double f) { return std::isinf(v) ? kInf : v * f; };
  sys.left_spring = {sc(y0.translational, std::pow(b, 3) / D), sc(y0.rotational, b / D)};
  sys.right_spring = {sc(yb.translational, std::pow(b, 3) / D), sc(yb.rotational, b / D)};
  sys.state_matrix = [k2, nu, lam_to_bar](double lambda) {
    const double lb = lambda * lam_to_bar;
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
    A(0, 1) = 1.0;
    A(1, 0) = nu * k2; A(1, 3) = 1.0;
    A(2, 0) = k2 * k2 * (1 - nu * nu) - lb; A(2, 3) = -nu * k2;
    A(3, 1) = 2.0 * (1 - nu) * k2; A(3, 2) = -1.0;
    return A;
  };
  sys.max_wavenumber = [k2, lam_to_bar](double lambda) {
    return std::sqrt(k2 + std::sqrt(std::abs(lambda) * lam_to_bar)) + 1.0;
  };
  return sys;
}

int levy_strip_count(double a, double D, double nu, double rho_h, double lambda) {
  int strips = 0;
  while ((1 - nu * nu) * D * std::pow((strips + 1) * pi / a, 4) < rho_h * lambda) ++strips;
  return strips;
}

Frequencies levy_frequencies(double a, double b, double D, double nu, double rho_h, EndSprings y0, EndSprings yb,
                             int k) {
  Frequencies result;
  if (k <= 0) return result;
  SliceStats st;
  // Strips whose (1 - nu^2) D k^4 exceeds rho h omega^2 have no mode below omega.
  auto count = [&](double lambda) {
    int total = 0;
    for (int m = 1; m <= levy_strip_count(a, D, nu, rho_h, lambda); ++m) {
      const AssembledLine asmb = assemble(levy_strip(a, b, D, nu, rho_h, y0, yb, m), lambda);
      st.max_unknowns = std::max<long>(st.max_unknowns, asmb.K.free_dofs());
      total += asmb.K.inertia().negative;
    }
    return total;
  };
  const double hint = D / (rho_h * std::pow(std::min(a, b), 4));
  for (double lam : slice_spectrum(count, k, 0.0, hint, 1e-13, &st)) result.omega_rad_s.push_back(std::sqrt(lam));
  result.count_evaluations = st.count_evaluations;
  result.unknowns = st.max_unknowns;
  return result;
}

std::vector<NavierMode> navier_modes(double a, double b, double D, double rho_h, int k) {
  std::vector<NavierMode> out;
  if (k <= 0) return out;
  const double c = pi * pi * std::sqrt(D / rho_h);
  for (int m = 1; m <= k; ++m)
    for (int n = 1; n <= k; ++n) out.push_back({c * (std::pow(m / a, 2) + std::pow(n / b, 2)), m, n});
  std::stable_sort(out.begin(), out.end(), [](const NavierMode& x, const NavierMode& y) { return x.omega < y.omega; });
  out.resize(static_cast<std::size_t>(k));
  return out;
}

}  // namespace modalbench::exact
