#include "modalbench/rfem/rfem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "modalbench/rfem/analysis.hpp"
#include "modalbench/rfem/builders.hpp"
#include "modalbench/rfem/system.hpp"
#include "analysis_detail.hpp"
#include "rfem_kernels.hpp"
#include "rotor.hpp"

namespace modalbench::rfem {

namespace {

std::string mesh_source(const Scene& s) { return s.source.empty() ? "command line" : s.source; }

/// The simply supported a x b plate's eigenvalues (m / a)^2 + (n / b)^2 up to lambda, counted (at most
/// 10^6).
double plate_modes_below(double a, double b, double lambda) {
  double count = 0;
  for (double m = 1; std::pow(m / a, 2) < lambda && count < 1e6; ++m)
    count += std::floor(b * std::sqrt(lambda - std::pow(m / a, 2)));
  return std::min(count, 1e6);
}

/// The modes of an a x b plate within 5 % above its k-th (as the simply supported plate's): the size
/// of the cluster an eigensolver must resolve to give the first k.
double plate_cluster(double a, double b, double k) {
  double lo = 0, hi = std::pow(k / a, 2) + std::pow(k / b, 2);  // k modes at least below hi
  for (int i = 0; i < 200 && hi > lo * (1 + 1e-12); ++i) {
    const double mid = 0.5 * (lo + hi);
    (plate_modes_below(a, b, mid) >= k ? hi : lo) = mid;
  }
  return plate_modes_below(a, b, 1.05 * hi);
}

}  // namespace

Capability RfemSolver::supports(const Scene& s) const {
  Capability c;
  if (s.is_frame()) {
    c.reason = frame_refusal(s);
    c.modes = c.statics = c.reason.empty();
    return c;
  }
  if (s.is_beam() || s.is_plate()) {
    c.modes = c.statics = c.frf = true;
    if (s.rotor) {
      c.reason = detail::rotor_scene_refusal(s);
      c.campbell = c.reason.empty();
    }
    return c;
  }
  c.reason = "rfem builds beams and plates only";
  return c;
}

// Fitted to runs of `modalbench solve --json` on the 2-core machine (Release, /usr/bin/time peak
// resident memory less the ~20 MB of the process): beams of 10^4 to 1.6 * 10^5 segments in
// bending (6 modes 3.1 KB and 11 us, statics 1.8 KB and 3.6 us per segment, a direct FRF 3.4 KB and
// 0.23 us per segment and sample), Kirchhoff plates of 6,000 to 96,000 fragments (modes 7.5 KB and
// 37-54 us, statics 4.7 KB and 17-35 us per fragment, a direct FRF 4.4 KB and 3.6-7.4 us per fragment
// and sample). Per coordinate the costs scale with the DOFs an element carries; Mindlin plates
// carry about twice a Kirchhoff plate's coordinates.
ResourceEstimate RfemSolver::estimate(const Scene& s, const Discretization& mesh, const Options& options) const {
  ResourceEstimate e;
  const auto& rq = s.request;
  const bool modal_frf = rq.frf && options.resolved.get_integer("frf_modes") > 0;
  const double samples = rq.frf ? rq.frf->points : 0;
  const double k = std::max<double>(rq.modes, modal_frf ? static_cast<double>(options.resolved.get_integer("frf_modes")) : 0.0);
  if (s.is_frame() && mesh.counts.size() == 1 && mesh.counts[0] >= 1) {
    // As a beam of all the members' segments (below).
    double n = 0;
    for (std::size_t i = 0; i < s.frame->members.size(); ++i)
      n += frame_member_segments(*s.frame, i, std::min(mesh.counts[0], 2000000));
    const double d = s.frame->spatial ? 3.0 : 1.5;
    e.bytes = std::max(k > 0 ? 3.1e3 * n * d * (1 + k / 60) : 0.0, rq.probes.empty() ? 0.0 : 1.8e3 * n * d);
    e.seconds = (k > 0 ? n * d * (6e-6 + 4.3e-7 * std::pow(k, 1.5)) : 0.0) + (rq.probes.empty() ? 0.0 : 3.6e-6 * n * d);
    e.basis = fmt::format("frame of {:.0f} segments, {} modes", n, k);
  } else if (s.is_beam() && mesh.counts.size() == 1) {
    const double n = mesh.counts[0];
    const double d = s.physics == Physics::Spatial   ? 3.0
                     : s.physics == Physics::Lateral ? 2.0
                     : s.physics == Physics::Planar  ? 1.5
                                                     : 1.0;
    double bytes = 0, t = 0;
    // Lanczos: ~k^1.5 per segment (measured 10 s for 200 modes of 8192 segments, 1.8 s for 6 of 160,000).
    if (k > 0) { bytes = std::max(bytes, 3.1e3 * n * d * (1 + k / 60)); t += n * d * (6e-6 + 4.3e-7 * std::pow(k, 1.5)); }
    if (!rq.probes.empty()) { bytes = std::max(bytes, 1.8e3 * n * d); t += 3.6e-6 * n * d; }
    if (rq.frf && !modal_frf) { bytes = std::max(bytes, 3.4e3 * n * d); t += 0.23e-6 * n * d * samples; }
    // A rotor: per spin, the stationary frame's projected sweep or Arnoldi (rotor.hpp's cost model,
    // which also chooses between them), Arnoldi in the rotating frame; Arnoldi's vectors 2 n x 40.
    // A lateral model has 4 coordinates per segment.
    const double spins = s.rotor ? static_cast<double>(s.rotor->spin.size()) : 0.0;
    if (spins > 0) {
      const double coordinates = 2.0 * n * d;
      const int roots = static_cast<int>(k);
      const bool projected = s.rotor->frame == Rotor::Frame::Stationary &&
                             detail::projected_sweep(options.resolved.get_choice("campbell_method"), coordinates, roots);
      bytes = std::max(bytes, 1.5e3 * n * d);
      t += spins * (projected ? detail::projected_seconds_per_spin(coordinates, roots)
                              : detail::arnoldi_seconds_per_spin(coordinates, roots));
    }
    e.bytes = bytes;
    e.seconds = t;
    e.basis = fmt::format("beam of {} segments, {} modes, {} FRF samples{}", mesh.counts[0], k, samples,
                          spins > 0 ? fmt::format(", {} spins", spins) : "");
  } else if (s.is_plate() && mesh.counts.size() == 2) {
    const double f = static_cast<double>(mesh.counts[0]) * mesh.counts[1];
    const double d = s.theory == Theory::Mindlin ? 2.0 : 1.0;
    const double growth = std::pow(std::max(1.0, f / 6000.0), 0.3);  // fill of the nested-dissection factor
    // Lanczos resolves a cluster as a whole: the modes within 5 % above the k-th, not k, set its
    // time (a 0.0106 x 10 m cantilever strip's 6 modes lie in a cluster of some 200: 43 s, estimated
    // 5.5 s by k alone, 57 s by the cluster). Its memory stays k's (850 MB for that run, where the
    // fit gives 0.41 GB by k and 2.2 GB by the cluster).
    const double kc = k > 0 ? std::max(k, plate_cluster(s.geometry.length, s.geometry.width, k)) : 0.0;
    double bytes = 0, t = 0;
    if (k > 0) { bytes = std::max(bytes, 7.5e3 * f * d * (1 + k / 40)); t += 3.7e-5 * f * d * growth * (1 + kc / 16); }
    if (!rq.probes.empty()) { bytes = std::max(bytes, 4.7e3 * f * d); t += 1.7e-5 * f * d * growth; }
    // FRF: one complex solve per sample on the factor's pattern (measured on the paper plate, 400
    // samples: 0.031 s at 40 x 32, 0.21 s at 80 x 64, 1.7 s at 152 x 122; 3.6e-6 had it 20x high).
    if (rq.frf && !modal_frf) { bytes = std::max(bytes, 4.4e3 * f * d * growth); t += 1.8e-7 * f * d * growth * samples; }
    e.bytes = bytes;
    e.seconds = t;
    e.basis = fmt::format("plate of {} x {} fragments, {} modes{}, {} FRF samples", mesh.counts[0], mesh.counts[1], k,
                          kc > 1.5 * k ? fmt::format(" (in a cluster of about {:.0f} within 5 % of the highest)", kc) : "",
                          samples);
  }
  return e;
}

std::vector<OptionSpec> RfemSolver::option_specs() const {
  using T = OptionSpec::Type;
  return {
      {"eigen", T::Choice, "auto", {"auto", "dense", "shift-invert"}, 0, 0,
       "eigensolver: dense (complete, refined) or Lanczos in shift-invert mode; auto picks by size"},
      {"dense_limit", T::Integer, "40", {}, 1, 1e6,
       "auto: the dense path up to this many coordinates (measured: shift-invert Lanczos is faster from 30 up)"},
      {"tolerance", T::Number, "1e-10", {}, 1e-15, 1e-3, "Lanczos relative tolerance"},
      {"sturm_check", T::Bool, "true", {}, 0, 0,
       "count the eigenvalues below the last mode by an LDL' inertia (on a second core) to prove none is missed"},
      {"seed", T::Integer, "20240917", {}, 0, 4294967295.0, "Lanczos start vector"},
      {"frf_modes", T::Integer, "0", {}, 0, 1e6,
       "0: FRF by direct solves (or the complete spectral decomposition of small models); N > 0: modal "
       "superposition over N modes (truncated: an approximation)"},
      {"frf_method", T::Choice, "auto", {"auto", "direct", "projected"}, 0, 0,
       "FRF without frf_modes: direct (one sparse solve per frequency), projected (modes below twice the top "
       "frequency plus load-dependent Ritz vectors, each sample's error bounded, those over the tolerance (at most 0.05 dB) solved "
       "directly), or auto (projected from 20 samples)"},
      {"campbell_method", T::Choice, "auto", {"auto", "projected", "arnoldi"}, 0, 0,
       "rotors, stationary frame: projected (K factored once; per spin the projected gyroscopic problem on a basis "
       "enriched by K^-1 residuals, each root's frequency bounded by its residual to 1e-9 (or, where rounding stops "
       "it, to at most 1e-7, reported), Arnoldi where not met; "
       "with sturm_check, a count at the top spin) or arnoldi (shift-invert Arnoldi on the companion form at every "
       "spin); auto: the cheaper by rfem's cost model (projected for few roots: 6 on 2000 coordinates, 5x faster; "
       "Arnoldi for many: 20 on 400); the rotating frame always uses Arnoldi"},
      {"beam_rigid_shear", T::Choice, "multipliers", {"multipliers", "joint-coordinates"}, 0, 0,
       "Euler-Bernoulli beams: rigid shear springs as constraints with multipliers, or by joint coordinates"},
      {"plate_rigid_shear", T::Choice, "corner-coordinates", {"corner-coordinates", "multipliers"}, 0, 0,
       "Kirchhoff plates: rigid transverse shear by corner-value coordinates, or constraints with multipliers"},
      {"plate_bending_correction", T::Bool, "true", {}, 0, 0,
       "plates: per-fragment Poisson coupling and Mindlin twist form (false: Table A1.1 springs as printed)"},
  };
}

Model RfemSolver::build_model(const Scene& s, const Discretization& mesh, const ResolvedOptions* options) {
  const std::string src = mesh_source(s);
  if (s.is_frame()) {
    if (mesh.counts.size() != 1)
      throw InputError(src, "--mesh",
                       fmt::format("a frame mesh is one count N (segments on its shortest member), e.g. 16 (got '{}')",
                                   mesh.spec()));
    const int n = mesh.counts[0];
    if (n < 1 || n > 2000000)
      throw InputError(src, "--mesh", fmt::format("a frame needs N in [1, 2000000] segments on its shortest member (got {})", n));
    try {
      return build_frame(s, n);
    } catch (const std::invalid_argument& e) {
      throw InputError(src, "--mesh", e.what());
    }
  }
  if (s.is_beam()) {
    if (mesh.counts.size() != 1)
      throw InputError(src, "--mesh",
                       fmt::format("a beam mesh is one count N (segments), e.g. 64 (got '{}')", mesh.spec()));
    const int n = mesh.counts[0];
    if (n < 1) throw InputError(src, "--mesh", fmt::format("a beam needs N >= 1 segments (got {})", n));
    if (n > 2000000) throw InputError(src, "--mesh", fmt::format("N = {} exceeds the limit of 2000000 segments", n));
    BeamOptions bo;
    // A rotor's Campbell diagram solves the quadratic eigenproblem without multipliers.
    if ((options && options->get_choice("beam_rigid_shear") == "joint-coordinates") || s.rotor)
      bo.rigid_shear = RigidShear::JointCoordinates;
    return build_beam(s, n, bo);
  }
  if (mesh.counts.size() != 2)
    throw InputError(src, "--mesh",
                     fmt::format("a plate mesh is NXxNY (fragments along x and y), e.g. 20x12 (got '{}')", mesh.spec()));
  const int nx = mesh.counts[0], ny = mesh.counts[1];
  if (nx < 2 || ny < 2)
    throw InputError(src, "--mesh", fmt::format("a plate needs at least 2x2 fragments (got {}x{})", nx, ny));
  if (static_cast<double>(nx) * ny > 4.0e6)
    throw InputError(src, "--mesh", fmt::format("{}x{} exceeds the limit of 4e6 fragments", nx, ny));
  PlateOptions po;
  po.nx = nx;
  po.ny = ny;
  if (options) {
    po.rigid_shear = options->get_choice("plate_rigid_shear") == "multipliers" ? RigidShear::Multipliers
                                                                               : RigidShear::JointCoordinates;
    po.bending_correction = options->get_bool("plate_bending_correction");
  }
  return build_plate(s, po);
}

std::unique_ptr<Kernels> RfemSolver::build(const Scene& s, const Discretization& mesh, const Options& options,
                                           Result& r) const {
  detail::reserve_blas_workspace();
  return detail::make_kernels(s, mesh, options, build_model(s, mesh, &options.resolved), r);
}

}  // namespace modalbench::rfem
