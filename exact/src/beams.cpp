#include "modalbench/exact/beams.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <functional>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "line_models.hpp"
#include "modalbench/gauss_legendre.hpp"

namespace modalbench::exact {

namespace {

using detail::BarLine;
using detail::BendingLine;
using detail::kInf;
using detail::note_unknowns;
using detail::bending_restrained;

Frequencies to_frequencies(const LineSpectrum& spec, const SliceStats& st) {
  Frequencies f;
  f.unknowns = st.max_unknowns;
  f.rigid = spec.rigid;
  f.unresolved = spec.unresolved;
  f.count_evaluations = st.count_evaluations;
  for (double lam : spec.lambdas) f.omega_rad_s.push_back(std::sqrt(std::max(lam, 0.0)));
  return f;
}

}  // namespace

bool detail::bending_restrained(EndSprings l, EndSprings r, const PointAttachments& points) {
  int translational = (l.translational > 0) + (r.translational > 0), rotational = (l.rotational > 0) + (r.rotational > 0);
  for (const PointAttachment& p : points) {
    translational += p.springs.translational > 0;
    rotational += p.springs.rotational > 0;
  }
  return translational >= 2 || (translational >= 1 && rotational >= 1);
}

namespace {

bool bar_restrained(double k_left, double k_right, const PointAttachments& points) {
  bool any = k_left > 0 || k_right > 0;
  for (const PointAttachment& p : points) any = any || p.springs.translational > 0;
  return any;
}

/// Makes the ends of the distributed loads (and, where there are any, the probes) nodes of the line.
void add_load_nodes(LineSystem& sys, double L, const DistributedLineLoads& dist, const std::vector<double>& probes) {
  if (dist.empty()) return;
  for (const DistributedLineLoad& q : dist) {
    sys.nodes_at.push_back(q.x_from / L);
    sys.nodes_at.push_back(q.x_to / L);
  }
  for (double x : probes) sys.nodes_at.push_back(x / L);
}

/// The distributed loads as Gauss-point loads (`unit(q)`: the nodal load vector of a point force q,
/// the line's dimensionless units): 4 per segment of a uniform piece, exact (beams.hpp); 16 per
/// segment of a tapered piece or under a load with a factor (8-point Gauss-Legendre on each half:
/// the fixed-end reactions there are smooth, not polynomial, and each tapered gap has at least 8
/// segments: the rule's error falls as (segment / distance to the profile's singularity)^16).
void add_distributed(const LineSystem& sys, const AssembledLine& asmb, double L, const DistributedLineLoads& dist,
                     const std::function<Eigen::VectorXd(double)>& unit, std::vector<LinePoint>& points,
                     Eigen::VectorXd& f) {
  static constexpr std::array<double, 4> node = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                                 0.8611363115940526};
  static constexpr std::array<double, 4> weight = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                                   0.3478548451374538};
  for (const DistributedLineLoad& q : dist) {
    const double a = q.x_from / L, b = q.x_to / L;
    // A Gauss point at xi of the rule on a part `width` long (dimensionless) with weight `w`.
    const auto add = [&](double xi, double width, double w) {
      const double t = (xi - a) / (b - a);
      double force = (q.q_from + (q.q_to - q.q_from) * t) * 0.5 * width * L * w;  // N
      if (q.factor) force *= q.factor(xi * L);
      points.push_back({xi, unit(force)});
      add_point_load(sys, asmb, 0.0, points.back(), f);
    };
    for (std::size_t i = 0; i + 1 < asmb.xi.size(); ++i) {
      const double lo = std::max(a, asmb.xi[i]), hi = std::min(b, asmb.xi[i + 1]);
      if (!(hi > lo)) continue;
      if (!q.factor && !sys.variation_at(0.5 * (asmb.xi[i] + asmb.xi[i + 1]))) {
        for (std::size_t g = 0; g < node.size(); ++g)
          add(0.5 * (lo + hi) + 0.5 * (hi - lo) * node[g], hi - lo, weight[g]);
        continue;
      }
      for (const auto& [l, h] : {std::pair{lo, 0.5 * (lo + hi)}, std::pair{0.5 * (lo + hi), hi}})
        for (std::size_t g = 0; g < gauss_legendre8::node.size(); ++g)
          for (const double sign : {-1.0, 1.0})
            add(0.5 * (l + h) + sign * 0.5 * (h - l) * gauss_legendre8::node[g], h - l, gauss_legendre8::weight[g]);
    }
  }
}

}  // namespace

