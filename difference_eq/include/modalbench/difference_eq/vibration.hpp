#pragma once
// Free vibration of the regular discrete beam: a characteristic equation of fixed size.
//
// With element matrices K_e (stiffness) and M_e (consistent: rhoA a/420 [[156, 22a, 54, -13a],
// ...]; lumped: rhoA a/2 on each translation, massless rotations), a harmonic motion obeys at
// every interior node the same pair of difference equations (the paper's (3)-(4) with inertia).
// In element units (EI/a^3) with Omega = omega^2 rhoA a^4 / (c EI), c = 420 (consistent) or
// 2 (lumped), the trial solution (w, phi)_r = v z^r gives a 2x2 symbol H(z) whose determinant
// is a quadratic in x = (z + 1/z)/2 - 1 (computed without cancellation):
//   A x^2 + B x + C = 0,   e.g. consistent: A = 48 + 48 Omega + 28 Omega^2,
//   B = -Omega (1680 + 952 Omega),  C = -420 Omega (12 - 2 Omega).
// Its two roots give the difference-equation roots z = e^{+-mu}, e^{+-i nu} of the paper
// (cosh mu = 1 + x1, cos nu = 1 + x2; for the lumped mass this is exactly the paper's
// alpha^2 = (1 - c)^2 / (2 (c + 2)) with Omega = 12 alpha^2). About the centre of the
// chain the solutions are even/odd: w = W cosh(mu t), phi = Phi sinh(mu t) and
// w = W sinh(mu t), phi = Phi cosh(mu t), t = r - R/2, with (W, Phi) = (h22, g sinh mu).
// The end forces of each solution are closed-form in sinh(mu/2), cosh(mu/2) (no
// differences of nearly equal nodal values, so long chains keep full accuracy), and all
// hyperbolic functions are scaled by 2 e^{-Re(mu) R/2}: nothing overflows for R up to 1e7.
//
// Four amplitudes, four end conditions (held DOF: u = 0; spring: f + k u = 0): the 4x4
// characteristic matrix C(Omega), whose columns are normalised to be real-analytic in Omega,
// so det C is a real, pole-free characteristic function; its size does not depend on R.
// Modes are counted exactly (Wittrick-Williams): with D(Omega) the 4x4 end dynamic stiffness
// of the chain (= F E^-1, same closed form) and N_pp the pinned-pinned count (closed form:
// the pinned-pinned modes are sin(k pi r / R), cos(k pi r / R), so it is a count of k per
// branch of the dispersion relation),
//   N(Omega) = N_pp(Omega) - neg(D_phiphi) + neg((D + S)_free).
// Mode j is bracketed from the pinned-pinned spectrum, isolated by bisection on N, and
// polished by Brent's method on det C. Cost per mode independent of R.

#include <vector>

#include "modalbench/difference_eq/regular_beam.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::difference_eq {

/// The mass model: core's one enum (consistent Hermite or lumped), to_string from core.
using modalbench::MassModel;

struct Spectrum {
  std::vector<double> omega_rad_s;  ///< ascending; rigid-body modes first, as exact zeros
  int rigid = 0;                    ///< rigid-body modes among them
  long available = 0;               ///< finite eigenvalues of the model (free DOFs; lumped: free translations)
  long count_evaluations = 0;       ///< Wittrick-Williams counts
  long determinant_evaluations = 0; ///< characteristic-determinant evaluations (Brent)
  double max_bracket = 0;           ///< largest relative width of a final root bracket
};

/// The k lowest natural frequencies (fewer if the model has fewer). Throws std::invalid_argument.
Spectrum natural_frequencies(const RegularBeam& beam, MassModel mass, int k);

/// Number of natural frequencies with omega^2 < lambda (exact count, O(1) in R).
long count_below(const RegularBeam& beam, MassModel mass, double lambda);

/// The real characteristic function det C at lambda = omega^2 (row-equilibrated, so only its
/// sign and zeros are meaningful).
double characteristic_function(const RegularBeam& beam, MassModel mass, double lambda);

/// The 4x4 end dynamic stiffness of the chain (no springs) at lambda, in element units EI/a^3,
/// DOF order (w0, phi0, wR, phiR) with phi = a psi. For tests against a condensed FE chain.
std::vector<double> end_dynamic_stiffness(const RegularBeam& beam, MassModel mass, double lambda);

struct ModeShape {
  std::vector<double> w, slope;  ///< nodal values, scaled to max |w| (or max |a slope|) = 1
};
/// The nodal mode shape at a natural frequency (null vector of C, then the closed-form fields).
ModeShape mode_shape(const RegularBeam& beam, MassModel mass, double omega_rad_s);

/// Normwise backward error ||(K - w^2 M) u||_inf / ((||K||_inf + w^2 ||M||_inf) ||u||_inf) of the
/// assembled FE equations (element by element, O(R)); a held DOF's |u| counts as residual.
double eigen_residual(const RegularBeam& beam, MassModel mass, double omega_rad_s, const ModeShape& u);

}  // namespace modalbench::difference_eq
