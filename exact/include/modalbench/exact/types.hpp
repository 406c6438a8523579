#pragma once
// Values shared by the exact beam, bar and plate references.

#include <vector>

namespace modalbench::exact {

/// Springs at a beam end or along a plate edge (per unit length), [0, inf].
struct EndSprings {
  double translational = 0;  ///< N/m (plate edge: N/m^2), [0, inf]
  double rotational = 0;     ///< N*m/rad (plate edge: N*m/(rad*m)), [0, inf]
};

struct Frequencies {
  std::vector<double> omega_rad_s;  ///< ascending, rigid-body modes as 0
  int rigid = 0;
  int unresolved = 0;  ///< of the `rigid` zeros: eigenvalues below 1e-250 of the scale, not rigid-body modes
  long count_evaluations = 0;
  long unknowns = 0;  ///< largest assembled dynamic stiffness factorized (free DOFs)
};

}  // namespace modalbench::exact
