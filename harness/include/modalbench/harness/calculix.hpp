#pragma once
// Optional external references by CalculiX: the scene's solid meshed with 20-node hexahedra with reduced
// integration (C3D20R, what docs/sources.md, P8, found the prism paper's ANSYS columns to be), solved by
// CalculiX (`ccx`, Debian package calculix-ccx) for its lowest frequencies. Mode families are
// read from the mode shapes (section-mean translations and twist per x-slice for beams;
// mid-plane w against in-plane motion for plates), so 3D axial, torsion and other-plane
// modes are never compared with bending ones.
//
// Supports: beam ends clamped (all translations of the end face) or free; plate edges
// simply supported (w = 0 on the mid-thickness edge line, as the paper's FEM did), clamped
// (the edge face held) or free. Springs, pinned or guided beam ends are refused with a reason.
//
// Beside the bricks, the element a practitioner would use for the scene's dimension runs over its
// own ladder (calculix_peers.cpp): B32R beams (every end DOF held or free) and S8R shells (edges
// as for the bricks; in-plane translations held everywhere, so no membrane mode appears).

#include <ostream>
#include <string>
#include <vector>

#include "modalbench/harness/comparison.hpp"

namespace modalbench {

struct SolidMesh {
  int nx = 1, ny = 1, nz = 1;  ///< elements along x, y, z
};

/// "This is Version 2.20"-style banner of `exe -v`, or "" when it does not run.
std::string calculix_version(const std::string& exe);
/// Empty if the scene can be modelled, else why not.
std::string calculix_unsupported_reason(const Scene& scene);
/// Meshes from coarse to fine for the scene.
std::vector<SolidMesh> calculix_ladder(const Scene& scene);
/// One CalculiX run in `work_dir`. What stays there: the input deck (NAME.inp) and the frequencies
/// read from it (NAME.modes.csv); ccx's own working files (.dat, .frd, .sta, .cvg, .12d, the log:
/// hundreds of MB over a report) are removed once read, unless `keep_work_files` (or the run failed:
/// then its log says why). Failures come back as a failed record with the reason.
RunRecord calculix_run(const Scene& scene, const SolidMesh& mesh, const std::string& exe, const std::string& work_dir,
                       bool keep_work_files = false);
/// The ladders under a time budget (seconds each), as runs for the harness: the bricks
/// ("calculix") and the practitioner's peer element ("calculix-S8R" / "calculix-B32R").
std::vector<RunRecord> calculix_runs(const Scene& scene, const std::string& exe, const std::string& work_dir,
                                     double budget_s, std::ostream* progress, bool keep_work_files = false);

/// The element a practitioner would use for the scene's dimension: "S8R" shells for plates,
/// "B32R" beams for beams (ccx expands both into C3D20R bricks; B32R takes no shear coefficient).
std::string calculix_peer_element(const Scene& scene);
/// Empty if the peer element can model the scene, else why not.
std::string calculix_peer_unsupported_reason(const Scene& scene);
/// The peer's meshes from coarse to fine: beam elements n, shell elements n x m.
std::vector<Discretization> calculix_peer_ladder(const Scene& scene);
/// One run of the peer element.
RunRecord calculix_peer_run(const Scene& scene, const Discretization& mesh, const std::string& exe,
                            const std::string& work_dir, bool keep_work_files = false);

}  // namespace modalbench
