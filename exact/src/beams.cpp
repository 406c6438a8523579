#include "modalbench/exact/beams.hpp"

#include <Eigen/Dense>
#include <algorithm>
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

Frequencies to_frequencies(const LineSpectrum& spec, const SliceStats& st) {
  Frequencies f;
  f.unknowns = st.max_unknowns;
  f.rigid = spec.rigid;
  f.unresolved = spec.unresolved;
  f.count_evaluations = st.count_evaluations;
  for (double lam : spec.lambdas) f.omega_rad_s.push_back(std::sqrt(std::max(lam, 0.0)));
  return f;
}

bool bending_restrained(EndSprings l, EndSprings r) {
  const bool some_t = l.translational > 0 || r.translational > 0;
  const bool some_r = l.rotational > 0 || r.rotational > 0;
  return (some_t && some_r) || (l.translational > 0 && r.translational > 0);
}

}  // namespace

Frequencies beam_bending_frequencies(const BeamBending& beam, EndSprings left, EndSprings right, int k) {
  BendingLine line(beam, left, right);
  SliceStats st;
  // Scale: Omega = 1.
  const auto spec = lowest_eigenvalues(line.sys, k, 1.0 / line.lam_to_Omega2, &st);
  return to_frequencies(spec, st);
}

Frequencies bar_frequencies(const Bar& bar, double k_left, double k_right, int k) {
  BarLine line(bar, k_left, k_right);
  SliceStats st;
  const auto spec = lowest_eigenvalues(line.sys, k, 1.0 / line.lam_to_Omega2, &st);
  return to_frequencies(spec, st);
}

std::vector<BendingResponse> beam_static(const BeamBending& beam, EndSprings left, EndSprings right,
                                         const std::vector<LineLoad>& loads, const std::vector<double>& probes,
                                         double moment_sign, long* unknowns) {
  if (!bending_restrained(left, right))
    throw std::runtime_error(
        "mechanism: the end supports do not restrain rigid translation and rotation in bending "
        "(need translational springs at both ends, or a translational and a rotational one)");
  BendingLine line(beam, left, right);
  const double L = beam.L;
  // Loads and probes lie inside segments (exact fixed-end reactions and transfer): no node is
  // made for them, so close points never make a short, stiff segment.
  AssembledLine asmb = assemble(line.sys, 0.0);
  note_unknowns(unknowns, asmb);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(asmb.K.nodes() * 2);
  std::vector<LinePoint> points;
  for (auto& p : loads) {
    points.push_back({p.x / L, Eigen::Vector2d(p.force * L * L / beam.EI, moment_sign * p.moment * L / beam.EI)});
    add_point_load(line.sys, asmb, 0.0, points.back(), f);
  }
  const Eigen::VectorXd d = solve_line(line.sys, asmb, 0.0, f);
  std::vector<BendingResponse> out;
  for (double x : probes) {
    const Eigen::VectorXd u = displacement_at(line.sys, asmb, 0.0, d, points, x / L);
    out.push_back({u[0] * L, moment_sign * u[1]});
  }
  return out;
}

std::vector<double> bar_static(const Bar& bar, double k_left, double k_right, const std::vector<LineLoad>& loads,
                               const std::vector<double>& probes, long* unknowns) {
  if (!(k_left > 0 || k_right > 0))
    throw std::runtime_error("mechanism: neither end restrains the bar (axial or torsional rigid motion)");
  BarLine line(bar, k_left, k_right);
  AssembledLine asmb = assemble(line.sys, 0.0);
  note_unknowns(unknowns, asmb);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(asmb.K.nodes());
  std::vector<LinePoint> points;
  for (auto& p : loads) {
    points.push_back({p.x / bar.L, Eigen::VectorXd::Constant(1, p.force * bar.L / bar.S)});
    add_point_load(line.sys, asmb, 0.0, points.back(), f);
  }
  const Eigen::VectorXd d = solve_line(line.sys, asmb, 0.0, f);
  std::vector<double> out;
  for (double x : probes) out.push_back(displacement_at(line.sys, asmb, 0.0, d, points, x / bar.L)[0]);
  return out;
}

double beam_receptance(const BeamBending& beam, EndSprings left, EndSprings right, double excite, double observe,
                       double omega, long* unknowns) {
  BendingLine line(beam, left, right);
  const double lam = omega * omega;
  AssembledLine asmb = assemble(line.sys, lam);
  note_unknowns(unknowns, asmb);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(asmb.K.nodes() * 2);
  const std::vector<LinePoint> points = {{excite / beam.L, Eigen::Vector2d(beam.L * beam.L / beam.EI, 0.0)}};
  add_point_load(line.sys, asmb, lam, points[0], f);
  const Eigen::VectorXd d = solve_line(line.sys, asmb, lam, f);
  return displacement_at(line.sys, asmb, lam, d, points, observe / beam.L)[0] * beam.L;
}

BeamBending bending_xz(const Scene& s) {
  const Section sec = s.section();
  const auto& m = s.material;
  const bool eb = s.theory == Theory::EulerBernoulli;
  return {m.E * sec.Iy, eb ? kInf : m.kappa * m.G * sec.A, m.rho * sec.A, eb ? 0.0 : m.rho * sec.Iy, s.geometry.length};
}

BeamBending bending_xy(const Scene& s) {
  const Section sec = s.section();
  const auto& m = s.material;
  const bool eb = s.theory == Theory::EulerBernoulli;
  return {m.E * sec.Iz, eb ? kInf : m.kappa * m.G * sec.A, m.rho * sec.A, eb ? 0.0 : m.rho * sec.Iz, s.geometry.length};
}

}  // namespace modalbench::exact
