#pragma once
// Private to the rfem solver: supports that act on one rigid element of a beam mesh.
#include <string>

#include "modalbench/scene.hpp"

namespace modalbench::rfem::detail {

/// Where two supports with a translational spring (an end, or a point between the ends) act on
/// one rigid element of the n-element mesh of a Timoshenko beam: a sentence saying which, how far
/// apart, and why that is not the scene's beam; empty otherwise. One rigid element has one
/// rotation, so two such supports on it hold it (a clamp), where a shear-deformable beam lets the
/// section turn between them at a shear stiffness kappa G A times their distance, which vanishes as
/// they close up. Under Euler-Bernoulli theory close supports do clamp the slope: no sentence.
std::string supports_sharing_an_element(const Scene& s, int n);

}  // namespace modalbench::rfem::detail