Frequencies beam_bending_frequencies(const BeamBending& beam, EndSprings left, EndSprings right, int k,
                                     const PointAttachments& points) {
  BendingLine line(beam, left, right, points);
  SliceStats st;
  // Scale: Omega = 1.
  const auto spec = lowest_eigenvalues(line.sys, k, 1.0 / line.lam_to_Omega2, &st);
  return to_frequencies(spec, st);
}

Frequencies bar_frequencies(const Bar& bar, double k_left, double k_right, int k, const PointAttachments& points) {
  BarLine line(bar, k_left, k_right, points);
  SliceStats st;
  const auto spec = lowest_eigenvalues(line.sys, k, 1.0 / line.lam_to_Omega2, &st);
  return to_frequencies(spec, st);
}

std::vector<BendingResponse> beam_static(const BeamBending& beam, EndSprings left, EndSprings right,
                                         const std::vector<LineLoad>& loads, const std::vector<double>& probes,
                                         double moment_sign, long* unknowns, const PointAttachments& supports,
                                         const DistributedLineLoads& dist, std::vector<SupportReaction>* reactions) {
  if (!bending_restrained(left, right, supports))
    throw std::runtime_error(
        "mechanism: the supports do not restrain rigid translation and rotation in bending "
        "(need translational springs at two points, or a translational and a rotational one)");
  BendingLine line(beam, left, right, supports);
  const double L = beam.L;
  // Point loads and probes lie inside segments (exact fixed-end reactions and transfer): no node
  // is made for them, so close points never make a short, stiff segment. Distributed loads make
  // nodes of their ends and of the probes.
  add_load_nodes(line.sys, L, dist, probes);
  AssembledLine asmb = assemble(line.sys, 0.0);
  note_unknowns(unknowns, asmb);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(asmb.K.nodes() * 2);
  std::vector<LinePoint> points;
  for (auto& p : loads) {
    points.push_back({p.x / L, Eigen::Vector2d(p.force * L * L / beam.EI, moment_sign * p.moment * L / beam.EI)});
    add_point_load(line.sys, asmb, 0.0, points.back(), f);
  }
  add_distributed(line.sys, asmb, L, dist, [&](double force) -> Eigen::VectorXd {
    return Eigen::Vector2d(force * L * L / beam.EI, 0.0);
  }, points, f);
  const Eigen::VectorXd d = solve_line(line.sys, asmb, 0.0, f);
  if (reactions)
    for (const LineReaction& r : line_reactions(line.sys, asmb, d, f))
      reactions->push_back({r.xi * L, r.r[0] * beam.EI / (L * L), moment_sign * r.r[1] * beam.EI / L});
  // The state [w, phi, Q, M] has Q = -dM/dx (beams.hpp); forces scaled by EI / L^2 and EI / L.
  std::vector<BendingResponse> out;
  for (double x : probes) {
    const Eigen::VectorXd y = state_at(line.sys, asmb, 0.0, d, points, x / L);
    out.push_back({y[0] * L, moment_sign * y[1], y[3] * beam.EI / L, -y[2] * beam.EI / (L * L)});
  }
  return out;
}

