#include "modalbench/exact/exact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "beam_attachments.hpp"
#include "exact_shapes.hpp"
#include "frames.hpp"
#include "plate_responses.hpp"
#include "rotor.hpp"
#include "modalbench/rotor_scene.hpp"

namespace modalbench::exact {

namespace {

bool simply_supported(const Support& e) { return std::isinf(e.translational) && e.rotational == 0.0; }
EndSprings bend(const Support& s) { return {s.translational, s.rotational}; }

enum class PlateMethod { None, Navier, Levy, LevyTransposed, Mindlin };
PlateMethod plate_method(const Scene& s, std::string& why) {
  const bool ssx = simply_supported(s.x0) && simply_supported(s.xL);
  const bool ssy = simply_supported(s.y0) && simply_supported(s.yB);
  if (s.theory == Theory::Mindlin) {
    if (ssx && ssy) return PlateMethod::Mindlin;
    why = "exact Mindlin plate only for all edges simply supported";
    return PlateMethod::None;
  }
  if (ssx && ssy) return PlateMethod::Navier;
  if (ssx) return PlateMethod::Levy;
  if (ssy) return PlateMethod::LevyTransposed;
  why = "exact Kirchhoff plate needs one pair of opposite edges simply supported (Levy)";
  return PlateMethod::None;
}

/// Modes collected from several families (each from its own line), sorted at the end.
struct ModeEntry {
  double omega = 0;
  ModeFamily family = ModeFamily::Unknown;  ///< as reported (Rigid for rigid-body modes)
  ModeFamily line = ModeFamily::Unknown;    ///< the line (family) that produced it
  int index = 0;                            ///< within that line; Navier: m
  int rigid_count = 0;                      ///< of that line; Navier: n
};
struct ModeList {
  std::vector<ModeEntry> modes;
  void add(const std::vector<double>& w, int rigid, ModeFamily fam) {
    for (std::size_t i = 0; i < w.size(); ++i)
      modes.push_back({w[i], static_cast<int>(i) < rigid ? ModeFamily::Rigid : fam, fam, static_cast<int>(i), rigid});
  }
  void add(const Frequencies& f, ModeFamily fam) { add(f.omega_rad_s, f.rigid, fam); }
};

/// Count evaluations and the largest dynamic stiffness factorized.
void note(Result& r, const Frequencies& f) {
  r.summary.set_diagnostic("count_evaluations", std::max(0.0, r.summary.diagnostic("count_evaluations")) +
                                                    static_cast<double>(f.count_evaluations));
  r.summary.unknowns = std::max(r.summary.unknowns, f.unknowns);
  if (f.unresolved > 0)
    r.summary.raise(Status::NumericalIssue,
                    fmt::format("exact: {} eigenvalue(s) below what the mode count resolves (springs far softer than "
                                "the structure: near-rigid modes) are reported as 0 but are not rigid-body modes",
                                f.unresolved));
}

void beam_modes(const Scene& s, ModeList& list, Result& r) {
  const int k = s.request.modes;
  auto fxz = beam_bending_frequencies(bending_xz(s), bend(s.x0), bend(s.xL), k, line_points(s, ModeFamily::BendingXZ));
  list.add(fxz, ModeFamily::BendingXZ);
  note(r, fxz);
  if (carries_axial(s.physics)) {
    auto fa = bar_frequencies(axial_bar(s), s.x0.axial, s.xL.axial, k, line_points(s, ModeFamily::Axial));
    list.add(fa, ModeFamily::Axial);
    note(r, fa);
  }
  if (carries_xy(s.physics)) {
    auto fxy = beam_bending_frequencies(bending_xy(s), bend(s.x0), bend(s.xL), k, line_points(s, ModeFamily::BendingXY));
    list.add(fxy, ModeFamily::BendingXY);
    note(r, fxy);
  }
  if (carries_torsion(s.physics)) {
    auto ft = bar_frequencies(torsion_bar(s), s.x0.torsional, s.xL.torsional, k, line_points(s, ModeFamily::Torsion));
    list.add(ft, ModeFamily::Torsion);
    note(r, ft);
  }
}

void beam_statics(const Scene& s, Result& r) {
  std::vector<double> xs;
  for (auto& p : s.request.probes) xs.push_back(p[0]);
  std::vector<Deflection> defl(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) defl[i].position = {xs[i], 0.0};
  std::vector<LineLoad> lz, la, ly, lt;
  for (auto& p : s.all_point_loads()) {
    lz.push_back({p.x, p.Fz, p.My});
    la.push_back({p.x, p.Fx, 0});
    ly.push_back({p.x, p.Fy, p.Mz});
    lt.push_back({p.x, p.Mx, 0});
  }
  DistributedLineLoads dz, da, dy;
  for (const DistributedLoad& q : s.all_distributed_loads()) {
    auto add = [&](DistributedLineLoads& to, const std::array<double, 2>& v) {
      if (v[0] != 0.0 || v[1] != 0.0) to.push_back({q.from[0], q.to[0], v[0], v[1], q.factor});
    };
    add(dz, q.qz);
    add(da, q.qx);
    add(dy, q.qy);
  }
  long& n = r.summary.unknowns;
  std::vector<SupportReaction> rz, ra, ry, rt;
  auto wz = beam_static(bending_xz(s), bend(s.x0), bend(s.xL), lz, xs, -1.0, &n, line_points(s, ModeFamily::BendingXZ), dz, &rz);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    defl[i].w = wz[i].w;
    defl[i].theta_y = wz[i].theta;
    defl[i].has_forces = true;
    defl[i].forces.My = wz[i].M;
    defl[i].forces.Qz = wz[i].Q;
  }
  if (carries_axial(s.physics)) {
    std::vector<double> N;
    auto u = bar_static(axial_bar(s), s.x0.axial, s.xL.axial, la, xs, &n, line_points(s, ModeFamily::Axial), da, &ra, &N);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      defl[i].u = u[i];
      defl[i].forces.N = N[i];
    }
  }
  if (carries_xy(s.physics)) {
    auto wy = beam_static(bending_xy(s), bend(s.x0), bend(s.xL), ly, xs, +1.0, &n, line_points(s, ModeFamily::BendingXY), dy, &ry);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      defl[i].v = wy[i].w;
      defl[i].theta_z = wy[i].theta;
      defl[i].forces.Mz = wy[i].M;
      defl[i].forces.Qy = wy[i].Q;
    }
  }
  if (carries_torsion(s.physics)) {
    std::vector<double> T;
    auto t = bar_static(torsion_bar(s), s.x0.torsional, s.xL.torsional, lt, xs, &n, line_points(s, ModeFamily::Torsion), {}, &rt, &T);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      defl[i].theta_x = t[i];
      defl[i].forces.T = T[i];
    }
  }
  r.deflections = defl;
  // Bending in x-z: Fz and My (the line's moment is My already, moment_sign applied); in x-y:
  // Fy and Mz; the bars: Fx and Mx.
  r.reactions = gather_reactions(s, rz, ra, ry, rt);
}

