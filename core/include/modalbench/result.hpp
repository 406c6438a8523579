#pragma once
// What a solver returns: frequencies, deflections, FRF samples and a summary that says
// how far each number can be trusted.

#include <array>
#include <complex>
#include <string>
#include <utility>
#include <vector>

namespace modalbench {

enum class Status {
  Success,         ///< every requested quantity computed and its checks passed
  NotConverged,    ///< best result returned, marked; see message
  NumericalIssue,  ///< a check failed (residual, conditioning, count); numbers are suspect
  Unsupported,     ///< the back-end cannot do this scene; see message
  InvalidInput,    ///< scene or discretization rejected; see message
};
std::string to_string(Status);

/// Which physical family a mode belongs to (never guessed: `unknown` if not known).
enum class ModeFamily { BendingXZ, BendingXY, Axial, Torsion, Plate, Rigid, Unknown };
std::string to_string(ModeFamily);  ///< bending-xz, bending-xy, axial, torsion, plate, rigid, unknown

/// Static response at one probe. Components a scene does not carry stay 0.
struct Deflection {
  std::array<double, 2> position{};  ///< beam: {x, 0}; plate: {x, y}, m
  double u = 0, v = 0, w = 0;        ///< m
  double theta_x = 0, theta_y = 0, theta_z = 0;  ///< rad, right-handed about the axes
};

struct FrfSample {
  double omega_rad_s = 0;
  std::complex<double> receptance;  ///< w(observe) / Fz(excite), m/N
};

struct Summary {
  Status status = Status::Success;
  std::string message;           ///< readable reason when status != Success
  std::string method;            ///< what was actually used (no silent fall-back)
  long dofs = 0;                 ///< unknowns of the discrete model (0 for closed forms)
  long iterations = 0;           ///< root-finder / eigensolver iterations
  double max_residual = 0;       ///< largest relative check residual (eigen-residual etc.)
  double condition_estimate = 0; ///< 0 when not estimated
  std::vector<std::pair<std::string, double>> timings_s;  ///< per phase, seconds
  std::vector<std::string> warnings;
  double total_time_s = 0;
};

struct Result {
  std::vector<double> frequencies_rad_s;  ///< ascending, repeated ones repeated
  std::vector<ModeFamily> mode_families;  ///< parallel to frequencies_rad_s
  std::vector<Deflection> deflections;    ///< one per requested probe
  std::vector<FrfSample> frf;
  Summary summary;

  bool ok() const { return summary.status == Status::Success; }
};

}  // namespace modalbench
