#include "modalbench/exact.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "modalbench/line_dsm.hpp"
#include "modalbench/timer.hpp"

namespace modalbench::exact {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double pi = std::numbers::pi;

/// Dimensionless Timoshenko line (xi = x / L, w_bar = w / L, forces scaled by EI / L^2, EI / L).
struct BendingLine {
  double s;       // EI / (kGA L^2)
  double r;       // rhoI / (rhoA L^2)
  double lam_to_Omega2;  // rhoA L^4 / EI: Omega^2 = lambda * this
  LineSystem sys;

  BendingLine(const BeamBending& b, EndSprings left, EndSprings right) {
    if (!(b.EI > 0 && b.rhoA > 0 && b.L > 0 && b.kGA > 0 && b.rhoI >= 0))
      throw std::invalid_argument("beam properties must be positive");
    s = std::isinf(b.kGA) ? 0.0 : b.EI / (b.kGA * b.L * b.L);
    r = b.rhoI / (b.rhoA * b.L * b.L);
    lam_to_Omega2 = b.rhoA * std::pow(b.L, 4) / b.EI;
    const double kt = std::pow(b.L, 3) / b.EI, kr = b.L / b.EI;
    sys.m = 2;
    sys.left_spring = {scaled(left.translational, kt), scaled(left.rotational, kr)};
    sys.right_spring = {scaled(right.translational, kt), scaled(right.rotational, kr)};
    const double ss = s, rr = r, c = lam_to_Omega2;
    sys.state_matrix = [ss, rr, c](double lambda) {
      const double O2 = lambda * c;
      Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4, 4);
      // y = [w, phi, Q, M]
      A(0, 1) = 1.0; A(0, 2) = ss;
      A(1, 3) = 1.0;
      A(2, 0) = -O2;
      A(3, 1) = -rr * O2; A(3, 2) = -1.0;
      return A;
    };
    sys.max_wavenumber = [ss, rr, c](double lambda) {
      const double O2 = std::abs(lambda) * c;
      return std::sqrt(O2 * (ss + rr) + std::sqrt(O2));
    };
  }
  static double scaled(double k, double factor) { return std::isinf(k) ? kInf : k * factor; }
};

/// Dimensionless bar (xi = x / L, q unscaled, forces scaled by S / L).
struct BarLine {
  double lam_to_Omega2;
  LineSystem sys;
  BarLine(const Bar& b, double k_left, double k_right) {
    if (!(b.S > 0 && b.mu > 0 && b.L > 0)) throw std::invalid_argument("bar properties must be positive");
    lam_to_Omega2 = b.mu * b.L * b.L / b.S;
    const double f = b.L / b.S;
    sys.m = 1;
    sys.left_spring = {std::isinf(k_left) ? kInf : k_left * f};
    sys.right_spring = {std::isinf(k_right) ? kInf : k_right * f};
    const double c = lam_to_Omega2;
    sys.state_matrix = [c](double lambda) {
      Eigen::MatrixXd A(2, 2);
      A << 0.0, 1.0, -lambda * c, 0.0;
      return A;
    };
    sys.max_wavenumber = [c](double lambda) { return std::sqrt(std::abs(lambda) * c); };
  }
};

Frequencies to_frequencies(const LineSpectrum& spec, const SliceStats& st) {
  Frequencies f;
  f.rigid = spec.rigid;
  f.count_evaluations = st.count_evaluations;
  for (double lam : spec.lambdas) f.omega_rad_s.push_back(std::sqrt(std::max(lam, 0.0)));
  return f;
}

bool bending_restrained(EndSprings l, EndSprings r) {
  const bool some_t = l.translational > 0 || r.translational > 0;
  const bool some_r = l.rotational > 0 || r.rotational > 0;
  return (some_t && some_r) || (l.translational > 0 && r.translational > 0);
}

}  // namespace

Frequencies beam_bending_frequencies(const BeamBending& beam, EndSprings left, EndSprings right, int k) {
  BendingLine line(beam, left, right);
  SliceStats st;
  // Scale: Omega = 1.
  const auto spec = lowest_eigenvalues(line.sys, k, 1.0 / line.lam_to_Omega2, &st);
  return to_frequencies(spec, st);
}

