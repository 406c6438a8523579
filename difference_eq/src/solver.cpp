// DifferenceEqSolver (difference_eq.hpp): what it supports, its meshes, options and cost model, and
// its model with its kernels (difference_eq_kernels.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include "modalbench/difference_eq/difference_eq.hpp"
#include "difference_eq_kernels.hpp"
#include "rotor.hpp"

namespace modalbench::difference_eq {

namespace {

// Node tolerance: x = r L / R within 1e-9 L.
constexpr double kNodeTol = 1e-9;

// Smallest q <= qmax with x / L within kNodeTol of a multiple of 1/q (0 if none).
long denominator(double x_over_L, long qmax) {
  for (long q = 1; q <= qmax; ++q) {
    const double v = x_over_L * static_cast<double>(q);
    if (std::abs(v - std::round(v)) <= kNodeTol * static_cast<double>(q)) return q;
  }
  return 0;
}

// Least R that puts every load, support and mass (and with `probes`, every probe) on a node (0 if
// they are not commensurate). Loads, supports and masses must be nodes; a probe between nodes is
// interpolated (Hermite, plus the element's clamped-clamped solution), on a node it is exact.
long base_mesh(const Scene& s, bool probes) {
  std::vector<double> xs;
  for (const auto& l : s.loads) xs.push_back(l.x);
  if (probes)
    for (const auto& p : s.request.probes) xs.push_back(p[0]);
  for (const auto& p : s.point_supports) xs.push_back(p.x);
  for (const auto& m : s.masses) xs.push_back(m.x);
  for (const auto& q : s.line_loads) xs.insert(xs.end(), {q.from[0], q.to[0]});
  long base = 1;
  for (double x : xs) {
    const long q = denominator(x / s.geometry.length, 4096);
    if (q == 0) return 0;
    base = std::lcm(base, q);
    if (base > 1'000'000) return 0;
  }
  return base;
}

/// The least R of base_mesh with the probes on nodes where they can be, else without them.
long base_mesh(const Scene& s) {
  const long with_probes = base_mesh(s, true);
  return with_probes > 0 ? with_probes : base_mesh(s, false);
}

/// The smallest multiple of every load's and probe's denominator (in units of L) with
/// R >= max(32, 8 modes); 64 when the positions are not commensurate.
Discretization default_mesh(const Scene& s) {
  const long base = base_mesh(s);
  const long want = std::max<long>(32, 8L * s.request.modes);
  if (base == 0) return Discretization{{64}};
  long R = base * ((want + base - 1) / base);
  if (R > 1'000'000) R = base;
  return Discretization{{static_cast<int>(R)}};
}

/// R = base, 2 base, 4 base, ... from >= 4 up to <= 4096 (base puts loads and probes on nodes).
std::vector<Discretization> mesh_ladder(const Scene& s) {
  const long base = base_mesh(s);
  std::vector<Discretization> out;
  if (base == 0 || base > 4096) return {default_mesh(s)};
  long R = base;
  while (R < 4) R *= 2;
  for (; R <= 4096; R *= 2) out.push_back(Discretization{{static_cast<int>(R)}});
  return out;
}

/// The ladder's top and the largest multiple of the load/probe grid not above R = 10^6 (the closed
/// forms are O(R) in statics, O(1) per mode).
std::vector<Discretization> stress_meshes(const Scene& s) {
  std::vector<Discretization> out{mesh_ladder(s).back()};
  const long base = base_mesh(s);
  if (base == 0) return out;
  const long R = base * (1'000'000 / base);
  if (R > out.back().counts[0]) out.push_back(Discretization{{static_cast<int>(R)}});
  return out;
}

/// Halved counts, where loads, supports and masses stay on nodes.
std::optional<CoarserMesh> coarser_mesh(const Scene& s, const Discretization& mesh, MassModel mass) {
  if (mesh.counts.size() != 1 || mesh.counts[0] < 4 || mesh.counts[0] % 2) return std::nullopt;
  const long base = base_mesh(s, false);
  const int half = mesh.counts[0] / 2;
  if (base == 0 || half % base) return std::nullopt;  // loads, supports or masses would leave the nodes
  // Hermite cubics: eigenvalues converge at h^4 with the consistent mass, h^2 with the lumped one.
  // The expansions are even in h: h^4 then h^6 (consistent), h^2 then h^4 (lumped).
  return mass == MassModel::Consistent ? CoarserMesh{{{half}}, 2.0, 4.0, 6.0} : CoarserMesh{{{half}}, 2.0, 2.0, 4.0};
}

/// The mesh times the factor, even, with loads (and probes where they can be) on nodes.
std::optional<Discretization> finer_mesh(const Scene& s, const Discretization& mesh, double factor) {
  const long base = base_mesh(s);
  if (mesh.counts.size() != 1 || base == 0) return std::nullopt;
  long R = std::lround(std::ceil(mesh.counts[0] * factor));
  R = base * ((R + 2 * base - 1) / (2 * base)) * 2;  // even, loads (and probes where they can be) on nodes
  if (R > 1'000'000) return std::nullopt;
  return Discretization{{static_cast<int>(R)}};
}

}  // namespace

MeshFamily DifferenceEqSolver::meshes(const Scene& s, const Options& options) const {
  MeshFamily f;
  f.default_mesh = default_mesh(s);
  f.ladder = mesh_ladder(s);
  // On Euler-Bernoulli beams in bending (x-z) only: elsewhere its difference from the scene's
  // theory is model error, not stability.
  if (s.is_beam() && s.theory == Theory::EulerBernoulli && s.physics == Physics::Bending) f.theory = f.default_mesh;
  f.stress = stress_meshes(s);
  // Hermite cubics: eigenvalues converge at h^4 with the consistent mass, h^2 with the lumped one.
  f.order = options.mass == MassModel::Consistent ? 4.0 : 2.0;
  // The closures keep a copy of the scene: the family outlives the caller's.
  auto scene = std::make_shared<const Scene>(s);
  const MassModel mass = options.mass;
  f.coarser = [scene, mass](const Discretization& m) { return coarser_mesh(*scene, m, mass); };
  f.finer = [scene](const Discretization& m, double factor) { return finer_mesh(*scene, m, factor); };
  return f;
}

RegularBeam beam_of(const Scene& s, long R) {
  const Section sec = s.section();
  RegularBeam b;
  b.EI = s.material.E * sec.Iy;
  b.rhoA = s.material.rho * sec.A;
  b.L = s.geometry.length;
  b.R = R;
  b.k0 = s.x0.translational;
  b.r0 = s.x0.rotational;
  b.kL = s.xL.translational;
  b.rL = s.xL.rotational;
  return b;
}

Capability DifferenceEqSolver::supports(const Scene& s) const {
  Capability c;
  if (!s.is_beam()) {
    c.reason = fmt::format("difference_eq solves beams only (a regular chain of Hermite beam elements); {}s are not "
                           "supported",
                           to_string(s.kind));
    return c;
  }
  if (s.is_stepped() || s.has_tapered_pieces()) {
    c.reason = fmt::format("difference_eq cannot model a {} ([[segments]]): its closed forms need a regular chain of "
                           "identical elements",
                           s.has_tapered_pieces() ? "tapered piece" : "stepped beam");
    return c;
  }
  c.modes = c.statics = true;
  c.frf = false;
  // The model restrictions (Euler-Bernoulli, bending in x-z) are stated by do_solve in the
  // result's warnings; here only what is not computed at all.
  c.reason = "FRF is not implemented by difference_eq (modes and statics only)";
  if (s.rotor) {
    const std::string why = rotor_refusal(s);
    c.campbell = why.empty();
    if (!why.empty()) c.reason += "; " + why;
  }
  if (!s.point_supports.empty() && rigid_body_modes(beam_of(s, 1)) > 0) {
    c.statics = false;
    c.reason += "; statics with supports between the ends need end supports that hold the beam by themselves "
                "(the points' reactions are superposed on that beam's closed form)";
  }
  return c;
}

// The closed forms cost O(1) per mode and O(R) per load; the banded FE check O(R) per solve.
ResourceEstimate DifferenceEqSolver::estimate(const Scene& s, const Discretization& mesh, const Options&) const {
  ResourceEstimate e;
  if (mesh.counts.size() != 1) return e;
  const double R = mesh.counts[0];
  const double loads = static_cast<double>(s.loads.size()), probes = static_cast<double>(s.request.probes.size());
  e.bytes = 400.0 * R + 64.0 * loads * probes;
  e.seconds = 2e-7 * R * (2 + loads) + 1e-7 * loads * probes + 2e-4 * s.request.modes;
  e.basis = fmt::format("R = {} elements, {} loads, {} probes, {} modes", mesh.counts[0], s.loads.size(),
                        s.request.probes.size(), s.request.modes);
  return e;
}

std::vector<OptionSpec> DifferenceEqSolver::option_specs() const {
  using T = OptionSpec::Type;
  return {{"static_method", T::Choice,
           config_.static_method == StaticMethod::PiecewiseCubic ? "piecewise-cubic" : "eigenfunction-expansion",
           {"piecewise-cubic", "eigenfunction-expansion"}, 0, 0,
           "statics: clamped-clamped solution by the closed piecewise cubic (O(R)) or by the paper's eigenfunction "
           "expansion (7) (O(R^2))"},
          {"residual_check_max_R", T::Integer, std::to_string(config_.residual_check_max_R), {}, 0, 1e7,
           "check the closed-form mode shapes against the assembled equations up to this R (O(R) per mode)"}};
}

std::unique_ptr<Kernels> DifferenceEqSolver::build(const Scene& s, const Discretization& mesh, const Options& options,
                                                   Result& res) const {
  if (mesh.counts.size() != 1)
    throw InputError("command line", "--mesh",
                     "difference_eq takes one integer R >= 1, the number of elements (got '" + mesh.spec() + "')");
  const long R = mesh.counts[0];
  if (R < 1 || R > RegularBeam::kMaxElements)
    throw InputError("command line", "--mesh",
                     fmt::format("R must satisfy 1 <= R <= {} (got '{}')", RegularBeam::kMaxElements, mesh.spec()));
  return make_kernels(s, R, options, res);
}

}  // namespace modalbench::difference_eq