std::vector<double> bar_static(const Bar& bar, double k_left, double k_right, const std::vector<LineLoad>& loads,
                               const std::vector<double>& probes, long* unknowns, const PointAttachments& supports,
                               const DistributedLineLoads& dist, std::vector<SupportReaction>* reactions,
                               std::vector<double>* forces) {
  if (!bar_restrained(k_left, k_right, supports))
    throw std::runtime_error("mechanism: no support restrains the bar (axial or torsional rigid motion)");
  BarLine line(bar, k_left, k_right, supports);
  add_load_nodes(line.sys, bar.L, dist, probes);
  AssembledLine asmb = assemble(line.sys, 0.0);
  note_unknowns(unknowns, asmb);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(asmb.K.nodes());
  std::vector<LinePoint> points;
  for (auto& p : loads) {
    points.push_back({p.x / bar.L, Eigen::VectorXd::Constant(1, p.force * bar.L / bar.S)});
    add_point_load(line.sys, asmb, 0.0, points.back(), f);
  }
  add_distributed(line.sys, asmb, bar.L, dist, [&](double force) -> Eigen::VectorXd {
    return Eigen::VectorXd::Constant(1, force * bar.L / bar.S);
  }, points, f);
  const Eigen::VectorXd d = solve_line(line.sys, asmb, 0.0, f);
  if (reactions)
    for (const LineReaction& r : line_reactions(line.sys, asmb, d, f))
      reactions->push_back({r.xi * bar.L, r.r[0] * bar.S / bar.L, 0.0});
  std::vector<double> out;
  for (double x : probes) {
    const Eigen::VectorXd y = state_at(line.sys, asmb, 0.0, d, points, x / bar.L);
    out.push_back(y[0]);
    if (forces) forces->push_back(y[1] * bar.S / bar.L);  // N = S u', scaled by S / L
  }
  return out;
}

double beam_receptance(const BeamBending& beam, EndSprings left, EndSprings right, double excite, double observe,
                       double omega, long* unknowns, const PointAttachments& attachments) {
  BendingLine line(beam, left, right, attachments);
  const double lam = omega * omega;
  AssembledLine asmb = assemble(line.sys, lam);
  note_unknowns(unknowns, asmb);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(asmb.K.nodes() * 2);
  const std::vector<LinePoint> points = {{excite / beam.L, Eigen::Vector2d(beam.L * beam.L / beam.EI, 0.0)}};
  add_point_load(line.sys, asmb, lam, points[0], f);
  const Eigen::VectorXd d = solve_line(line.sys, asmb, lam, f);
  return displacement_at(line.sys, asmb, lam, d, points, observe / beam.L)[0] * beam.L;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A piece's bending properties from its section and shear coefficient (`I`: Iy or Iz).
BendingProps bending_props(const Material& m, const Section& sec, double kappa, double Section::*I, bool eb) {
  return {m.E * (sec.*I), eb ? kInf : kappa * m.G * sec.A, m.rho * sec.A, eb ? 0.0 : m.rho * (sec.*I)};
}

/// A tapered piece's bending variation: its properties at x, and the comparison over [x0, x1] from
/// Segment::bounds_on (NaN where the weakest section does not exist: the line cuts further).
BendingVariation bending_variation(const Segment& p, double Section::*I, bool eb) {
  return {[p, I, eb](double x) { return bending_props(p.material, p.properties_at(x), p.kappa_at(x), I, eb); },
          [p, I, eb](double x0, double x1) {
            const Segment::Bounds b = p.bounds_on(x0, x1);
            if (!b.weakest_exists) return BendingProps{kNaN, kNaN, kNaN, kNaN};
            const BendingProps lo = bending_props(p.material, b.weakest, b.kappa_lo, I, eb);
            const BendingProps hi = bending_props(p.material, b.heaviest, b.kappa_lo, I, eb);
            return BendingProps{lo.EI, lo.kGA, hi.rhoA, hi.rhoI};
          }};
}

/// A scene's beam in one plane, piece by piece; `I` picks the piece's second moment (Iy or Iz).
BeamBending bending_of(const Scene& s, double Section::*I) {
  const bool eb = s.theory == Theory::EulerBernoulli;
  BeamBending out;
  out.L = s.geometry.length;
  for (const Segment& p : s.beam_pieces()) {
    const BendingProps at = bending_props(p.material, p.properties_at(p.x_from), p.kappa_at(p.x_from), I, eb);
    const BendingVariation v = p.tapered() ? bending_variation(p, I, eb) : BendingVariation{};
    if (p.x_from == 0.0) {
      out.EI = at.EI;
      out.kGA = at.kGA;
      out.rhoA = at.rhoA;
      out.rhoI = at.rhoI;
      out.varies = v;
    } else {
      out.steps.push_back({p.x_from, at.EI, at.kGA, at.rhoA, at.rhoI, v});
    }
  }
  return out;
}

/// A scene's beam as a bar, piece by piece: stiffness and inertia per length from the section at x
/// (`props`), and a tapered piece's comparison (S from the weakest section, mu from the heaviest).
Bar bar_of(const Scene& s, const std::function<BarProps(const Material&, const Section&)>& props) {
  Bar out;
  out.L = s.geometry.length;
  for (const Segment& p : s.beam_pieces()) {
    const BarProps at = props(p.material, p.properties_at(p.x_from));
    BarVariation v;
    if (p.tapered())
      v = {[p, props](double x) { return props(p.material, p.properties_at(x)); },
           [p, props](double x0, double x1) {
             const Segment::Bounds b = p.bounds_on(x0, x1);
             if (!b.weakest_exists) return BarProps{kNaN, kNaN};
             return BarProps{props(p.material, b.weakest).S, props(p.material, b.heaviest).mu};
           }};
    if (p.x_from == 0.0) {
      out.S = at.S;
      out.mu = at.mu;
      out.varies = v;
    } else {
      out.steps.push_back({p.x_from, at.S, at.mu, v});
    }
  }
  return out;
}

}  // namespace