void beam_frf(const Scene& s, Result& r) {
  const auto& f = *s.request.frf;
  if (s.material.loss_factor > 0)
    r.summary.warnings.push_back("exact FRF is undamped: material.loss_factor is not applied");
  const BeamBending b = bending_xz(s);
  const PointAttachments frf_points = line_points(s, ModeFamily::BendingXZ);
  int skipped = 0;
  std::string reason;
  for (int i = 0; i < f.points; ++i) {
    const double w = f.omega_min + (f.omega_max - f.omega_min) * i / (f.points - 1);
    try {
      r.frf.push_back({w, beam_receptance(b, bend(s.x0), bend(s.xL), f.excite[0], f.observe[0], w, &r.summary.unknowns, frf_points)});
    } catch (const std::runtime_error& e) {
      // On a natural frequency (or at 0 for a mechanism) K(omega) is singular: no finite receptance.
      // Anything else that fails is a numerical breakdown, and is said as such below.
      if (reason.empty()) reason = fmt::format("at {:.6g} rad/s: {}", w, e.what());
      ++skipped;
    }
  }
  note_frf_omissions(r.summary, skipped, f.points, reason);
}

void plate_modes(const Scene& s, PlateMethod pm, ModeList& list, Result& r) {
  const int k = s.request.modes;
  const double a = s.geometry.length, b = s.geometry.width, h = s.geometry.height;
  const auto& m = s.material;
  const double D = s.plate_D(), rho_h = m.rho * h;
  switch (pm) {
    case PlateMethod::Navier:
      r.summary.method = "exact Kirchhoff plate, Navier (all edges simply supported)";
      for (const NavierMode& nm : navier_modes(a, b, D, rho_h, k))
        list.modes.push_back({nm.omega, ModeFamily::Plate, ModeFamily::Plate, nm.m, nm.n});
      break;
    case PlateMethod::Mindlin:
      r.summary.method = "exact Mindlin plate (all edges simply supported), every branch";
      list.add(mindlin_ss_frequencies(a, b, h, m.E, m.nu, m.G, m.kappa, m.rho, k), 0, ModeFamily::Plate);
      break;
    case PlateMethod::Levy: {
      r.summary.method = "exact Kirchhoff plate, Levy (x-edges simply supported): dynamic stiffness + count";
      auto f = levy_frequencies(a, b, D, m.nu, rho_h, bend(s.y0), bend(s.yB), k);
      list.add(f.omega_rad_s, 0, ModeFamily::Plate);
      note(r, f);
      break;
    }
    case PlateMethod::LevyTransposed: {
      r.summary.method = "exact Kirchhoff plate, Levy (y-edges simply supported): dynamic stiffness + count";
      auto f = levy_frequencies(b, a, D, m.nu, rho_h, bend(s.x0), bend(s.xL), k);
      list.add(f.omega_rad_s, 0, ModeFamily::Plate);
      note(r, f);
      break;
    }
    case PlateMethod::None: break;
  }
}