Frequencies bar_frequencies(const Bar& bar, double k_left, double k_right, int k) {
  BarLine line(bar, k_left, k_right);
  SliceStats st;
  const auto spec = lowest_eigenvalues(line.sys, k, 1.0 / line.lam_to_Omega2, &st);
  return to_frequencies(spec, st);
}

std::vector<BendingResponse> beam_static(const BeamBending& beam, EndSprings left, EndSprings right,
                                         const std::vector<LineLoad>& loads, const std::vector<double>& probes,
                                         double moment_sign) {
  if (!bending_restrained(left, right))
    throw std::runtime_error(
        "mechanism: the end supports do not restrain rigid translation and rotation in bending "
        "(need translational springs at both ends, or a translational and a rotational one)");
  BendingLine line(beam, left, right);
  const double L = beam.L;
  for (auto& p : loads) line.sys.nodes_at.push_back(p.x / L);
  for (double x : probes) line.sys.nodes_at.push_back(x / L);
  AssembledLine asmb = assemble(line.sys, 0.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(asmb.K.nodes() * 2);
  for (auto& p : loads) {
    const int n = asmb.node_at(p.x / L);
    f[2 * n] += p.force * L * L / beam.EI;
    f[2 * n + 1] += moment_sign * p.moment * L / beam.EI;
  }
  const Eigen::VectorXd d = asmb.K.solve(f);
  std::vector<BendingResponse> out;
  for (double x : probes) {
    const int n = asmb.node_at(x / L);
    out.push_back({d[2 * n] * L, moment_sign * d[2 * n + 1]});
  }
  return out;
}

std::vector<double> bar_static(const Bar& bar, double k_left, double k_right, const std::vector<LineLoad>& loads,
                               const std::vector<double>& probes) {
  if (!(k_left > 0 || k_right > 0))
    throw std::runtime_error("mechanism: neither end restrains the bar (axial or torsional rigid motion)");
  BarLine line(bar, k_left, k_right);
  for (auto& p : loads) line.sys.nodes_at.push_back(p.x / bar.L);
  for (double x : probes) line.sys.nodes_at.push_back(x / bar.L);
  AssembledLine asmb = assemble(line.sys, 0.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(asmb.K.nodes());
  for (auto& p : loads) f[asmb.node_at(p.x / bar.L)] += p.force * bar.L / bar.S;
  const Eigen::VectorXd d = asmb.K.solve(f);
  std::vector<double> out;
  for (double x : probes) out.push_back(d[asmb.node_at(x / bar.L)]);
  return out;
}

double beam_receptance(const BeamBending& beam, EndSprings left, EndSprings right, double excite, double observe,
                       double omega) {
  BendingLine line(beam, left, right);
  line.sys.nodes_at = {excite / beam.L, observe / beam.L};
  AssembledLine asmb = assemble(line.sys, omega * omega);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(asmb.K.nodes() * 2);
  f[2 * asmb.node_at(excite / beam.L)] = beam.L * beam.L / beam.EI;
  const Eigen::VectorXd d = asmb.K.solve(f);
  return d[2 * asmb.node_at(observe / beam.L)] * beam.L;
}

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
  // w = sum phi_mn(xe, ye) phi_mn(xo, yo) / (M (omega_mn^2 (1 + i eta) - omega^2)),
  // phi_mn = sin(m pi x / a) sin(n pi y / b), modal mass M = rho h a b / 4.
  std::vector<double> sxe(terms + 1), sxo(terms + 1), sye(terms + 1), syo(terms + 1);
  for (int m = 1; m <= terms; ++m) {
    sxe[m] = std::sin(m * pi * xe / a);
    sxo[m] = std::sin(m * pi * xo / a);
    sye[m] = std::sin(m * pi * ye / b);
    syo[m] = std::sin(m * pi * yo / b);
  }
  const double M = rho_h * a * b / 4.0, c = pi * pi * pi * pi * D / rho_h;
  std::complex<double> sum = 0, half = 0;
  for (int m = 1; m <= terms; ++m)
    for (int n = 1; n <= terms; ++n) {
      const double q = std::pow(m / a, 2) + std::pow(n / b, 2);
      const double w2 = c * q * q;
      const std::complex<double> term = sxe[m] * sye[n] * sxo[m] * syo[n] / (M * (w2 * std::complex<double>(1, eta) - omega * omega));
      sum += term;
      if (2 * m <= terms && 2 * n <= terms) half += term;
    }
  if (tail) *tail = std::abs(sum - half);
  return sum;
}

std::array<double, 3> navier_static(double a, double b, double D, const std::vector<std::array<double, 3>>& forces,
                                    double x, double y, int terms, double* tail) {
  // w = sum_mn W_mn sin(m pi x/a) sin(n pi y/b), W_mn = 4 F sin sin / (a b D pi^4 q^2).
  std::array<double, 3> out{0, 0, 0}, half{0, 0, 0};
  std::vector<double> sx(terms + 1), cx(terms + 1), sy(terms + 1), cy(terms + 1);
  for (int m = 1; m <= terms; ++m) {
    sx[m] = std::sin(m * pi * x / a);
    cx[m] = std::cos(m * pi * x / a);
    sy[m] = std::sin(m * pi * y / b);
    cy[m] = std::cos(m * pi * y / b);
  }
  for (const auto& f : forces) {
    std::vector<double> sfx(terms + 1), sfy(terms + 1);
    for (int m = 1; m <= terms; ++m) {
      sfx[m] = std::sin(m * pi * f[0] / a);
      sfy[m] = std::sin(m * pi * f[1] / b);
    }
    for (int m = 1; m <= terms; ++m)
      for (int n = 1; n <= terms; ++n) {
        const double q = std::pow(m / a, 2) + std::pow(n / b, 2);
        const double W = 4.0 * f[2] * sfx[m] * sfy[n] / (a * b * D * std::pow(pi, 4) * q * q);
        const std::array<double, 3> t = {W * sx[m] * sy[n], W * (m * pi / a) * cx[m] * sy[n], W * (n * pi / b) * sx[m] * cy[n]};
        for (int k = 0; k < 3; ++k) {
          out[k] += t[k];
          if (2 * m <= terms && 2 * n <= terms) half[k] += t[k];
        }
      }
  }
  if (tail) *tail = std::abs(out[0] - half[0]);
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

Frequencies levy_frequencies(double a, double b, double D, double nu, double rho_h, EndSprings y0, EndSprings yb,
                             int k) {
  Frequencies result;
  if (k <= 0) return result;
  // Strip m: w = W(y) sin(m pi x / a). Dimensionless y_bar = y / b, W_bar = W / b,
  // lambda_bar = rho h omega^2 b^4 / D, k_bar = m pi b / a. State [W, W', F_w, F_theta] with
  // F_theta = W'' - nu k^2 W (= -M_y b / D) and F_w = -W''' + (2 - nu) k^2 W' (= V_y b^2 / D).
  const double lam_to_bar = rho_h * std::pow(b, 4) / D;
  auto strip = [&](int m) {
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
  };
  // Strips whose (1 - nu^2) D k^4 exceeds rho h omega^2 have no mode below omega.
  auto count = [&](double lambda) {
    int total = 0;
    for (int m = 1;; ++m) {
      const double km = m * pi / a;
      if ((1 - nu * nu) * D * std::pow(km, 4) >= rho_h * lambda) break;
      total += count_below(strip(m), lambda);
    }
    return total;
  };
  SliceStats st;
  const double hint = D / (rho_h * std::pow(std::min(a, b), 4));
  for (double lam : slice_spectrum(count, k, 0.0, hint, 1e-13, &st)) result.omega_rad_s.push_back(std::sqrt(lam));
  result.count_evaluations = st.count_evaluations;
  return result;
}

BeamBending bending_xz(const Scene& s) {
  const Section sec = s.section();
  const auto& m = s.material;
  const bool eb = s.theory == Theory::EulerBernoulli;
  return {m.E * sec.Iy, eb ? kInf : m.kappa * m.G * sec.A, m.rho * sec.A, eb ? 0.0 : m.rho * sec.Iy, s.geometry.length};
}

BeamBending bending_xy(const Scene& s) {
  const Section sec = s.section();
  const auto& m = s.material;
  const bool eb = s.theory == Theory::EulerBernoulli;
  return {m.E * sec.Iz, eb ? kInf : m.kappa * m.G * sec.A, m.rho * sec.A, eb ? 0.0 : m.rho * sec.Iz, s.geometry.length};
}

namespace {

bool simply_supported(const Support& e) { return std::isinf(e.translational) && e.rotational == 0.0; }
EndSprings bend(const Support& s) { return {s.translational, s.rotational}; }

enum class PlateMethod { None, Navier, Levy, LevyTransposed, Mindlin };
PlateMethod plate_method(const Scene& s, std::string& why) {
  const bool ssx = simply_supported(s.x0) && simply_supported(s.xL);
  const bool ssy = simply_supported(s.y0) && simply_supported(s.yB);
  if (s.theory == Theory::Mindlin) {
    if (ssx && ssy) return PlateMethod::Mindlin;
    why = "exact Mindlin plate only for all edges simply supported";
    return PlateMethod::None;
  }
  if (ssx && ssy) return PlateMethod::Navier;
  if (ssx) return PlateMethod::Levy;
  if (ssy) return PlateMethod::LevyTransposed;
  why = "exact Kirchhoff plate needs one pair of opposite edges simply supported (Levy)";
  return PlateMethod::None;
}

}  // namespace

Capability ExactSolver::supports(const Scene& s) const {
  Capability c;
  if (s.is_beam()) {
    c.modes = c.statics = c.frf = true;
    return c;
  }
  std::string why;
  const PlateMethod pm = plate_method(s, why);
  c.modes = pm != PlateMethod::None;
  c.statics = c.frf = pm == PlateMethod::Navier;
  if (!c.statics) c.reason = (why.empty() ? "" : why + "; ") + "exact plate statics and FRF only for a simply supported Kirchhoff plate (Navier)";
  return c;
}

void ExactSolver::do_solve(const Scene& s, const Discretization& mesh, const Options&, Result& r) const {
  if (!mesh.counts.empty())
    throw InputError("command line", "--mesh", "the exact back-end has no mesh (got '" + mesh.spec() + "')");
  Timer timer;
  const int k = s.request.modes;
  r.summary.dofs = 0;
  std::vector<std::pair<double, ModeFamily>> modes;
  auto add = [&](const std::vector<double>& w, int rigid, ModeFamily fam) {
    for (std::size_t i = 0; i < w.size(); ++i)
      modes.emplace_back(w[i], static_cast<int>(i) < rigid ? ModeFamily::Rigid : fam);
  };
  if (s.is_beam()) {
    const Section sec = s.section();
    const auto& m = s.material;
    r.summary.method = fmt::format("exact {} beam: dynamic stiffness + Wittrick-Williams count",
                                   to_string(s.theory));
    if (k > 0) {
      auto fxz = beam_bending_frequencies(bending_xz(s), bend(s.x0), bend(s.xL), k);
      add(fxz.omega_rad_s, fxz.rigid, ModeFamily::BendingXZ);
      r.summary.iterations += fxz.count_evaluations;
      if (s.physics != Physics::Bending) {
        auto fa = bar_frequencies({m.E * sec.A, m.rho * sec.A, s.geometry.length}, s.x0.axial, s.xL.axial, k);
        add(fa.omega_rad_s, fa.rigid, ModeFamily::Axial);
        r.summary.iterations += fa.count_evaluations;
      }
      if (s.physics == Physics::Spatial) {
        auto fxy = beam_bending_frequencies(bending_xy(s), bend(s.x0), bend(s.xL), k);
        add(fxy.omega_rad_s, fxy.rigid, ModeFamily::BendingXY);
        auto ft = bar_frequencies({m.G * sec.J, m.rho * sec.Ip, s.geometry.length}, s.x0.torsional,
                                  s.xL.torsional, k);
        add(ft.omega_rad_s, ft.rigid, ModeFamily::Torsion);
        r.summary.iterations += fxy.count_evaluations + ft.count_evaluations;
      }
      r.summary.timings_s.emplace_back("frequencies", timer.lap());
    }
    if (!s.request.probes.empty()) {
      std::vector<double> xs;
      for (auto& p : s.request.probes) xs.push_back(p[0]);
      std::vector<Deflection> defl(xs.size());
      for (std::size_t i = 0; i < xs.size(); ++i) defl[i].position = {xs[i], 0.0};
      try {
        std::vector<LineLoad> lz, la, ly, lt;
        for (auto& p : s.loads) {
          lz.push_back({p.x, p.Fz, p.My});
          la.push_back({p.x, p.Fx, 0});
          ly.push_back({p.x, p.Fy, p.Mz});
          lt.push_back({p.x, p.Mx, 0});
        }
        auto wz = beam_static(bending_xz(s), bend(s.x0), bend(s.xL), lz, xs, -1.0);
        for (std::size_t i = 0; i < xs.size(); ++i) {
          defl[i].w = wz[i].w;
          defl[i].theta_y = wz[i].theta;
        }
        if (s.physics != Physics::Bending) {
          auto u = bar_static({m.E * sec.A, m.rho * sec.A, s.geometry.length}, s.x0.axial, s.xL.axial, la, xs);
          for (std::size_t i = 0; i < xs.size(); ++i) defl[i].u = u[i];
        }
        if (s.physics == Physics::Spatial) {
          auto wy = beam_static(bending_xy(s), bend(s.x0), bend(s.xL), ly, xs, +1.0);
          auto t = bar_static({m.G * sec.J, m.rho * sec.Ip, s.geometry.length}, s.x0.torsional, s.xL.torsional,
                              lt, xs);
          for (std::size_t i = 0; i < xs.size(); ++i) {
            defl[i].v = wy[i].w;
            defl[i].theta_z = wy[i].theta;
            defl[i].theta_x = t[i];
          }
        }
        r.deflections = defl;
      } catch (const std::runtime_error& e) {
        r.summary.status = Status::InvalidInput;
        r.summary.message = s.source + ": supports: static solve impossible: " + e.what();
      }
      r.summary.timings_s.emplace_back("statics", timer.lap());
    }
    if (s.request.frf) {
      const auto& f = *s.request.frf;
      if (m.loss_factor > 0)
        r.summary.warnings.push_back("exact FRF is undamped: material.loss_factor is not applied");
      const BeamBending b = bending_xz(s);
      int skipped = 0;
      for (int i = 0; i < f.points; ++i) {
        const double w = f.omega_min + (f.omega_max - f.omega_min) * i / (f.points - 1);
        try {
          r.frf.push_back({w, beam_receptance(b, bend(s.x0), bend(s.xL), f.excite[0], f.observe[0], w)});
        } catch (const std::runtime_error&) {
          ++skipped;  // omega sits on a natural frequency (or 0 for a mechanism): no finite receptance
        }
      }
      if (skipped)
        r.summary.warnings.push_back(fmt::format("FRF: {} sample(s) on a natural frequency omitted", skipped));
      r.summary.timings_s.emplace_back("frf", timer.lap());
    }
  } else {
    std::string why;
    const PlateMethod pm = plate_method(s, why);
    const double a = s.geometry.length, b = s.geometry.width, h = s.geometry.height;
    const auto& m = s.material;
    const double D = s.plate_D(), rho_h = m.rho * h;
    if (k > 0) {
      if (pm == PlateMethod::None) throw std::runtime_error(why);
      switch (pm) {
        case PlateMethod::Navier:
          r.summary.method = "exact Kirchhoff plate, Navier (all edges simply supported)";
          add(navier_frequencies(a, b, D, rho_h, k), 0, ModeFamily::Plate);
          break;
        case PlateMethod::Mindlin:
          r.summary.method = "exact Mindlin plate (all edges simply supported), every branch";
          add(mindlin_ss_frequencies(a, b, h, m.E, m.nu, m.G, m.kappa, m.rho, k), 0, ModeFamily::Plate);
          break;
        case PlateMethod::Levy: {
          r.summary.method = "exact Kirchhoff plate, Levy (x-edges simply supported): dynamic stiffness + count";
          auto f = levy_frequencies(a, b, D, m.nu, rho_h, bend(s.y0), bend(s.yB), k);
          add(f.omega_rad_s, 0, ModeFamily::Plate);
          r.summary.iterations = f.count_evaluations;
          break;
        }
        case PlateMethod::LevyTransposed: {
          r.summary.method = "exact Kirchhoff plate, Levy (y-edges simply supported): dynamic stiffness + count";
          auto f = levy_frequencies(b, a, D, m.nu, rho_h, bend(s.x0), bend(s.xL), k);
          add(f.omega_rad_s, 0, ModeFamily::Plate);
          r.summary.iterations = f.count_evaluations;
          break;
        }
        case PlateMethod::None: break;
      }
      r.summary.timings_s.emplace_back("frequencies", timer.lap());
    }
    if (pm == PlateMethod::Navier) {
      // Truncations: statics to m, n <= 2000, FRF to m, n <= 300; the tail estimates are checked
      // (FRF: against the static flexibility of the same pair, since |H| vanishes at anti-resonances).
      double worst_tail = 0;
      if (!s.request.probes.empty()) {
        std::vector<std::array<double, 3>> forces;
        for (const auto& p : s.loads) forces.push_back({p.x, p.y, p.Fz});
        double scale = 0;
        for (const auto& p : s.request.probes) {
          double tail = 0;
          const auto w = navier_static(a, b, D, forces, p[0], p[1], 2000, &tail);
          Deflection d;
          d.position = p;
          d.w = w[0];
          d.theta_x = w[2];   // rotation about x: +dw/dy
          d.theta_y = -w[1];  // rotation about y: -dw/dx
          r.deflections.push_back(d);
          worst_tail = std::max(worst_tail, tail);
          scale = std::max(scale, std::abs(w[0]));
        }
        if (scale > 0 && worst_tail > 1e-5 * scale)
          r.summary.warnings.push_back(fmt::format("Navier static series truncated at 2000 x 2000 terms: estimated relative error {:.1e}",
                                                   worst_tail / scale));
        r.summary.max_residual = std::max(r.summary.max_residual, scale > 0 ? worst_tail / scale : 0.0);
        r.summary.timings_s.emplace_back("statics", timer.lap());
      }
      if (s.request.frf) {
        const auto& f = *s.request.frf;
        double worst = 0;
        const double flex = std::abs(navier_receptance(a, b, D, rho_h, 0.0, f.excite[0], f.excite[1], f.observe[0],
                                                       f.observe[1], 0.0, 300));
        for (int i = 0; i < f.points; ++i) {
          const double w = f.omega_min + (f.omega_max - f.omega_min) * i / (f.points - 1);
          double tail = 0;
          const auto rec = navier_receptance(a, b, D, rho_h, m.loss_factor, f.excite[0], f.excite[1], f.observe[0],
                                             f.observe[1], w, 300, &tail);
          if (!std::isfinite(std::abs(rec))) continue;  // exactly on an undamped resonance
          r.frf.push_back({w, rec});
          worst = std::max(worst, tail);
        }
        if (flex > 0 && worst > 1e-3 * flex)
          r.summary.warnings.push_back(fmt::format(
              "Navier FRF series truncated at 300 x 300 terms: estimated error up to {:.1e} of the static flexibility",
              worst / flex));
        r.summary.timings_s.emplace_back("frf", timer.lap());
      }
    }
  }
  std::stable_sort(modes.begin(), modes.end(), [](auto& x, auto& y) { return x.first < y.first; });
  if (static_cast<int>(modes.size()) > k) modes.resize(k);
  for (auto& [w, fam] : modes) {
    r.frequencies_rad_s.push_back(w);
    r.mode_families.push_back(fam);
  }
}

}  // namespace modalbench::exact
