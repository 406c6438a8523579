// The paper's own case reproduced formula by formula (Lasecka, Eqs. (7)-(23)), each step checked
// against the assembled FE system (the condensed eigenproblem and direct solves in binary128).
#define BOOST_TEST_MODULE difference_eq_lasecka
#include <boost/test/unit_test.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

#include "helpers.hpp"
#include "modalbench/difference_eq/assembled.hpp"
#include "modalbench/difference_eq/lasecka.hpp"
#include "modalbench/difference_eq/statics.hpp"

using namespace modalbench::difference_eq;
using deq_test::quad;

namespace {

// Scene values of scenes/lasecka_elastic_beam.toml: EI = 1.3333e7 N m^2, L = 4 m,
// K0 = 40, KR = 10, Kf = 5.
constexpr double EI = 2.0e11 * 0.1 * 0.2 * 0.2 * 0.2 / 12.0, L = 4.0;
constexpr double kappa0 = 40.0 * EI / (L * L * L), kappaR = 10.0 * EI / (L * L * L), chi0 = 5.0 * EI / L;

// The clamped-pinned condensed stiffness S (w DOFs only, rotations eliminated), units EI/a^3 = 1.
Eigen::MatrixXd condensed_clamped_pinned(long R) {
  RegularBeam b{1.0, 1.0, static_cast<double>(R), R, kInf, kInf, kInf, 0.0};
  Eigen::MatrixXd K, M;
  std::vector<long> dofs;
  deq_test::dense_KM(b, true, K, M, dofs);
  std::vector<int> wi, pi;
  for (std::size_t i = 0; i < dofs.size(); ++i) (dofs[i] % 2 == 0 ? wi : pi).push_back(static_cast<int>(i));
  Eigen::MatrixXd Kww(wi.size(), wi.size()), Kwp(wi.size(), pi.size()), Kpp(pi.size(), pi.size());
  for (std::size_t i = 0; i < wi.size(); ++i) {
    for (std::size_t j = 0; j < wi.size(); ++j) Kww(i, j) = K(wi[i], wi[j]);
    for (std::size_t j = 0; j < pi.size(); ++j) Kwp(i, j) = K(wi[i], pi[j]);
  }
  for (std::size_t i = 0; i < pi.size(); ++i)
    for (std::size_t j = 0; j < pi.size(); ++j) Kpp(i, j) = K(pi[i], pi[j]);
  return Kww - Kwp * Kpp.ldlt().solve(Kwp.transpose());
}

std::vector<double> loads_P(long R) {
  std::vector<double> P(R + 1, 0.0);
  P[R / 4] = -10000.0;
  P[R / 2] = -20000.0;
  P[3 * R / 4] = 5000.0;
  P[1] += 1200.0;
  P[0] = 700.0;      // on the supports too: (19) carries them
  P[R] = -300.0;
  return P;
}

RegularBeam elastic(long R) { return RegularBeam{EI, 0.0, L, R, kappa0, chi0, kappaR, 0.0}; }

std::vector<NodalLoad> nodal(const std::vector<double>& P) {
  std::vector<NodalLoad> l;
  for (std::size_t r = 0; r < P.size(); ++r)
    if (P[r] != 0.0) l.push_back({static_cast<long>(r), P[r], 0.0});
  return l;
}

}  // namespace

// alpha_k^2 (8) from the characteristic equation equal B x the eigenvalues of the condensed
// stiffness (B = a^3 / 24 EI = 1/24 here); the equation as printed is not zero there (erratum:
// the factor (cosh mu - cos nu) belongs to the whole left side).
BOOST_AUTO_TEST_CASE(eigenvalues_from_the_characteristic_equation) {
  for (long R : {2L, 3L, 8L, 31L, 100L}) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(condensed_clamped_pinned(R));
    const std::vector<double> a2 = lasecka::eigenvalues(R);
    BOOST_REQUIRE(a2.size() == static_cast<std::size_t>(R - 1));
    double printed = 0;
    for (long k = 0; k < R - 1; ++k) {
      BOOST_TEST(std::abs(a2[k] - es.eigenvalues()[k] / 24.0) <= 1e-12 * (1.0 + a2[k]), "R=" << R << " k=" << k + 1);
      BOOST_TEST(std::abs(lasecka::characteristic(R, a2[k])) < 1e-12);
      printed = std::max(printed, std::abs(lasecka::characteristic_printed(R, a2[k])));
    }
    if (R > 2) BOOST_TEST(printed > 1e-3, "the printed characteristic equation vanishes at the roots (R=" << R << ")");
  }
}