ModeShapes shapes_frame(const Scene& s) {
  ModeShapes out;
  out.points = s.shape_points();
  out.components = s.shape_components();
  out.total_mass = s.material.rho * s.geometry.height * s.geometry.length * s.geometry.width;
  if (s.is_beam()) {
    out.total_mass = 0;
    for (const Segment& p : s.beam_pieces()) out.total_mass += p.mass();
    for (const PointMass& pm : s.masses) out.total_mass += pm.mass;  // as rfem and dtfm
  }
  out.directions = {s.is_beam() && carries_axial(s.physics), s.is_beam() && carries_xy(s.physics), true};
  return out;
}

/// Index of component `dof` in the shapes' component list (-1: not carried).
int slot(const ModeShapes& ms, int dof) {
  for (std::size_t c = 0; c < ms.components.size(); ++c)
    if (ms.components[c] == dof) return static_cast<int>(c);
  return -1;
}

ModeShapes beam_shapes(const Scene& s, const std::vector<ModeEntry>& modes) {
  ModeShapes out = shapes_frame(s);
  std::vector<double> xs;
  for (const auto& p : out.points) xs.push_back(p[0]);
  const bool moments = s.request.shapes && s.request.shapes->moments;
  for (const auto& e : modes) {
    std::vector<std::vector<double>> mode(out.components.size(), std::vector<double>(xs.size(), 0.0));
    std::array<double, 3> gamma{0, 0, 0};
    LineShape ls;
    auto put = [&](int dof, const std::vector<double>& v, double sign) {
      if (const int c = slot(out, dof); c >= 0)
        for (std::size_t i = 0; i < v.size(); ++i) mode[static_cast<std::size_t>(c)][i] = sign * v[i];
    };
    switch (e.line) {
      case ModeFamily::BendingXZ:
        ls = bending_shape(bending_xz(s), bend(s.x0), bend(s.xL), e.omega, e.index, e.rigid_count, xs,
                           line_points(s, ModeFamily::BendingXZ));
        put(2, ls.disp, 1.0);
        put(4, ls.rot, -1.0);  // theta_y = -phi
        gamma[2] = ls.participation;
        if (moments) out.moments.push_back(ls.moment);
        break;
      case ModeFamily::BendingXY:
        ls = bending_shape(bending_xy(s), bend(s.x0), bend(s.xL), e.omega, e.index, e.rigid_count, xs,
                           line_points(s, ModeFamily::BendingXY));
        put(1, ls.disp, 1.0);
        put(5, ls.rot, 1.0);  // theta_z = +phi
        gamma[1] = ls.participation;
        break;
      case ModeFamily::Axial:
        ls = bar_shape(axial_bar(s), s.x0.axial, s.xL.axial, e.omega, xs, line_points(s, ModeFamily::Axial));
        put(0, ls.disp, 1.0);
        gamma[0] = ls.participation;
        break;
      case ModeFamily::Torsion:
        ls = bar_shape(torsion_bar(s), s.x0.torsional, s.xL.torsional, e.omega, xs, line_points(s, ModeFamily::Torsion));
        put(3, ls.disp, 1.0);
        break;
      default: throw std::logic_error("exact beam mode without a line");
    }
    if (moments && out.moments.size() == out.values.size()) out.moments.emplace_back(xs.size(), 0.0);  // no My
    out.values.push_back(std::move(mode));
    out.generalized_mass.push_back(ls.modal_mass);
    out.participation.push_back(gamma);
  }
  out.note = "exact: the null vector of the exact dynamic stiffness at each frequency, the fields between nodes by "
             "the transfer matrix; modal mass and participation by GSL quadrature of the exact fields; each mode "
             "belongs to one family (bending x-z, x-y, axial, torsion)";
  finish_mode_shapes(out);
  return out;
}

