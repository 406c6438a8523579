// The reduced-order state-space model of a scene (rom.hpp): a modal solve sampled at the inputs
// and outputs, the static flexibility for D, and the full receptance for the H-infinity check,
// each through the back-end's own Solver::solve.
#include "modalbench/rom.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

namespace modalbench {

namespace {

std::string where(const Scene& s, const std::array<double, 2>& p) {
  return s.is_beam() ? fmt::format("x = {:g} m", p[0]) : fmt::format("(x, y) = ({:g}, {:g}) m", p[0], p[1]);
}

/// The scene without its loads and requests (the structure alone), undamped.
Scene structure_of(const Scene& scene) {
  Scene s = scene;
  s.loads.clear();
  s.line_loads.clear();
  s.pressures.clear();
  s.gravity.reset();
  const double tol = s.request.tolerance;
  s.request = Request{};
  s.request.tolerance = tol;
  s.material.loss_factor = 0;
  for (Segment& p : s.segments) p.material.loss_factor = 0;
  return s;
}

Options without_estimate() {
  Options o;
  o.estimate_error = false;
  return o;
}

/// phi[mode][point] of w at the inputs then the outputs, and the frequencies.
struct Modes {
  std::vector<double> omega;
  std::vector<std::vector<double>> w;
};

Modes modes_at(const Result& r, std::size_t points) {
  Modes m;
  const auto& ms = r.mode_shapes;
  const auto wi =
      static_cast<std::size_t>(std::find(ms.components.begin(), ms.components.end(), 2) - ms.components.begin());
  for (std::size_t n = 0; n < std::min(r.frequencies_rad_s.size(), ms.values.size()); ++n) {
    m.omega.push_back(r.frequencies_rad_s[n]);
    m.w.push_back(std::vector<double>(ms.values[n][wi].begin(), ms.values[n][wi].begin() + static_cast<long>(points)));
  }
  return m;
}

/// G(output, input): w at the outputs under a unit Fz at each input (the back-end's statics).
std::optional<Eigen::MatrixXd> static_flexibility(const Solver& solver, const Scene& structure,
                                                  const Discretization& mesh, const RomRequest& rq, std::string& why) {
  Eigen::MatrixXd G(rq.outputs.size(), rq.inputs.size());
  for (std::size_t i = 0; i < rq.inputs.size(); ++i) {
    Scene s = structure;
    PointLoad unit;
    unit.x = rq.inputs[i][0];
    unit.y = rq.inputs[i][1];
    unit.Fz = 1.0;
    s.loads = {unit};
    s.request.probes = rq.outputs;
    const Result r = solver.solve(s, mesh, without_estimate());
    if (!r.ok() || r.deflections.size() != rq.outputs.size()) {
      why = fmt::format("the statics under a unit force at {} were {}: {}", where(structure, rq.inputs[i]),
                        to_string(r.summary.status), r.summary.message);
      return std::nullopt;
    }
    for (std::size_t o = 0; o < rq.outputs.size(); ++o)
      G(static_cast<long>(o), static_cast<long>(i)) = r.deflections[o].w;
  }
  return G;
}

/// G(p, p) at each point: w at p under a unit Fz at p (the back-end's statics).
std::optional<std::vector<double>> driving_point_flexibility(const Solver& solver, const Scene& structure,
                                                             const Discretization& mesh,
                                                             const std::vector<std::array<double, 2>>& points) {
  std::vector<double> g;
  for (const auto& p : points) {
    Scene s = structure;
    PointLoad unit;
    unit.x = p[0];
    unit.y = p[1];
    unit.Fz = 1.0;
    s.loads = {unit};
    s.request.probes = {p};
    const Result r = solver.solve(s, mesh, without_estimate());
    if (!r.ok() || r.deflections.size() != 1) return std::nullopt;
    g.push_back(r.deflections[0].w);
  }
  return g;
}

/// The bound on the truncated tail (StateSpaceModel::tail_bound), from the residual driving-point
/// flexibilities at the inputs then the outputs (`g`, in md.w's point order).
double tail_bound(const Modes& md, int N, const std::vector<double>& g, std::size_t ni, double band,
                  bool corrected) {
  const double next = md.omega[static_cast<std::size_t>(N)];
  if (!(next > band)) return std::numeric_limits<double>::infinity();
  std::vector<double> R(g.size());
  for (std::size_t p = 0; p < g.size(); ++p) {
    double s = 0;
    for (int k = 0; k < N; ++k) {
      const double phi = md.w[static_cast<std::size_t>(k)][p], om = md.omega[static_cast<std::size_t>(k)];
      s += phi * phi / (om * om);
    }
    // Non-negative in exact arithmetic (every mode's phi^2 / omega^2 >= 0): rounding of the
    // difference is allowed for at 1e-12 of G.
    R[p] = std::max(0.0, g[p] - s) + 1e-12 * std::abs(g[p]);
  }
  double worst = 0;
  for (std::size_t o = ni; o < g.size(); ++o)
    for (std::size_t i = 0; i < ni; ++i) worst = std::max(worst, std::sqrt(R[o] * R[i]));
  return worst * (corrected ? band * band : next * next) / (next * next - band * band);
}

void assemble(const Modes& md, int N, const RomRequest& rq, const std::optional<Eigen::MatrixXd>& G,
              StateSpaceModel& m) {
  const long n = N, ni = static_cast<long>(rq.inputs.size()), no = static_cast<long>(rq.outputs.size());
  Eigen::MatrixXd Pin(ni, n), Pout(no, n);
  for (long k = 0; k < n; ++k) {
    for (long i = 0; i < ni; ++i) Pin(i, k) = md.w[static_cast<std::size_t>(k)][static_cast<std::size_t>(i)];
    for (long o = 0; o < no; ++o) Pout(o, k) = md.w[static_cast<std::size_t>(k)][static_cast<std::size_t>(ni + o)];
  }
  Eigen::VectorXd w2(n), c(n);
  for (long k = 0; k < n; ++k) {
    const double om = md.omega[static_cast<std::size_t>(k)];
    w2(k) = om * om;
    c(k) = 2 * rq.zeta * om;
  }
  m.A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  m.A.topRightCorner(n, n).setIdentity();
  m.A.bottomLeftCorner(n, n) = (-w2).asDiagonal();
  m.A.bottomRightCorner(n, n) = (-c).asDiagonal();
  m.B = Eigen::MatrixXd::Zero(2 * n, ni);
  m.B.bottomRows(n) = Pin.transpose();
  m.C = Eigen::MatrixXd::Zero(3 * no, 2 * n);
  m.C.block(0, 0, no, n) = Pout;
  m.C.block(no, n, no, n) = Pout;
  m.C.block(2 * no, 0, no, n) = -Pout * w2.asDiagonal();
  m.C.block(2 * no, n, no, n) = -Pout * c.asDiagonal();
  m.D = Eigen::MatrixXd::Zero(3 * no, ni);
  m.D.bottomRows(no) = Pout * Pin.transpose();
  if (G) {
    Eigen::VectorXd inv(n);
    for (long k = 0; k < n; ++k) inv(k) = 1.0 / w2(k);
    m.D.topRows(no) = *G - Pout * inv.asDiagonal() * Pin.transpose();
  }
}

/// The model's undamped displacement receptance at omega (rows outputs, columns inputs).
Eigen::MatrixXd receptance(const Modes& md, int N, std::size_t ni, std::size_t no, const Eigen::MatrixXd& Dw,
                           double omega) {
  Eigen::MatrixXd H = Dw;
  for (int k = 0; k < N; ++k) {
    const auto& phi = md.w[static_cast<std::size_t>(k)];
    const double om = md.omega[static_cast<std::size_t>(k)], den = om * om - omega * omega;
    for (std::size_t o = 0; o < no; ++o)
      for (std::size_t i = 0; i < ni; ++i) H(static_cast<long>(o), static_cast<long>(i)) += phi[ni + o] * phi[i] / den;
  }
  return H;
}

/// The H-infinity check against the back-end's own FRF, undamped, on a uniform grid over
/// (0, band], leaving out samples within 1 % of a computed frequency (where both are poles).
void check(const Solver& solver, const Scene& structure, const Discretization& mesh, const Modes& md, int N,
           const RomRequest& rq, StateSpaceModel& m) {
  if (!solver.supports(structure).frf) {
    m.note += "; no H-infinity check: the back-end computes no FRF for this scene";
    return;
  }
  const std::size_t ni = rq.inputs.size(), no = rq.outputs.size();
  const double band = md.omega[static_cast<std::size_t>(N) - 1] > 0 ? md.omega[static_cast<std::size_t>(N) - 1] : 1.0;
  m.band_rad_s = band;
  const Eigen::MatrixXd Dw = m.D.topRows(static_cast<long>(no));
  double worst = 0, largest = 0;
  for (std::size_t i = 0; i < ni; ++i)
    for (std::size_t o = 0; o < no; ++o) {
      Scene s = structure;
      s.request.frf = FrfRequest{rq.inputs[i], rq.outputs[o], band / rq.check_points, band, rq.check_points};
      const Result r = solver.solve(s, mesh, without_estimate());
      for (const FrfSample& f : r.frf) {
        bool near_pole = false;
        for (double om : md.omega)
          near_pole = near_pole || std::abs(f.omega_rad_s - om) <= 0.01 * std::max(om, f.omega_rad_s);
        if (near_pole || !std::isfinite(std::abs(f.receptance))) continue;
        const double h = receptance(md, N, ni, no, Dw, f.omega_rad_s)(static_cast<long>(o), static_cast<long>(i));
        worst = std::max(worst, std::abs(f.receptance - h));
        largest = std::max(largest, std::abs(f.receptance));
      }
    }
  m.hinf_error = worst;
  m.hinf_relative = largest > 0 ? worst / largest : kNotMeasured;
  if (static_cast<std::size_t>(N) < md.omega.size()) {
    const double om = md.omega[static_cast<std::size_t>(N)], den = om * om - band * band;
    double lead = 0;
    for (std::size_t o = 0; o < no; ++o)
      for (std::size_t i = 0; i < ni; ++i)
        lead =
            std::max(lead, std::abs(md.w[static_cast<std::size_t>(N)][ni + o] * md.w[static_cast<std::size_t>(N)][i]));
    m.first_neglected = lead * (m.static_correction ? band * band / (om * om * den) : 1.0 / den);
  }
}

void label(const Scene& scene, const RomRequest& rq, int N, StateSpaceModel& m) {
  for (int k = 1; k <= N; ++k) m.states.push_back(fmt::format("q{} (m kg^0.5)", k));
  for (int k = 1; k <= N; ++k) m.states.push_back(fmt::format("dq{}/dt (m kg^0.5 / s)", k));
  for (const auto& p : rq.inputs) m.inputs.push_back(fmt::format("Fz at {} (N)", where(scene, p)));
  for (const auto& p : rq.outputs) m.outputs.push_back(fmt::format("w at {} (m)", where(scene, p)));
  for (const auto& p : rq.outputs) m.outputs.push_back(fmt::format("dw/dt at {} (m/s)", where(scene, p)));
  for (const auto& p : rq.outputs) m.outputs.push_back(fmt::format("d2w/dt2 at {} (m/s^2)", where(scene, p)));
}

/// Inputs and outputs on the body, at least one of each (InputError naming the list and index).
void check_request(const Scene& s, const RomRequest& rq) {
  if (s.is_frame())
    throw InputError(s.source.empty() ? "rom" : s.source, "scene.kind",
                     "a reduced model of a frame is not available yet (its modes carry no shapes); beams and plates only");
  if (rq.inputs.empty()) throw InputError("rom", "inputs", "at least one input point is needed");
  if (rq.outputs.empty()) throw InputError("rom", "outputs", "at least one output point is needed");
  if (rq.modes < 1) throw InputError("rom", "modes", fmt::format("must be >= 1 (got {})", rq.modes));
  if (!(rq.zeta >= 0 && rq.zeta <= 100))
    throw InputError("rom", "zeta", fmt::format("must lie in [0, 100] (got {})", rq.zeta));
  for (const auto* list : {&rq.inputs, &rq.outputs})
    for (std::size_t i = 0; i < list->size(); ++i) {
      const auto& p = (*list)[i];
      const bool inside =
          p[0] >= 0 && p[0] <= s.geometry.length && (s.is_plate() ? p[1] >= 0 && p[1] <= s.geometry.width : p[1] == 0);
      if (!inside)
        throw InputError("rom", fmt::format("{}[{}]", list == &rq.inputs ? "inputs" : "outputs", i),
                         fmt::format("{} lies outside the {}", where(s, p), s.is_plate() ? "plate" : "beam's axis"));
    }
}

}  // namespace

StateSpaceModel export_rom(const Solver& solver, const Scene& scene, const std::optional<Discretization>& mesh,
                           const RomRequest& rq) {
  check_request(scene, rq);
  StateSpaceModel m;
  m.backend = solver.name();
  const Scene structure = structure_of(scene);
  // The modes, on the mesh given or the default refined to the tolerance.
  Scene modal = structure;
  modal.request.modes = rq.modes + 1;
  ShapeRequest sr;
  sr.points = rq.inputs;
  sr.points.insert(sr.points.end(), rq.outputs.begin(), rq.outputs.end());
  modal.request.shapes = sr;
  const Result r = mesh ? solver.solve(modal, *mesh, Options{}) : solver.solve_default(modal, Options{});
  m.mesh = r.summary.mesh;
  if (severity(r.summary.status) >= severity(Status::NumericalIssue) || r.mode_shapes.empty()) {
    m.status = severity(r.summary.status) >= severity(Status::NumericalIssue) ? r.summary.status : Status::Unsupported;
    m.message = r.summary.message.empty() ? solver.name() + " gives no mode shapes for this scene" : r.summary.message;
    return m;
  }
  if (r.summary.status != Status::Success) m.status = r.summary.status, m.message = r.summary.message;
  const Discretization kept = m.mesh == "-" ? Discretization{} : Discretization::parse(m.mesh);
  const Modes md = modes_at(r, sr.points.size());
  const int N = std::min<int>(rq.modes, static_cast<int>(md.omega.size()));
  m.omega_rad_s.assign(md.omega.begin(), md.omega.begin() + N);
  m.rigid_modes = static_cast<int>(std::count(m.omega_rad_s.begin(), m.omega_rad_s.end(), 0.0));
  std::string why;
  std::optional<Eigen::MatrixXd> G;
  if (rq.static_correction && m.rigid_modes == 0) G = static_flexibility(solver, structure, kept, rq, why);
  if (rq.static_correction && m.rigid_modes > 0) why = "the structure has rigid-body modes (no static flexibility)";
  m.static_correction = G.has_value();
  assemble(md, N, rq, G, m);
  label(scene, rq, N, m);
  m.note = fmt::format("modal truncation to {} modes of {} on mesh {}; modal damping {} in A; {}", N, solver.name(),
                       m.mesh, rq.zeta,
                       G ? "static correction in D (the statics minus the retained modes' static part)"
                         : (rq.static_correction ? "no static correction: " + why : "no static correction (off)"));
  if (m.rigid_modes > 0)
    m.note += fmt::format(
        "; {} rigid-body modes kept (states q1..q{} with their rates: a double integrator each, "
        "omega = 0); python-control's balanced reductions refuse such marginally stable systems: "
        "split these states off first",
        m.rigid_modes, m.rigid_modes);
  if (N < rq.modes) m.note += fmt::format("; the model has only {} modes", N);
  if (N > 0) {
    m.band_rad_s = md.omega[static_cast<std::size_t>(N) - 1] > 0 ? md.omega[static_cast<std::size_t>(N) - 1] : 1.0;
    check(solver, structure, kept, md, N, rq, m);
  }
  if (N > 0 && N < static_cast<int>(md.omega.size()) && m.rigid_modes == 0) {
    if (const auto g = driving_point_flexibility(solver, structure, kept, sr.points))
      m.tail_bound = tail_bound(md, N, *g, rq.inputs.size(), m.band_rad_s, m.static_correction);
  }
  if (std::isnan(m.tail_bound))
    m.note += "; no bound on the truncated tail (it needs the static flexibility and a neglected mode)";
  return m;
}

nlohmann::json to_json(const StateSpaceModel& m) {
  using nlohmann::json;
  auto rows = [](const Eigen::MatrixXd& X) {
    json a = json::array();
    for (long i = 0; i < X.rows(); ++i) {
      json row = json::array();
      for (long j = 0; j < X.cols(); ++j) row.push_back(X(i, j));
      a.push_back(row);
    }
    return a;
  };
  auto num = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  return {{"status", to_string(m.status)},
          {"message", m.message},
          {"backend", m.backend},
          {"mesh", m.mesh},
          {"A", rows(m.A)},
          {"B", rows(m.B)},
          {"C", rows(m.C)},
          {"D", rows(m.D)},
          {"states", m.states},
          {"inputs", m.inputs},
          {"outputs", m.outputs},
          {"omega_rad_s", m.omega_rad_s},
          {"rigid_modes", m.rigid_modes},
          {"static_correction", m.static_correction},
          {"check",
           {{"hinf_error_m_per_n", num(m.hinf_error)},
            {"hinf_relative", num(m.hinf_relative)},
            {"band_rad_s", num(m.band_rad_s)},
            {"first_neglected_m_per_n", num(m.first_neglected)},
            {"tail_bound_m_per_n", num(m.tail_bound)},
            {"how",
             "the displacement rows against the back-end's own receptance, undamped, on a uniform grid over "
             "(0, band], samples within 1 % of a natural frequency left out"}}},
          {"note", m.note}};
}

}  // namespace modalbench