// W_{r,k} as printed satisfies (8) at the interior nodes and the boundary conditions (9)
// (W_0 = W_R = 0, Phi_0 = 0, moment-free at r = R), and is the eigenvector of the condensed
// stiffness; Phi_{r,k} as printed is the rotation field that goes with it; after normalising,
// sum_r W_rk W_rj = delta_kj.
BOOST_AUTO_TEST_CASE(eigenfunctions_as_printed) {
  const long R = 9;
  const Eigen::MatrixXd S = condensed_clamped_pinned(R);
  const std::vector<double> a2 = lasecka::eigenvalues(R);
  std::vector<std::vector<double>> Wn;
  for (double al : a2) {
    const auto ef = lasecka::eigenfunction(R, al);
    auto W = [&](long r) { return ef.W[r + 1]; };
    auto Phi = [&](long r) { return ef.Phi[r + 1]; };
    double scale = 0;
    for (long r = 0; r <= R; ++r) scale = std::max(scale, std::abs(W(r)));
    BOOST_TEST(std::abs(W(0)) < 1e-13 * scale);
    BOOST_TEST(std::abs(W(R)) < 1e-13 * scale);
    BOOST_TEST(std::abs(Phi(0)) < 1e-13 * scale);
    for (long r = 1; r < R; ++r) {  // (8): Delta^4 W - 4 alpha^2 (Delta^2 + 6) W = 0 (W_{-1}, W_{R+1} extended)
      const double d4 = (r + 2 <= R + 1 ? W(r + 2) : 0.0) - 4 * W(r + 1) + 6 * W(r) - 4 * W(r - 1) +
                        (r - 2 >= -1 ? W(r - 2) : 0.0);
      const double d2p6 = W(r + 1) + W(r - 1) + 4 * W(r);
      if (r >= 1 && r + 2 <= R + 1 && r - 2 >= -1) BOOST_TEST(std::abs(d4 - 4 * al * d2p6) < 1e-11 * scale);
    }
    // S W = (alpha^2 / B) W with B = 1/24.
    Eigen::VectorXd v(R - 1);
    for (long r = 1; r < R; ++r) v[r - 1] = W(r);
    BOOST_TEST((S * v - 24.0 * al * v).norm() < 1e-11 * 24.0 * al * v.norm());
    // Equilibrium of the moments at every free rotation with m_r = 0 (first of (3)):
    // 6(W_{r-1} - W_r) + 2(Phi_{r-1} + 2 Phi_r) + 6(W_r - W_{r+1}) + 2(2 Phi_r + Phi_{r+1}) = 0, r < R;
    // at r = R only the left element: 6(W_{R-1} - W_R) + 2(Phi_{R-1} + 2 Phi_R) = 0.
    for (long r = 1; r < R; ++r)
      BOOST_TEST(std::abs(6 * (W(r - 1) - W(r + 1)) + 2 * (Phi(r - 1) + 4 * Phi(r) + Phi(r + 1))) < 1e-11 * scale);
    BOOST_TEST(std::abs(6 * (W(R - 1) - W(R)) + 2 * (Phi(R - 1) + 2 * Phi(R))) < 1e-11 * scale);
    double n = 0;
    for (long r = 0; r <= R; ++r) n += W(r) * W(r);
    std::vector<double> w(R + 1);
    for (long r = 0; r <= R; ++r) w[r] = W(r) / std::sqrt(n);
    Wn.push_back(w);
  }
  for (std::size_t k = 0; k < Wn.size(); ++k)
    for (std::size_t j = 0; j < Wn.size(); ++j) {
      double s = 0;
      for (long r = 0; r <= R; ++r) s += Wn[k][r] * Wn[j][r];
      BOOST_TEST(std::abs(s - (k == j ? 1.0 : 0.0)) < 1e-12);
    }
}

