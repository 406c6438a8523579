// DtfmSolver (dtfm.hpp): what it supports, its options and cost model, and its model with its
// kernels (dtfm_kernels.cpp); its meshes are in meshes.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "modalbench/dtfm/dtfm.hpp"
#include "dtfm_kernels.hpp"
#include "rotor.hpp"

namespace modalbench::dtfm {

Capability DtfmSolver::supports(const Scene& s) const {
  Capability c;
  if (s.is_frame()) {
    c.reason = "dtfm does not model frames yet (one prism per member, joined at nodes: issue 49); exact solves them";
    return c;
  }
  c.modes = c.statics = c.frf = true;
  if (s.rotor) {
    c.reason = detail::rotor_refusal(s);
    c.campbell = c.reason.empty();
  }
  return c;
}

// Fitted to bench_dtfm_timing on the 2-core machine, built with MODALBENCH_ARCH=none (the slower of
// the two builds; x86-64-v3 takes 0.13 s): a 40-strip plate takes 0.21 s for 8 modes (its two
// symmetry classes side by side, about 111 count evaluations) and the cost grows about 5- to 8-fold
// per doubling of strips (the segment exponentials and doublings); the spatial 6 x 6 beam (216
// fields) 0.23 s for 8 modes with x86-64-v3; a FRF sample costs about one count evaluation. Memory
// is a few dense blocks per line and segment.
ResourceEstimate DtfmSolver::estimate(const Scene& scene, const Discretization& mesh, const Options&) const {
  ResourceEstimate e;
  double fields = 0;  // prism DOF fields in the model
  if (scene.is_plate() && mesh.counts.size() == 1) fields = 3.0 * (mesh.counts[0] + 1);
  else if (!scene.is_plate() && !mesh.counts.empty()) {
    const double per = scene.physics == Physics::Spatial   ? 6
                       : scene.physics == Physics::Lateral ? 4
                       : scene.physics == Physics::Planar  ? 3
                                                           : 2;
    // A tapered beam's mesh counts steps along it; each is one prism.
    fields = scene.has_tapered_pieces() ? per
                                        : per * mesh.counts[0] * (mesh.counts.size() > 1 ? mesh.counts[1] : mesh.counts[0]);
  }
  // A tapered beam's staircase: each step a node of the line, its cost about linear in them (the
  // conical shaft's 31 spins of 4 roots: 6.7 s on 51 pieces, where a uniform shaft takes 86 ms).
  double steps = 1;
  if (scene.has_tapered_pieces() && mesh.counts.size() == 1)
    for (const Segment& p : scene.segments) steps += p.tapered() ? mesh.counts[0] : 1;
  const double line_factor = steps > 1 ? 1.5 * steps : 1.0;
  if (fields <= 0) return e;
  const double scale = std::pow(fields / 123.0, 3.0);  // 40 strips: 123 fields
  const double per_eval = 0.21 / 111.0 * scale * line_factor;  // ~111 count evaluations for 8 modes
  const auto& rq = scene.request;
  e.seconds = per_eval * (20.0 * std::max(0, rq.modes) + 10.0 * static_cast<double>(rq.probes.size()) + (rq.frf ? rq.frf->points : 0));
  // A rotor (one prism): two whirl lines per spin, each sliced like the modes, and the criticals
  // (measured: 86 ms for the Timoshenko shaft's 31 spins of 4 roots, 89 ms for Friswell's 21 of 6,
  // 76 ms for a stepped shaft's 7 of 6).
  if (scene.rotor)
    e.seconds += (0.02 + 0.5e-3 * std::max(1, rq.modes) * static_cast<double>(scene.rotor->spin.size())) * line_factor;
  e.bytes = 8.0 * fields * fields * 200.0;
  e.basis = fmt::format("{} prism fields, {} modes, {} FRF samples", fields, rq.modes, rq.frf ? rq.frf->points : 0);
  return e;
}

std::vector<OptionSpec> DtfmSolver::option_specs() const {
  using T = OptionSpec::Type;
  const SolveControls c;
  auto num = [](double v) { return fmt::format("{}", v); };
  return {
      {"layers", T::Choice, to_string(options_.layers), {"consistent", "staggered", "paper"}, 0, 0,
       "spring layers between prisms: consistent (Eq. (25) springs + cross terms), staggered, or paper (Eq. (25) "
       "as printed)"},
      {"kirchhoff_penalty", T::Number, num(options_.kirchhoff_penalty), {}, 1e-3, 1e6,
       "Kirchhoff plates: layer shear penalty in units of 12 D / dy^3"},
      {"rel_tol", T::Number, num(c.rel_tol), {}, 1e-15, 1e-3,
       "relative tolerance on omega^2 (plates, where not given: 1e-4 of [request] tolerance if larger)"},
      {"im_h", T::Number, num(c.im_h), {}, 1e-3, 3.0, "base pieces: bound on |Im p| h"},
      {"re_h", T::Number, num(c.re_h), {}, 1e-3, 20.0, "base pieces: bound on |Re p| h"},
      {"family_threshold", T::Number, num(c.family_threshold), {}, 0.0, 1.0,
       "beam modes are labelled by family when the rigid-section share of kinetic energy reaches this"},
  };
}

std::unique_ptr<Kernels> DtfmSolver::build(const Scene& scene, const Discretization& mesh, const Options& options,
                                           Result& r) const {
  return make_kernels(scene, mesh, options, options_, r);
}

}  // namespace modalbench::dtfm
