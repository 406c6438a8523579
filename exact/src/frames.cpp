#include "frames.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "frame_system.hpp"
#include "modalbench/frame.hpp"
#include "modalbench/numerics/spectrum_slicing.hpp"

namespace modalbench::exact::detail {

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