// The whole chain of the paper for the elastically supported beam of Fig. 5 (scene
// lasecka_elastic_beam: K0 = 40, Kf = 5, KR = 10), every step against the assembled FE system.
BOOST_AUTO_TEST_CASE(elastic_supports_step_by_step) {
  for (long R : {4L, 16L, 64L, 200L, 1000L}) {
    lasecka::Input in;
    in.R = R;
    in.EI = EI;
    in.L = L;
    in.P = loads_P(R);
    in.kappa0 = kappa0;
    in.chi0 = chi0;
    in.kappaR = kappaR;
    const lasecka::Output out = lasecka::solve(in);
    const double a = L / static_cast<double>(R);

    // (7): rigid supports (clamped-pinned) against the assembled solve.
    std::vector<quad> wq, sq;
    RegularBeam cp{EI, 0.0, L, R, kInf, kInf, kInf, 0.0};
    assembled::static_solve<quad>(cp, nodal(in.P), wq, sq);
    BOOST_TEST(deq_test::rel_max_error(out.w_rigid, wq) < 1e-10, "R=" << R);

    // (19): reactions of the rigid-support problem (force of the beam on the support) =
    // -(support action of the assembled solution); f0 = F0 / a.
    const quad ke = quad(EI) / (quad(a) * quad(a) * quad(a));
    const quad r_w0 = ke * (quad(-12) * wq[1] + quad(6) * quad(a) * sq[1]) - quad(in.P[0]);
    const quad r_f0 = ke * (quad(-6) * wq[1] + quad(2) * quad(a) * sq[1]);  // moment / a
    const quad r_wR = ke * (quad(-12) * wq[R - 1] - quad(6) * quad(a) * sq[R - 1] - quad(6) * quad(a) * sq[R]) - quad(in.P[R]);
    const double Ps = 20000.0;
    BOOST_TEST(std::abs(out.V0 + static_cast<double>(r_w0)) < 1e-10 * Ps);
    BOOST_TEST(std::abs(out.f0 + static_cast<double>(r_f0)) * a < 1e-10 * Ps * L);  // f0 = F0 / a: compare moments
    BOOST_TEST(std::abs(out.VR + static_cast<double>(r_wR)) < 1e-10 * Ps);

    // (21), (22) corrected, (15), and the final form (23) against the elastic-support solve.
    std::vector<quad> we, se;
    assembled::static_solve<quad>(elastic(R), nodal(in.P), we, se);
    BOOST_TEST(std::abs(out.V0s - kappa0 * static_cast<double>(we[0])) < 1e-10 * Ps);
    BOOST_TEST(std::abs(out.VRs - kappaR * static_cast<double>(we[R])) < 1e-10 * Ps);
    BOOST_TEST(std::abs(out.f0s * a - chi0 * static_cast<double>(se[0])) < 1e-10 * Ps * L);
    const double wsc = std::abs(static_cast<double>(we[R / 2]));
    BOOST_TEST(std::abs(out.v0 - static_cast<double>(we[0])) < 1e-10 * wsc);
    BOOST_TEST(std::abs(out.vR - static_cast<double>(we[R])) < 1e-10 * wsc);
    BOOST_TEST(std::abs(out.Theta0 - a * static_cast<double>(se[0])) < 1e-10 * wsc);
    // The printed (22) is not the solution of (20) (erratum: V_0 and V_R swapped in one term each).
    BOOST_TEST(std::abs(out.v0_printed - out.v0) > 1e-3 * wsc);
    BOOST_TEST(std::abs(out.vR_printed - out.vR) > 1e-3 * wsc);
    BOOST_TEST(deq_test::rel_max_error(out.w, we) < 1e-10, "(7)+(15)+(22), R=" << R);
    BOOST_TEST(deq_test::rel_max_error(out.w23, we) < 1e-10, "(23), R=" << R);
    std::vector<double> slope(R + 1);
    for (long r = 0; r <= R; ++r) slope[r] = out.phi[r] / a;
    BOOST_TEST(deq_test::rel_max_error(slope, se) < 1e-10, "rotations, R=" << R);

    // And the production path (piecewise cubic + 4x4) on the same beam.
    const StaticSolution st = solve_static(elastic(R), nodal(in.P));
    BOOST_TEST(deq_test::rel_max_error(st.w, we) < 1e-10);
  }
}