/// False when the plate's method has no shapes (Mindlin).
bool plate_shapes(const Scene& s, const std::vector<ModeEntry>& modes, ModeShapes& out) {
  std::string why;
  const PlateMethod pm = plate_method(s, why);
  if (pm == PlateMethod::Mindlin || pm == PlateMethod::None) return false;
  out = shapes_frame(s);
  const double a = s.geometry.length, b = s.geometry.width, D = s.plate_D();
  const double rho_h = s.material.rho * s.geometry.height, nu = s.material.nu;
  for (const auto& e : modes) {
    PlateShape ps;
    if (pm == PlateMethod::Navier) ps = navier_shape(a, b, rho_h, e.index, e.rigid_count, out.points);
    else if (pm == PlateMethod::Levy) ps = levy_shape(a, b, D, nu, rho_h, bend(s.y0), bend(s.yB), e.omega, out.points, false);
    else ps = levy_shape(b, a, D, nu, rho_h, bend(s.x0), bend(s.xL), e.omega, out.points, true);
    out.values.push_back({ps.w, ps.theta_x, ps.theta_y});
    out.generalized_mass.push_back(ps.modal_mass);
    out.participation.push_back({0.0, 0.0, ps.participation});
  }
  out.note = pm == PlateMethod::Navier
                 ? "exact: Navier modes sin(m pi x/a) sin(n pi y/b) in closed form (repeated frequencies: the (m, n) "
                   "and (n, m) modes, orthogonal)"
                 : "exact: Levy modes W(y) sin(m pi x/a), W from the null vector of the strip's exact dynamic "
                   "stiffness and its transfer matrix; modal mass and participation by GSL quadrature";
  finish_mode_shapes(out);
  return true;
}

