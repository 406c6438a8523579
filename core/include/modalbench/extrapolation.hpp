#pragma once
// Richardson extrapolation of a meshed result from the meshes of its own error estimate, with an
// error estimate of the extrapolated values.
//
// A quantity on a mesh of size h with the error expansion q(h) = q0 + C h^p + D h^s + ... (p the
// family's formal order, s > p the order of the next term) is extrapolated from the judged mesh h
// and the coarser H = r h as
//   R(h) = q(h) + (q(h) - q(H)) / (r^p - 1),          error  D h^s c(r),  c(r) = (r^p - r^s) / (r^p - 1),
// and the same from H and 2H = r' H gives R(H). Their difference is D h^s (c(r) - c(r') r^s), so
//   e(R(h)) = |R(h) - R(H)| |c(r)| / |c(r) - c(r') r^s|      (equal ratios: |R(h) - R(H)| / (r^s - 1)),
// and the estimate reported is Roache's factor of safety 3 (an order s assumed, not observed) times
// that, plus the judged solve's own bound (rounding, which neither refinement nor extrapolation sees).
// To it is added how far R would move with the order the three meshes show instead of p,
// |q(h) - q(H)| |1 / (r^p - 1) - 1 / (r^po - 1)|: the leading order is known only that well.
// With a fourth mesh 4H, R(2H) too: the order of R's own sequence is observed (and used where it
// is below s), and the larger of that estimate and 1.25 times the one of R(H) carried to h is
// reported (Roache's guard, as for the mesh's own estimate in result.hpp); where that order
// confirms s > p (within 20 %), the factor of safety of R(h)'s own estimate is 1.25 instead of 3.
// s is the back-end's (CoarserMesh::next_order); deflections use s = p (a point load's h^2 log h
// term is not removed by extrapolation, and with s = p its estimate still covers it), which makes
// their estimate a conservative one.
//
// Usage:
//   Extrapolation x = richardson_extrapolate(fine, {&coarse, r}, {&coarser, r2}, p, s, solve_bound);
//   if (!x.frequencies_rad_s.empty()) ... x.frequency_error ...

#include <string>

#include "modalbench/result.hpp"

namespace modalbench {

/// Roache's factors of safety, for the mesh's own estimate (result.hpp, ErrorEstimate) and the
/// extrapolation's alike: 3 for an estimate whose order is assumed, not observed; 1.25 for the
/// guard from the next coarser pair.
inline constexpr double kRoacheSafetyFactor = 3.0, kRoacheGuardFactor = 1.25;

/// The order p in [lo, hi] at which errors C h^p give the differences d1 = q(h) - q(H) and
/// d2 = q(H) - q(2H) on the ratios r = H / h and r2 = 2H / H: d2 / d1 = r^p (r2^p - 1) / (r^p - 1),
/// increasing in p; clamped to [lo, hi], NaN where d2 / d1 is not positive (the differences change
/// sign).
double observed_order(double d1, double d2, double r, double r2, double lo, double hi);

/// Whether mesh b is mesh a coarsened by r in every direction (every count divided by r): errors
/// C_x h_x^p + C_y h_y^p scale by one ratio only then, and an observed order means something.
bool uniform_coarsening(const Result& a, const Result& b, double r);

/// One mesh of the extrapolation: its result and how much coarser it is than the next finer one.
struct ExtrapolationMesh {
  const Result* result = nullptr;
  double ratio = 2.0;  ///< H / h (for the coarse mesh), 2H / H (for the coarser one)
};

/// Extrapolates `fine` (mesh h) with `coarse` (H) and `coarser` (2H): frequencies where every
/// requested mode pairs (same family, index by index, none rigid on one mesh only), deflections
/// where every probe is present on all three. What cannot be extrapolated is left empty and said in
/// the note. `order` is p, `next_order` s for frequencies (deflections take s = p);
/// `solve_bound` the judged solve's own relative frequency bound (NaN: none).
/// `coarsest` (4H = r'' 2H, optional): R's own sequence R(h), R(H), R(2H) then shows its order (used
/// where below s), and the estimate of R(H) carried to h guards the one of R(h) (times 1.25).
Extrapolation richardson_extrapolate(const Result& fine, const ExtrapolationMesh& coarse,
                                     const ExtrapolationMesh& coarser, double order, double next_order,
                                     double solve_bound, const ExtrapolationMesh* coarsest = nullptr);

}  // namespace modalbench
