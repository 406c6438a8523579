#include "modalbench/exact/beams.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <functional>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "line_models.hpp"

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

/// The distributed loads as Gauss-point loads, 4 per segment they cover (exact: see beams.hpp);
/// `unit(q)` is the nodal load vector of a point force q (the line's dimensionless units).
void add_distributed(const LineSystem& sys, const AssembledLine& asmb, double L, const DistributedLineLoads& dist,
                     const std::function<Eigen::VectorXd(double)>& unit, std::vector<LinePoint>& points,
                     Eigen::VectorXd& f) {
  static constexpr std::array<double, 4> node = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                                 0.8611363115940526};
  static constexpr std::array<double, 4> weight = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                                   0.3478548451374538};
  for (const DistributedLineLoad& q : dist) {
    const double a = q.x_from / L, b = q.x_to / L;
    for (std::size_t i = 0; i + 1 < asmb.xi.size(); ++i) {
      const double lo = std::max(a, asmb.xi[i]), hi = std::min(b, asmb.xi[i + 1]);
      if (!(hi > lo)) continue;
      for (std::size_t g = 0; g < node.size(); ++g) {
        const double xi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * node[g];
        const double t = (xi - a) / (b - a);
        const double force = (q.q_from + (q.q_to - q.q_from) * t) * 0.5 * (hi - lo) * L * weight[g];  // N
        points.push_back({xi, unit(force)});
        add_point_load(sys, asmb, 0.0, points.back(), f);
      }
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

/// A scene's beam in one plane, piece by piece; `I` picks the piece's second moment (Iy or Iz).
BeamBending bending_of(const Scene& s, double Section::*I) {
  const bool eb = s.theory == Theory::EulerBernoulli;
  BeamBending out;
  out.L = s.geometry.length;
  for (const Segment& p : s.beam_pieces()) {
    const Section sec = p.properties();
    const Material& m = p.material;
    const BendingStep b{p.x_from, m.E * (sec.*I), eb ? kInf : m.kappa * m.G * sec.A, m.rho * sec.A,
                        eb ? 0.0 : m.rho * (sec.*I)};
    if (p.x_from == 0.0) {
      out.EI = b.EI;
      out.kGA = b.kGA;
      out.rhoA = b.rhoA;
      out.rhoI = b.rhoI;
    } else {
      out.steps.push_back(b);
    }
  }
  return out;
}

/// A scene's beam as a bar, piece by piece: stiffness and inertia per length from the piece.
Bar bar_of(const Scene& s, const std::function<std::pair<double, double>(const Segment&)>& props) {
  Bar out;
  out.L = s.geometry.length;
  for (const Segment& p : s.beam_pieces()) {
    const auto [S, mu] = props(p);
    if (p.x_from == 0.0) {
      out.S = S;
      out.mu = mu;
    } else {
      out.steps.push_back({p.x_from, S, mu});
    }
  }
  return out;
}

}  // namespace

BeamBending BeamBending::at(double x) const {
  BeamBending b{EI, kGA, rhoA, rhoI, L, {}};
  for (const BendingStep& s : steps)
    if (x >= s.x_from) b = {s.EI, s.kGA, s.rhoA, s.rhoI, L, {}};
  return b;
}

Bar Bar::at(double x) const {
  Bar b{S, mu, L, {}};
  for (const BarStep& s : steps)
    if (x >= s.x_from) b = {s.S, s.mu, L, {}};
  return b;
}

BeamBending bending_xz(const Scene& s) { return bending_of(s, &Section::Iy); }
BeamBending bending_xy(const Scene& s) { return bending_of(s, &Section::Iz); }

Bar axial_bar(const Scene& s) {
  return bar_of(s, [](const Segment& p) {
    const Section sec = p.properties();
    return std::pair{p.material.E * sec.A, p.material.rho * sec.A};
  });
}

Bar torsion_bar(const Scene& s) {
  return bar_of(s, [](const Segment& p) {
    const Section sec = p.properties();
    return std::pair{p.material.G * sec.J, p.material.rho * sec.Ip};
  });
}

}  // namespace modalbench::exact