/// The exact references of one scene: beams and bars by their lines' dynamic stiffness, plates by
/// Navier, Levy and the Mindlin closed form (the scene's supports choose).
class ExactKernels final : public Kernels {
 public:
  ExactKernels(const Scene& s, const Options& o) : s_(s), o_(o) {}

  void modes(Result& r) override {
    if (s_.is_frame()) {
      detail::frame_modes(s_, r);
      return;
    }
    if (s_.is_beam()) {
      beam_modes(s_, list_, r);
    } else {
      std::string why;
      const PlateMethod pm = plate_method(s_, why);
      if (pm == PlateMethod::None) throw std::runtime_error(why);
      plate_modes(s_, pm, list_, r);
    }
    auto& modes = list_.modes;
    std::stable_sort(modes.begin(), modes.end(), [](auto& x, auto& y) { return x.omega < y.omega; });
    if (static_cast<int>(modes.size()) > s_.request.modes) modes.resize(s_.request.modes);
    for (const auto& e : modes) {
      r.frequencies_rad_s.push_back(e.omega);
      r.mode_families.push_back(e.family);
    }
  }
  void shapes(Result& r) override {
    if (s_.is_frame()) r.summary.warnings.push_back("mode shapes are not computed for frames yet");
    else if (s_.is_beam()) r.mode_shapes = beam_shapes(s_, list_.modes);
    else if (!plate_shapes(s_, list_.modes, r.mode_shapes))
      r.summary.warnings.push_back("mode shapes are not computed for the exact Mindlin plate");
  }
  void statics(Result& r) override {
    if (s_.is_frame()) detail::frame_statics(s_, r);
    else if (s_.is_beam()) beam_statics(s_, r);
    else detail::navier_statics(s_, static_cast<int>(o_.resolved.get_integer("navier_static_terms")), r);
  }
  void frf(Result& r) override {
    if (s_.is_beam()) beam_frf(s_, r);
    else detail::navier_frf(s_, static_cast<int>(o_.resolved.get_integer("navier_frf_terms")), r);
  }
  void campbell(Result& r) override { r.campbell = detail::rotor_campbell(s_, r.summary); }

 private:
  const Scene& s_;
  const Options& o_;
  ModeList list_;
};

/// The shaft's bending frequencies below a spin, about (as a pinned uniform beam of its weaker
/// plane, the discs' mass spread over it): the modes a Campbell diagram must reach at that spin.
double modes_below(const Scene& s, double spin) {
  const Section sec = s.section();
  double mass = s.material.rho * sec.A * s.geometry.length;
  for (const PointMass& m : s.masses) mass += m.mass;
  const double EI = s.material.E * std::max(std::min(sec.Iy, sec.Iz), 1e-300), L = s.geometry.length;
  const double omega1 = std::numbers::pi * std::numbers::pi / (L * L) * std::sqrt(EI * L / mass);
  return omega1 > 0 ? std::floor(std::sqrt(std::min(spin / omega1, 1e18))) : 0.0;
}

/// A rotor's Campbell diagram, from the modes' cost `modes_s(n)`. Per spin: an axisymmetric shaft's
/// two whirl lines, each a count like the modes' (measured: 2.6 ms per spin on the Timoshenko
/// shaft's 4 roots, 13 ms on Friswell's two-disc rotor's 6), and the critical speeds below the top
/// spin; an asymmetric shaft's modes of both planes up to the spin (doubled until they pass it). A
/// spin far above the shaft's frequencies (E = 0.5 Pa for 0.5 GPa: 1e7 times the first) takes
/// thousands of modes per spin: that is what refuses it up front.
double rotor_seconds(const Scene& s, double k, const std::function<double(double)>& modes_s) {
  const double spins = static_cast<double>(s.rotor->spin.size()), top = s.rotor->spin.back();
  const double below_top = std::min(modes_below(s, top), 1e9);
  if (axisymmetric_shaft(s)) return spins * 2.5 * modes_s(k) + 2.0 * modes_s(below_top + 1);
  double per_spin = 0;
  for (const double spin : s.rotor->spin) per_spin += 2.0 * 2.0 * modes_s(std::max(k, std::min(modes_below(s, spin), 1e9) + k));
  return per_spin + 2.0 * 2.0 * modes_s(std::max(4.0 * k, below_top + 1));
}

}  // namespace