BeamBending BeamBending::at(double x) const {
  BeamBending b{EI, kGA, rhoA, rhoI, L, {}};
  const BendingVariation* v = varies ? &varies : nullptr;
  for (const BendingStep& s : steps)
    if (x >= s.x_from) {
      b = {s.EI, s.kGA, s.rhoA, s.rhoI, L, {}};
      v = s.varies ? &s.varies : nullptr;
    }
  if (v) {
    const BendingProps p = v->at(x);
    b = {p.EI, p.kGA, p.rhoA, p.rhoI, L, {}};
  }
  return b;
}

bool BeamBending::tapered() const {
  return static_cast<bool>(varies) || std::any_of(steps.begin(), steps.end(), [](const BendingStep& s) { return static_cast<bool>(s.varies); });
}

Bar Bar::at(double x) const {
  Bar b{S, mu, L, {}};
  const BarVariation* v = varies ? &varies : nullptr;
  for (const BarStep& s : steps)
    if (x >= s.x_from) {
      b = {s.S, s.mu, L, {}};
      v = s.varies ? &s.varies : nullptr;
    }
  if (v) {
    const BarProps p = v->at(x);
    b = {p.S, p.mu, L, {}};
  }
  return b;
}

bool Bar::tapered() const {
  return static_cast<bool>(varies) || std::any_of(steps.begin(), steps.end(), [](const BarStep& s) { return static_cast<bool>(s.varies); });
}

BeamBending bending_xz(const Scene& s) { return bending_of(s, &Section::Iy); }
BeamBending bending_xy(const Scene& s) { return bending_of(s, &Section::Iz); }

Bar axial_bar(const Scene& s) {
  return bar_of(s, [](const Material& m, const Section& sec) { return BarProps{m.E * sec.A, m.rho * sec.A}; });
}

Bar torsion_bar(const Scene& s) {
  return bar_of(s, [](const Material& m, const Section& sec) { return BarProps{m.G * sec.J, m.rho * sec.Ip}; });
}

}  // namespace modalbench::exact
