#pragma once
// A reduced-order model of a scene for control design (`modalbench rom`): the first-order
// state-space model (A, B, C, D) of unit forces Fz at input points and w, its velocity and its
// acceleration at output points, from a back-end's modes (modal truncation), with the static
// correction in D, and its H-infinity error against the same back-end's full receptance measured
// on a frequency grid.
//
// States x = [q; q'] (modal coordinates of unit modal mass), inputs u = Fz at each input (N):
//   A = [[0, I], [-Omega^2, -2 Z Omega]],  B = [[0], [Phi_in']]
//   w = [Phi_out, 0] x + D_w u          D_w = G - Phi_out Omega^-2 Phi_in' (static correction; G the
//                                        back-end's static flexibility), else 0
//   v = [0, Phi_out] x
//   a = [-Phi_out Omega^2, -Phi_out 2 Z Omega] x + Phi_out Phi_in' u
//
// Usage:
//   RomRequest rq; rq.inputs = {{0.3, 0}}; rq.outputs = {{0.5, 0}}; rq.modes = 8;
//   const StateSpaceModel m = export_rom(registry.get("exact"), scene, std::nullopt, rq);
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "modalbench/solver.hpp"

namespace modalbench {

struct RomRequest {
  std::vector<std::array<double, 2>> inputs;   ///< beam {x, 0}, plate {x, y}: a unit Fz each
  std::vector<std::array<double, 2>> outputs;  ///< where w, velocity and acceleration are output
  int modes = 12;                              ///< modes retained (rigid-body modes included)
  double zeta = 0;                             ///< modal damping ratio in A
  bool static_correction = true;
  int check_points = 100;  ///< frequencies of the H-infinity check
};

struct StateSpaceModel {
  Status status = Status::Success;
  std::string message;
  Eigen::MatrixXd A, B, C, D;
  std::vector<std::string> states, inputs, outputs;  ///< labels, with units
  std::vector<double> omega_rad_s;                   ///< the retained modes
  int rigid_modes = 0;
  bool static_correction = false;
  std::string backend, mesh;
  /// The displacement rows' H-infinity error against the back-end's full receptance, undamped,
  /// measured at check_points frequencies over (0, band] away from the poles: m/N, and relative to
  /// the largest |H_full| there. NaN where the back-end gives no FRF.
  double hinf_error = kNotMeasured, hinf_relative = kNotMeasured, band_rad_s = kNotMeasured;
  /// The first neglected mode's share of the displacement rows at the band's top (the truncated
  /// tail's leading term), m/N.
  double first_neglected = kNotMeasured;
  /// A bound on the whole truncated tail of the displacement rows over [0, band], m/N: with R(p) =
  /// G(p, p) - sum_retained phi(p)^2 / omega^2 >= 0 the residual driving-point flexibility at each
  /// input and output (the truncated modes' sum of phi^2 / omega^2), Cauchy-Schwarz gives
  /// |tail(o, i)| <= sqrt(R(o) R(i)) band^2 / (omega_next^2 - band^2) with the static correction, and
  /// sqrt(R(o) R(i)) omega_next^2 / (omega_next^2 - band^2) without. NaN without static flexibilities
  /// (rigid-body modes) or without a neglected mode.
  double tail_bound = kNotMeasured;
  std::string note;
};

/// Builds the model on `mesh` (nullopt: the back-end's default mesh, refined to the scene's
/// tolerance). Failures come back in status and message; a point off the body, no inputs or
/// outputs, or modes < 1 throw InputError (source "rom", the list and index as key).
StateSpaceModel export_rom(const Solver& solver, const Scene& scene, const std::optional<Discretization>& mesh,
                           const RomRequest& rq);

/// {A, B, C, D} as arrays of rows (NumPy: np.array(doc["A"])), with labels, units and the check.
nlohmann::json to_json(const StateSpaceModel& m);

}  // namespace modalbench