Capability ExactSolver::supports(const Scene& s) const {
  Capability c;
  if (s.is_frame()) {
    c.modes = c.statics = true;
    return c;
  }
  if (s.is_beam()) {
    c.modes = c.statics = c.frf = true;
    if (s.rotor) {
      c.reason = detail::rotor_refusal(s);
      c.campbell = c.reason.empty();
    }
    return c;
  }
  if (!s.point_supports.empty() || !s.masses.empty()) {
    c.reason = "exact has no closed form for a plate with supports or masses at points (its plates are Navier and "
               "Levy series); rfem models them";
    return c;
  }
  std::string why;
  const PlateMethod pm = plate_method(s, why);
  c.modes = pm != PlateMethod::None;
  c.statics = c.frf = pm == PlateMethod::Navier;
  if (!c.statics)
    c.reason = (why.empty() ? "" : why + "; ") +
               "exact plate statics and FRF only for a simply supported Kirchhoff plate (Navier)";
  for (const PointLoad& p : s.loads)
    if (c.statics && (p.Mx != 0 || p.My != 0)) {
      c.statics = false;
      c.reason = "exact's plate series take forces, not point moments (loads[].Mx, My); rfem models them";
    }
  return c;
}

std::vector<OptionSpec> ExactSolver::option_specs() const {
  using T = OptionSpec::Type;
  return {{"navier_static_terms", T::Integer, "2000", {}, 10, 20000,
           "Navier plate statics: about this squared terms, balanced to the aspect (m / a = n / b), doubled up to 4 "
           "times while the deflections' tail exceeds the tolerance (the driving point converges like terms^-2)"},
          {"navier_frf_terms", T::Integer, "300", {}, 10, 5000,
           "Navier plate FRF: about this squared terms to start, balanced to the aspect (m / a = n / b), doubled "
           "up to 64 times while the tail exceeds the tolerance"}};
}

