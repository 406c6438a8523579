#include "frames.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "frame_system.hpp"
#include "modalbench/frame.hpp"
#include "modalbench/numerics/spectrum_slicing.hpp"

namespace modalbench::exact::detail {

ResourceEstimate frame_estimate(const Scene& s) {
  // A count assembles every member (closed forms, or a Timoshenko field's doubling in O(log k))
  // and factors the dense K(lambda) of n unknowns; about 45 counts per mode.
  ResourceEstimate e;
  const double k = std::max(0, s.request.modes);
  const double n = 6.0 * static_cast<double>(s.frame->nodes.size() + 2 * s.frame->members.size());
  const double count_s = 2e-5 * static_cast<double>(s.frame->members.size()) * std::log2(k + 2) + 1e-9 * n * n * n;
  e.seconds = 45.0 * k * count_s;
  e.bytes = 8.0 * n * n * 4;
  e.basis = fmt::format("{} modes of a frame of {} members, about {:.0f} unknowns", s.request.modes,
                        s.frame->members.size(), n);
  return e;
}

std::string frame_method(const Scene& s) {
  return fmt::format(
      "exact {} frame: each member's exact dynamic stiffness (axial, bending{}: bars and Euler-Bernoulli "
      "bending in closed form, Timoshenko bending by doubling from pieces with |p| h <= 1), assembled at the "
      "nodes; frequencies by bisection on the Wittrick-Williams count (the members' clamped-end counts J0 plus the "
      "negative pivots of K(omega); a member cut where omega lies next to one of its clamped frequencies) to 1e-13 "
      "in omega^2; statics by K(0) with each member's exact fixed-end forces",
      to_string(s.theory), s.frame->spatial ? " in both planes, torsion" : "");
}

void frame_modes(const Scene& s, Result& r) {
  const FrameSystem sys(s);
  const int k = s.request.modes;
  r.summary.unknowns = std::max<long>(r.summary.unknowns, sys.unknowns());
  long evaluations = 0;
  const auto count = [&](double lambda) {
    ++evaluations;
    return sys.count_det(lambda).first;
  };
  const double scale = sys.lambda_scale();
  // Below 1e-10 of the frame's scale only its rigid motions lie (as a line's: kRigidThreshold).
  const double lo = 1e-10 * scale;
  if (const int below = count(-lo); below != 0)
    throw std::runtime_error(fmt::format("{} negative eigenvalue(s) omega^2 < 0: the frame is unstable", below));
  const int rigid = std::min(count(lo), k), free = sys.rigid_motions();
  if (rigid != std::min(free, k))
    r.summary.raise(Status::NumericalIssue,
                    fmt::format("exact: {} eigenvalue(s) below 1e-10 of the frame's scale but K(0) leaves {} rigid "
                                "motion(s) free: near-rigid modes (springs far softer than the members) reported as 0",
                                rigid, free));
  SliceStats stats;
  const std::vector<double> rest = slice_spectrum(count, k - rigid, lo, scale, 1e-13, &stats);
  for (int i = 0; i < rigid; ++i) {
    r.frequencies_rad_s.push_back(0.0);
    r.mode_families.push_back(ModeFamily::Rigid);
  }
  for (const double lambda : rest) {
    r.frequencies_rad_s.push_back(std::sqrt(lambda));
    r.mode_families.push_back(ModeFamily::Unknown);
  }
  r.summary.set_diagnostic("count_evaluations", static_cast<double>(evaluations));
}

void frame_statics(const Scene& s, Result& r) {
  const FrameSystem sys(s);
  r.summary.unknowns = std::max<long>(r.summary.unknowns, sys.unknowns());
  const FrameSystem::Statics st = sys.statics();
  r.deflections = st.probes;
  r.reactions = st.reactions;
  r.summary.note_backward_error(st.backward_error);
  r.summary.set_diagnostic("reaction_imbalance", st.imbalance);
  // The members' end forces balance their loads exactly, the nodes to the solve's rounding.
  if (!(st.imbalance <= 1e-9))
    r.summary.raise(Status::NumericalIssue,
                    fmt::format("exact: statics: the reactions balance the loads only to {:.2g} (relative)", st.imbalance));
  for (const std::string& id : sys.undefined_rotations())
    r.summary.warnings.push_back(fmt::format(
        "node '{}': every member is hinged there, so the node itself has no rotation in some direction; a probe "
        "there reports 0 for it (the members' own end rotations are at member probes, s = 0 or 1)",
        id));
}

}  // namespace modalbench::exact::detail
