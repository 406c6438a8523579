// dtfm's meshes (dtfm.hpp): a beam's prism sections (one prism by default: the beam itself), a
// plate's strips across its width; the ladder, the stress meshes, and the error estimate's
// coarser and finer meshes.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "modalbench/dtfm/dtfm.hpp"
#include "staircase.hpp"

namespace modalbench::dtfm {

namespace {

/// The least strip count in [lo, hi] that is a multiple of 4 and puts every point of the plate's
/// loads, probes, point supports, masses and FRF points on a strip line (y = j b / n) on it and on
/// its two halvings (the error estimate's meshes), or -1 where none does or there is no such point
/// off the edges. Off the lines a point is
/// shared between the two lines around it, in proportions that change from mesh to mesh: the
/// deflection under the paper plate's point load (y = b / 3) came out 9.7e-4 off on 92 strips
/// (refined from 24) where the estimate from 61 and 92 said 2.1e-4; on 96 strips it is 1.5e-4 off,
/// estimated 3.9e-4.
int strips_on_points(const Scene& s, long lo, long hi) {
  std::vector<double> ys;
  for (const PointLoad& p : s.all_point_loads()) ys.push_back(p.y);
  for (const auto& p : s.request.probes) ys.push_back(p[1]);
  for (const PointSupport& p : s.point_supports) ys.push_back(p.y);
  for (const PointMass& p : s.masses) ys.push_back(p.y);
  if (s.request.frf) ys.insert(ys.end(), {s.request.frf->excite[1], s.request.frf->observe[1]});
  // The edges are lines of every mesh; a plate without inner points keeps its count.
  std::erase_if(ys, [&](double y) { return y <= 0.0 || y >= s.geometry.width; });
  if (ys.empty()) return -1;
  for (long n = lo + (4 - lo % 4) % 4; n <= hi; n += 4) {
    bool on = true;
    for (double y : ys) {
      const double t = y / s.geometry.width * static_cast<double>(n / 4);
      on = on && std::abs(t - std::round(t)) <= 1e-9 * static_cast<double>(n);
    }
    if (on) return static_cast<int>(n);
  }
  return -1;
}

/// A beam: one prism; a plate: about 6 strips per half-wave across the width of the requested
/// modes, with the points on strip lines where a count below twice that puts them there.
Discretization default_mesh(const Scene& scene) {
  // A beam: one prism, the beam of the scene's theory itself (no discretization error). A section
  // cut into prisms (2x2, ...) tends to 3D elasticity, another model: a deliberate --mesh choice.
  if (!scene.is_plate()) return Discretization::parse("1x1");
  // Strips across the width: about 6 per half-wave across it among the requested modes, and the
  // points on strip lines where a count below twice that puts them there.
  const int n_max = plate_half_waves(scene.geometry.length, scene.geometry.width, std::max(1, scene.request.modes)).second;
  // A tolerance below 6e-4 starts (6e-4 / tolerance)^(1/4) times finer where the strip ends are
  // held (the family whose frequencies are extrapolated at fourth order): on the paper plate as a
  // Mindlin plate (8 modes) the 24 strips of 6 per half-wave gave an extrapolated estimate of 2.5e-3
  // (mode 8 not yet asymptotic), 36 strips 9.5e-5 and 48 strips 2.0e-5, so at 1e-4 the refinement
  // went 24 -> 60 (0.42 s) where 38 strips meet it at once.
  const auto held = [](const Support& e) { return e.kind == "pinned" || e.kind == "clamped"; };
  const double tol = scene.request.tolerance;
  const double finer = held(scene.x0) && held(scene.xL) && tol > 0 && tol < 6e-4 ? std::pow(6e-4 / tol, 0.25) : 1.0;
  const int n = std::clamp(static_cast<int>(std::ceil(6 * (n_max + 1) * finer)), 10, 400);
  const int on = strips_on_points(scene, n, std::min(2 * n, 400));
  return Discretization{{on > 0 ? on : n}};
}

/// Halved counts (order 2; a plate's strips with held ends extrapolated at fourth order); none for
/// a one-prism beam (exact for its model).
std::optional<CoarserMesh> coarser_mesh(const Scene& scene, const Discretization& mesh) {
  if (scene.is_plate()) {
    if (mesh.counts.size() != 1 || mesh.counts[0] < 4) return std::nullopt;
    const int n = mesh.counts[0] / 2;
    // Strips: the extrapolated frequencies converge at fourth order where both strip ends (x0, xL)
    // are held, pinned or clamped (tests/solvers/test_extrapolation_orders: the paper plate; its
    // variants with the long edges clamped or free were within their estimates too). A free or
    // sprung end is not extrapolated: on NAFEMS FV16's cantilever the 32-strip values came out
    // 1.7e-4 and 4.8e-4 off (modes 2 and 5) where the estimates said 1.8e-5 and 3.0e-5 (against
    // rfem's 192 x 192 extrapolation, itself within 1.7e-5).
    const auto held = [](const Support& e) { return e.kind == "pinned" || e.kind == "clamped"; };
    const double next = held(scene.x0) && held(scene.xL) ? 4.0 : std::numeric_limits<double>::quiet_NaN();
    return CoarserMesh{{{n}}, static_cast<double>(mesh.counts[0]) / n, 2.0, next};
  }
  // A one-prism beam is the exact Timoshenko beam of its section: no discretization error.
  if (mesh.counts.empty() || *std::max_element(mesh.counts.begin(), mesh.counts.end()) < 2) return std::nullopt;
  CoarserMesh c;
  c.ratio = 1;
  for (int n : mesh.counts) {
    c.mesh.counts.push_back(std::max(1, n / 2));
    c.ratio = std::max(c.ratio, static_cast<double>(n) / c.mesh.counts.back());
  }
  if (c.mesh.counts.size() == 1) c.mesh.counts.push_back(c.mesh.counts[0]);
  c.order = 2;
  return c;
}

/// A plate's strips times the factor, on the points where they can be; none for beams (sections
/// tend to 3D: not a default).
std::optional<Discretization> finer_mesh(const Scene& scene, const Discretization& mesh, double factor) {
  if (!scene.is_plate() || mesh.counts.size() != 1) return std::nullopt;  // sections tend to 3D: not a default
  const long n = std::lround(std::ceil(mesh.counts[0] * factor));
  if (n > 400) return std::nullopt;
  const int on = strips_on_points(scene, n, std::min<long>(2 * n, 400));  // the points on strip lines
  return Discretization{{on > 0 ? on : static_cast<int>(n)}};
}

/// Beam: 1x1, 2x2, 4x4, 8x8 (spatial physics: up to 6x6; only uniform rectangles are cut); plate:
/// 4, 7, 10, 20, 40 strips.
std::vector<Discretization> mesh_ladder(const Scene& scene) {
  std::vector<const char*> specs;
  if (scene.is_plate()) specs = {"4", "7", "10", "20", "40"};
  else if (scene.cross_section.shape != SectionShape::Rectangle || scene.is_stepped() ||
           scene.physics == Physics::Lateral)
    specs = {"1x1"};  // only uniform rectangles are cut, and not for a rotor's lateral model
  else if (scene.physics == Physics::Spatial) specs = {"1x1", "2x2", "4x4", "6x6"};  // 6 fields per prism
  else specs = {"1x1", "2x2", "4x4", "8x8"};
  std::vector<Discretization> out;
  for (const char* m : specs) out.push_back(Discretization::parse(m));
  return out;
}

/// How far a beam's tapered pieces vary: the largest |ln(end / start)| of A, Iy and Iz over them.
double taper_spread(const Scene& scene) {
  double g = 0;
  for (const Segment& p : scene.segments)
    if (p.tapered()) {
      const Section a = p.properties_at(p.x_from), b = p.properties_at(p.x_to);
      for (double r : {b.A / a.A, b.Iy / a.Iy, b.Iz / a.Iz}) g = std::max(g, std::abs(std::log(r)));
    }
  return g;
}

/// A tapered beam: one prism per section and N uniform steps per tapered piece (staircase.hpp),
/// second order in 1 / N, halved for the estimate, multiplied by the refinement's factor. The
/// default N from the tolerance: the staircase's error was about 0.1 (g / N)^2 with g the taper's
/// spread (taper_spread) on SDLL09 (g = 5.8, mode 5: 7.9e-4 at 64 steps) and SDLL10 (g = 1.2), and
/// the estimate from N / 2 and N / 4 carries a factor of safety up to 3: N = g sqrt(0.3 / tol).
MeshFamily tapered_family(const Scene& scene) {
  MeshFamily f;
  const double tol = scene.request.tolerance > 0 ? scene.request.tolerance : 1e-3;
  const double g = std::max(0.5, taper_spread(scene));
  const int n = std::clamp(static_cast<int>(std::ceil(g * std::sqrt(0.3 / tol))), 8, detail::kMaxSteps);
  f.default_mesh = detail::staircase_mesh(n + n % 2);
  for (int k : {4, 8, 16, 32, 64}) f.ladder.push_back(detail::staircase_mesh(k));
  f.theory = f.default_mesh;
  f.stress = {detail::staircase_mesh(detail::kMaxSteps)};
  f.coarser = [](const Discretization& m) -> std::optional<CoarserMesh> {
    const int steps = detail::staircase_steps(m);
    if (steps < 2 * detail::kMinSteps) return std::nullopt;
    // The midpoint staircase's error expands in even powers of 1 / N (test_tapered measures the
    // extrapolated values' order 4 on SDLL10): its values are extrapolated.
    return CoarserMesh{detail::staircase_mesh(steps / 2), static_cast<double>(steps) / (steps / 2), 2.0, 4.0};
  };
  f.finer = [](const Discretization& m, double factor) -> std::optional<Discretization> {
    const int now = detail::staircase_steps(m);
    if (now >= detail::kMaxSteps) return std::nullopt;
    const long steps = std::min<long>(std::lround(std::ceil(now * factor)), detail::kMaxSteps);
    return detail::staircase_mesh(static_cast<int>(steps + steps % 2));  // even: its halving is exact
  };
  return f;
}

}  // namespace

MeshFamily DtfmSolver::meshes(const Scene& scene, const Options&) const {
  if (scene.has_tapered_pieces()) return tapered_family(scene);
  MeshFamily f;
  f.default_mesh = default_mesh(scene);
  f.ladder = mesh_ladder(scene);
  // A beam: one prism (the scene's beam theory itself); a plate: the default strips.
  f.theory = scene.is_plate() ? f.default_mesh : Discretization::parse("1x1");
  f.stress = {f.ladder.back()};
  // The closures keep a copy of the scene: the family outlives the caller's.
  auto s = std::make_shared<const Scene>(scene);
  f.coarser = [s](const Discretization& m) { return coarser_mesh(*s, m); };
  f.finer = [s](const Discretization& m, double factor) { return finer_mesh(*s, m, factor); };
  return f;
}

}  // namespace modalbench::dtfm
