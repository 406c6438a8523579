// rfem's meshes (rfem.hpp): the default mesh from the geometry and the modes, the ladder, the
// stress meshes, and the error estimate's coarser and finer meshes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <vector>

#include "modalbench/rfem/rfem.hpp"

namespace modalbench::rfem {

namespace {

/// At least n elements and one cell per gap between the beam's features (ends, steps, supports
/// between the ends, point masses), so that no two of them act on one rigid element (a support
/// 1 mm from a clamped end on the end's element: every mesh of the family clamped the same element
/// twice and converged, to 1e-9 by its estimate, to a span 1.6e-3 short in frequency); then the
/// smallest count in [that, 2 that) whose element centres or cell boundaries (x = j L / (2 n'))
/// hold every feature (halving then keeps most of them there), or that count where none does.
/// Features closer than 2^-20 L share a cell (the estimate's coarser meshes then say so).
int beam_mesh_on_features(const Scene& s, int n) {
  std::vector<double> at;
  for (std::size_t i = 1; i < s.segments.size(); ++i) at.push_back(s.segments[i].x_from / s.geometry.length);
  for (const PointSupport& p : s.point_supports) at.push_back(p.x / s.geometry.length);
  for (const PointMass& p : s.masses) at.push_back(p.x / s.geometry.length);
  if (at.empty()) return n;
  std::vector<double> all = at;
  all.insert(all.end(), {0.0, 1.0});
  std::sort(all.begin(), all.end());
  double gap = 1.0;
  for (std::size_t i = 0; i + 1 < all.size(); ++i)
    if (all[i + 1] - all[i] > 1e-12) gap = std::min(gap, all[i + 1] - all[i]);
  const int lo = std::max(n, std::min(1 << 20, static_cast<int>(std::ceil(1.0 / gap - 1e-9))));
  for (int m = lo + lo % 2; m < 2 * lo; m += 2) {
    bool all_on = true;
    for (double t : at) all_on = all_on && std::abs(t * 2 * m - std::round(t * 2 * m)) <= 1e-9 * 2 * m;
    if (all_on) return m;
  }
  return lo;
}

/// About 32 segments per half-wave of a beam's highest requested mode; a plate's ~10 fragments per
/// half-wave in each direction.
Discretization default_mesh(const Scene& s) {
  const int k = std::max(1, s.request.modes);
  if (s.is_frame()) {
    // The modes spread over the members: about 8 segments on the shortest member per mode asked,
    // a power of 2 from 16 (second order: ~1e-3 on the first modes).
    int n = 16;
    while (n < 8L * (k + 1) && n < (1 << 16)) n *= 2;
    return {{n}};
  }
  if (s.is_beam()) {
    // About 32 segments per half-wave of the highest requested mode (second order: ~1e-3).
    int n = 128;
    while (n < 32L * (k + 1) && n < (1 << 17)) n *= 2;
    return {{beam_mesh_on_features(s, n)}};
  }
  // Half-waves of the first k modes of the plate (simply supported pattern), ~10 fragments per
  // half-wave in each direction, and cells no more elongated than 3 : 1.
  const double a = s.geometry.length, b = s.geometry.width;
  const auto [m_max, n_max] = plate_half_waves(a, b, k);
  long nx = 10L * (m_max + 1), ny = 10L * (n_max + 1);
  nx = std::max<long>(nx, std::lround(std::min(1e6, std::ceil(a / b * static_cast<double>(ny) / 3.0))));
  ny = std::max<long>(ny, std::lround(std::min(1e6, std::ceil(b / a * static_cast<double>(nx) / 3.0))));
  // Multiples of 8: the error estimate's halvings (H, 2H and the fourth mesh 4H) are then uniform
  // coarsenings, which the Richardson extrapolation needs (50 x 40 halved twice gave 12 x 10: not
  // extrapolated, and the default path refined to the mesh's own estimate instead).
  nx = std::clamp<long>(nx + (8 - nx % 8) % 8, 8, 2000);
  ny = std::clamp<long>(ny + (8 - ny % 8) % 8, 8, 2000);
  return {{static_cast<int>(nx), static_cast<int>(ny)}};
}

std::vector<Discretization> mesh_ladder(const Scene& s) {
  std::vector<Discretization> v;
  if (s.is_frame()) {
    for (int f : {2, 4, 8, 16, 32, 64}) v.push_back({{f}});
    return v;
  }
  if (s.is_beam()) {
    // Steps, supports and masses on element centres or cell boundaries, as the default mesh: off
    // them a step's cell changes with every mesh and the errors fall unevenly (a stepped shaft on
    // 8 ... 256: ratios 2.2 to 7.3 per halving, and no gain from Richardson). Doubling keeps them there.
    const int n0 = beam_mesh_on_features(s, 8);
    for (int f : {1, 2, 4, 8, 16, 32}) v.push_back({{n0 * f}});
    return v;
  }
  const double a = s.geometry.length, b = s.geometry.width, longest = std::max(a, b);
  const int nx0 = std::max(2, static_cast<int>(std::lround(10.0 * a / longest)));
  const int ny0 = std::max(2, static_cast<int>(std::lround(10.0 * b / longest)));
  for (int f : {1, 2, 4, 8}) v.push_back({{nx0 * f, ny0 * f}});
  return v;
}

std::vector<Discretization> stress_meshes(const Scene& s) {
  if (s.is_frame()) return {{{4096}}};
  if (s.is_beam()) return {{{10000}}, {{100000}}};
  const double a = s.geometry.length, b = s.geometry.width, longest = std::max(a, b);
  return {{{std::max(2, static_cast<int>(std::lround(100.0 * a / longest))),
            std::max(2, static_cast<int>(std::lround(100.0 * b / longest)))}}};
}

std::optional<CoarserMesh> coarser_mesh(const Scene& s, const Discretization& mesh) {
  // The term after h^2 is h^3, beams and plates alike (measured against the exact solutions in
  // tests/solvers/test_extrapolation_orders.cpp: the extrapolated frequencies of NAFEMS FV5's beam,
  // the Lasecka beam, the spatial cantilever and the paper plate converge at third order; only
  // the symmetric clamped-clamped paper beam shows fourth).
  if (s.is_beam() && mesh.counts.size() == 1 && mesh.counts[0] >= 2)
    return CoarserMesh{{{mesh.counts[0] / 2}}, static_cast<double>(mesh.counts[0]) / (mesh.counts[0] / 2), 2.0, 3.0};
  // Frames: each member's segments halve with n (frame_member_segments is linear in n for even n);
  // the next order is not measured on frames yet, so no extrapolation.
  if (s.is_frame() && mesh.counts.size() == 1 && mesh.counts[0] >= 2 && mesh.counts[0] % 2 == 0)
    return CoarserMesh{{{mesh.counts[0] / 2}}, 2.0, 2.0, std::numeric_limits<double>::quiet_NaN()};
  // Plates: halve each side that keeps at least 2 fragments (a side too coarse to halve stays).
  if (s.is_plate() && mesh.counts.size() == 2 && std::max(mesh.counts[0], mesh.counts[1]) >= 4) {
    const int nx = mesh.counts[0] >= 4 ? mesh.counts[0] / 2 : mesh.counts[0];
    const int ny = mesh.counts[1] >= 4 ? mesh.counts[1] / 2 : mesh.counts[1];
    return CoarserMesh{{{nx, ny}}, std::max(static_cast<double>(mesh.counts[0]) / nx, static_cast<double>(mesh.counts[1]) / ny), 2.0,
                       3.0};
  }
  return std::nullopt;
}

/// The next mesh of a plate's graded sequence n0 x {1, 1.5, 2, 3, 4, 6, 8, ...}: x 4/3 from counts
/// whose common divisor has the factor 3 (the last step was x 1.5), x 1.5 otherwise. Even counts
/// stay on the sequence (a default mesh is a multiple of 8).
Discretization graded_step(const Discretization& mesh) {
  const int g = std::gcd(mesh.counts[0], mesh.counts[1]);
  Discretization d;
  for (int n : mesh.counts) d.counts.push_back(g % 3 == 0 ? n / 3 * 4 : n / 2 * 3);
  return d;
}

/// The least half-integer factor f >= `factor` with every count times f a multiple of 8 (f = 2
/// always is one for counts that are).
double multiple_of_8_factor(const Discretization& mesh, double factor) {
  for (double f = std::max(1.5, std::ceil(2.0 * factor - 1e-9) / 2.0);; f += 0.5) {
    bool ok = true;
    for (int n : mesh.counts) {
      const double m = n * f;
      ok = ok && m == std::floor(m) && static_cast<long>(m) % 8 == 0;
    }
    if (ok) return f;
  }
}

/// A plate mesh on which the default path refines by graded steps: even counts, and nothing whose
/// error depends on its place within a cell (probes, point supports, masses).
bool evenly_converging(const Scene& s, const Discretization& mesh) {
  return mesh.counts.size() == 2 &&
         std::all_of(mesh.counts.begin(), mesh.counts.end(), [](int n) { return n >= 2 && n % 2 == 0; }) &&
         s.request.probes.empty() && s.point_supports.empty() && s.masses.empty();
}

std::optional<Discretization> finer_mesh(const Scene& s, const Discretization& mesh, double factor) {
  // A plate whose errors fall evenly (no probe, point support or mass sits in its cells, where
  // the error changes with the place in the cell from mesh to mesh) refines by one step of its
  // graded sequence (x 1.5, then x 4/3, ...), whatever factor is asked: the refinement's last
  // meshes are then at most 1.5 apart, and the window the estimate and the extrapolation judge lies
  // in the asymptotic range as early as it can. One jump by the factor asked left the coarse end of
  // the window behind: the Mindlin paper plate at 1e-4 went 56 x 40 -> 112 x 80, judged mode 8 on
  // 28 x 20 and 14 x 10 (pre-asymptotic: estimate 1.6e-4 for a true 1.3e-5) and went on to
  // 168 x 120 (2.7 s in all); graded, 84 x 60 -> 112 x 80 meets it (0.6 s), and 1e-5 on 168 x 120
  // (1.5 s, where the jumps took 56 x 40 -> 224 x 160 -> 448 x 320, 37 s). With a point feature,
  // graded steps took 4.7 s where jumps took 1.2 s (a deflection beside a point support at 1e-3).
  if (s.is_plate() && evenly_converging(s, mesh)) {
    Discretization d = graded_step(mesh);
    if (std::max(d.counts[0], d.counts[1]) > 2000) return std::nullopt;
    return d;
  }
  // Otherwise a plate mesh of multiples of 8 (default_mesh) grows by the least factor of 1.5, 2,
  // 2.5, ... (at least the one asked) that keeps every count a multiple of 8: the refined mesh, the
  // one before it and that one's halving are then uniform coarsenings of each other, which the
  // extrapolation needs.
  const bool whole = s.is_plate() && std::all_of(mesh.counts.begin(), mesh.counts.end(), [](int n) { return n % 8 == 0; });
  if (whole) factor = multiple_of_8_factor(mesh, factor);
  Discretization d;
  for (int n : mesh.counts) {
    long m = std::lround(std::ceil(n * factor));
    m += m % 2;
    if (m > (s.is_plate() ? 2000L : 2000000L)) return std::nullopt;
    d.counts.push_back(static_cast<int>(m));
  }
  return d;
}

}  // namespace

MeshFamily RfemSolver::meshes(const Scene& s, const Options&) const {
  MeshFamily f;
  f.default_mesh = default_mesh(s);
  f.ladder = mesh_ladder(s);
  f.theory = f.default_mesh;
  f.stress = stress_meshes(s);
  // Twice the other families' where the steps are graded: two of them make one doubling (the
  // Mindlin paper plate at 1e-5 takes three).
  f.refinement_steps = s.is_plate() && evenly_converging(s, f.default_mesh) ? 6 : 3;
  // The closures keep a copy of the scene: the family outlives the caller's.
  auto scene = std::make_shared<const Scene>(s);
  f.coarser = [scene](const Discretization& m) { return coarser_mesh(*scene, m); };
  f.finer = [scene](const Discretization& m, double factor) { return finer_mesh(*scene, m, factor); };
  return f;
}

}  // namespace modalbench::rfem
