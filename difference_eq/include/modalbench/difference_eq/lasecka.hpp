#pragma once
// The paper's own case, reproduced formula by formula: Lasecka, "Analiza ukladow pretowych z
// niejednorodnymi warunkami brzegowymi metoda funkcji wlasnych" (seed
// lasecka-difference-equation-beam-pl.txt).
//
// A beam of R elements (a = L / R, B = a^3 / (24 EI)) clamped at r = 0 and pinned at r = R
// (Fig. 4), loaded by nodal forces P_r only, then elastically supported (Fig. 5): kappa0,
// chi0 at r = 0 and kappaR at r = R.
//  * Eigenvalues alpha_k^2 (k = 1..R-1) of Delta^4 w - 4 alpha^2 (Delta^2 + 6) w = 0, Eq. (8),
//    from the characteristic equation, with cosh mu = 1 + a2 + sqrt(a2^2 + 6 a2),
//    cos nu = 1 + a2 - sqrt(a2^2 + 6 a2). Erratum (found here, checked against the FE
//    eigenproblem): the printed equation misplaces a bracket; the factor (cosh mu - cos nu)
//    multiplies the whole left side, i.e. the equation is
//      (cos nu + 2) sinh mu sin(nu R) cosh(mu R) - (cosh mu + 2) sin nu sinh(mu R) cos(nu R) = 0.
//    Roots are bracketed by an exact count (they are the lumped-mass clamped-pinned
//    frequencies, Omega = 12 alpha^2; see vibration.hpp) and polished on this equation.
//  * W_{r,k}, Phi_{r,k} as printed, evaluated in an algebraically identical form divided by
//    cosh(mu R) (the printed form cancels e^{mu R}-sized terms), normalised so that
//    sum_r W_{r,k} W_{r,j} = delta_kj (docs/sources.md, L2; Phi with the same factor).
//  * Expansion (7) (sum to R-1, L1), reactions (19), reactions of the elastic supports
//    (21), settlements (22) -- erratum (found here): in the printed v0 the term
//    3 K_R (V_R^(P) - f_0^(P)/R) must read 3 K_R (V_0^(P) - f_0^(P)/R), and in vR the term
//    3 K_0 (V_0^(P) + f_0^(P)/R) must read 3 K_0 (V_R^(P) + f_0^(P)/R) (both follow from (21)
//    with v = V*/kappa) -- then the settlement field (15).
//  * The final form (23) (with Omega_1..3), evaluated literally as a second route to w_r.
//
// Cost O(R^2): a reproduction and a cross-check, not the production path (see statics.hpp).

#include <vector>

namespace modalbench::difference_eq::lasecka {

struct Input {
  long R = 1;              ///< elements (>= 2)
  double EI = 0, L = 0;    ///< N m^2, m
  std::vector<double> P;   ///< nodal forces P_0..P_R (along +w), N
  double kappa0 = 0, chi0 = 0, kappaR = 0;  ///< N/m, N m/rad, N/m; finite, >= 0, not a mechanism
};

struct Output {
  std::vector<double> alpha2;        ///< alpha_k^2, k = 1..R-1
  std::vector<double> char_residual; ///< |corrected characteristic function| at each root, relative
  std::vector<double> printed_char;  ///< the printed (uncorrected) equation at each root, same scaling
  std::vector<double> w;             ///< (7) + (15) with (22): deflections w_0..w_R, m
  std::vector<double> phi;           ///< rotations phi_r = a psi_r from (7) (Phi) + (15), m
  std::vector<double> w23;           ///< the final form (23), m
  std::vector<double> w_rigid;       ///< (7) alone: rigid supports (clamped-pinned), m
  double V0 = 0, VR = 0, f0 = 0;     ///< (19): reactions of the rigid-support problem (force of beam on support)
  double V0s = 0, VRs = 0, f0s = 0;  ///< (21): reactions with elastic supports
  double v0 = 0, vR = 0, Theta0 = 0; ///< (22) corrected: settlements (Theta0 = a theta0)
  double v0_printed = 0, vR_printed = 0;  ///< (22) as printed, for the record
};

Output solve(const Input& in);

/// The clamped-pinned eigenvalues alpha_k^2, k = 1..R-1 (empty for R = 1).
std::vector<double> eigenvalues(long R);

/// The paper's W_{r,k} and Phi_{r,k} for one alpha^2, as printed (unnormalised), evaluated in
/// the rearranged form that never builds e^{mu R}-sized terms.
struct Eigenfunction {
  std::vector<double> W, Phi;  ///< r = -1..R+1 (index r + 1)
  /// Delta^2 W_r (r = 0..R) and (E - 1) Delta^2 W_r (r = 0..R-1), applied to the closed form
  /// term by term (Delta^2 cosh(mu r) = 2 (cosh mu - 1) cosh(mu r), ...) instead of differencing
  /// nodal values, which would lose ~R^3 eps in the end reactions (19).
  std::vector<double> D2, D3;
};
Eigenfunction eigenfunction(long R, double alpha2);
/// The corrected characteristic function (divided by cosh(mu R) (cosh mu + 2)); and as printed.
double characteristic(long R, double alpha2);
double characteristic_printed(long R, double alpha2);

}  // namespace modalbench::difference_eq::lasecka