// Beams: bisection on the Wittrick-Williams count over a line cut into pieces with |p| h <= 1, so
// a count costs O(pieces) and the pieces grow with the highest wavenumber: k modes cost O(k^2)
// (measured: 500 modes of a Timoshenko beam in 31 s). An FRF sample costs a solve over the pieces
// at that frequency (measured 2e-4 s per piece and sample: 400 samples up to the ~200th mode, 54 s).
// Plates: closed forms (Navier, Mindlin) or one line per half-wave number (Levy).
ResourceEstimate ExactSolver::estimate(const Scene& s, const Discretization&, const Options& o) const {
  ResourceEstimate e;
  const auto& rq = s.request;
  const double k = std::max(0, rq.modes);
  double pieces_frf = 0;
  if (s.is_frame()) return detail::frame_estimate(s);
  if (s.is_beam()) {
    // The counts' long segments cost O(log k) per gap between features (ends, steps, point
    // supports and masses), with a few more gaps where a halving's clamped frequency lies next to
    // the count's: measured on the paper beam (one gap) without its FRF, 1000 modes 0.9 s, 2000
    // 1.9 s, 4000 6.2 s, 8000 13 s.
    const double gaps = 1.0 + static_cast<double>(s.segments.size() + s.point_supports.size() + s.masses.size());
    // A tapered piece is cut into segments of |p| h <= 1 at every count, each a Magnus product
    // (measured on SDLL10, one tapered piece: 4 modes 0.57 s, 10 modes 1.86 s, 20 modes 6.2 s).
    const double tapered = static_cast<double>(
        std::count_if(s.segments.begin(), s.segments.end(), [](const Segment& p) { return p.tapered(); }));
    const auto uniform_s = [gaps](double n) { return 0.65e-4 * n * std::log2(n + 2) * (1.0 + gaps); };
    const auto tapered_s = [tapered](double n) { return tapered * (0.0104 * n * n + 0.1 * n); };
    const auto modes_s = [&](double n) { return uniform_s(n) + tapered_s(n); };
    e.seconds = modes_s(k);
    // rotor_seconds charges 2.5 mode counts per spin (measured on uniform shafts); a tapered
    // shaft's whirl lines cost about one count of its modes per spin (the conical shaft: 31 spins
    // in 16 s, 0.52 s per spin against 0.57 s for its 4 modes).
    if (s.rotor) e.seconds += rotor_seconds(s, k, [&](double n) { return uniform_s(n) + tapered_s(n) / 2.5; });
    if (rq.frf) {
      const Section sec = s.section();
      const double EI = s.material.E * std::max(sec.Iy, 1e-300), rhoA = s.material.rho * sec.A;
      const double p = std::pow(rq.frf->omega_max * rq.frf->omega_max * rhoA / EI, 0.25);
      pieces_frf = std::max(1.0, std::min(p * s.geometry.length, 1e12)) + static_cast<double>(s.loads.size());
      e.seconds += 2e-4 * pieces_frf * rq.frf->points / 3.0;
    }
    e.bytes = 2e3 * std::max(k, pieces_frf) + 1e3 * static_cast<double>(s.loads.size() + rq.probes.size());
  } else {
    const double terms_s = static_cast<double>(o.resolved.get_integer("navier_static_terms"));
    const double terms_f = static_cast<double>(o.resolved.get_integer("navier_frf_terms"));
    e.seconds = 1e-6 * k * std::log2(k + 2) + 2e-4 * k +
                2e-9 * terms_s * terms_s * static_cast<double>(rq.probes.size() * std::max<std::size_t>(1, s.loads.size())) +
                (rq.frf ? 4e-9 * terms_f * terms_f * rq.frf->points : 0.0);
    e.bytes = 200.0 * k;
  }
  e.basis = fmt::format("{} modes{}{}", rq.modes,
                        pieces_frf > 0 ? fmt::format(", FRF over ~{:.3g} pieces x {} samples", pieces_frf, rq.frf->points) : "",
                        s.rotor && s.is_beam() ? fmt::format(", {} spins up to {:.3g} rad/s, about {:.3g} shaft modes below it",
                                                             s.rotor->spin.size(), s.rotor->spin.back(),
                                                             modes_below(s, s.rotor->spin.back()))
                                               : "");
  return e;
}

std::unique_ptr<Kernels> ExactSolver::build(const Scene& s, const Discretization& mesh, const Options& o,
                                            Result& r) const {
  if (!mesh.counts.empty())
    throw InputError("command line", "--mesh", "the exact back-end has no mesh (got '" + mesh.spec() + "')");
  r.summary.converges_to_scene_theory = true;  // it is the scene's theory
  r.summary.model = fmt::format("the exact {} {}", to_string(s.theory), to_string(s.kind));
  if (s.is_beam())
    r.summary.method = fmt::format("exact {} beam: dynamic stiffness + Wittrick-Williams count", to_string(s.theory));
  if (s.is_frame()) r.summary.method = detail::frame_method(s);
  if (s.is_beam() && s.has_tapered_pieces())
    r.summary.method +=
        "; tapered pieces: transfer matrices by the sixth-order Magnus integrator, steps doubled until two agree "
        "(estimated error below 1e-15 of each matrix, refused above 1e-12), the count kept exact by cutting them until "
        "each segment's comparison piece (its lowest stiffness, its highest inertia) has no clamped frequency below "
        "omega; loads on them by 16 Gauss points per segment";
  return std::make_unique<ExactKernels>(s, o);
}

}  // namespace modalbench::exact
