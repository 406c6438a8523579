// A spinning axisymmetric shaft on the one-prism line (rotor.hpp): each whirl direction a prism
// line with the gyroscopic rotary term, its frequencies by the Wittrick-Williams count.
#include "rotor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "modalbench/rotor_scene.hpp"
#include "modalbench/whirl.hpp"
#include "prism_model_detail.hpp"

namespace modalbench::dtfm::detail {

namespace {

/// How the spin enters one whirl direction's line.
struct Whirling {
  int sense = +1;            ///< +1 forward, -1 backward
  double spin = 0;           ///< Omega, rad/s (not used when synchronous)
  bool synchronous = false;  ///< omega = Omega: the critical speeds' problem
};

/// rho I_p per length of each piece on its theta_y field (0 under Euler-Bernoulli theory).
Eigen::MatrixXd section_gyro(const PrismModel& mdl, const Segment& piece, Theory theory) {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(mdl.m, mdl.m);
  const int k = mdl.field(0, dofs::Ry);
  if (k >= 0 && theory != Theory::EulerBernoulli) G(k, k) = piece.material.rho * piece.properties().Ip;
  return G;
}

/// The shaft's x-z line (Iy; axisymmetric: Iz alike) with its supports and discs, its rotary
/// inertias changed per `w`.
PrismModel whirl_model(const Scene& s, const ModelOptions& mo, const Whirling& w) {
  Scene plane = s;
  plane.physics = Physics::Bending;
  plane.rotor.reset();
  PrismModel mdl = build_model(plane, Discretization::parse("1x1"), mo);
  add_disc_gyro(mdl, plane);
  const std::vector<Segment> pieces = s.beam_pieces();
  mdl.G = section_gyro(mdl, pieces.front(), s.theory);
  for (std::size_t i = 0; i < mdl.steps.size(); ++i) mdl.steps[i].G = section_gyro(mdl, pieces[i + 1], s.theory);
  if (!w.synchronous) {
    mdl.whirl = w.sense * w.spin;
    return mdl;
  }
  // omega = Omega: the gyroscopic term is a constant change of the rotary inertia.
  auto shift = [&](Eigen::MatrixXd& M, const Eigen::MatrixXd& G) {
    if (G.size() == 0) return;
    if (M.size() == 0) M = Eigen::MatrixXd::Zero(G.rows(), G.cols());
    M -= w.sense * G;
  };
  shift(mdl.M, mdl.G);
  for (auto& p : mdl.steps) shift(p.M, p.G);
  for (auto& e : mdl.ends) shift(e.mass, e.gyro);
  for (auto& p : mdl.points) shift(p.cond.mass, p.cond.gyro);
  mdl.G.resize(0, 0);
  return mdl;
}

/// A whirl line's analysis with its count tallied into the summary.
struct Line {
  PrismModel model;
  LineAnalysis la;
  Line(const Scene& s, const ModelOptions& mo, const SolveControls& ctl, const Whirling& w)
      : model(whirl_model(s, mo, w)), la(model, ctl) {}
};

void tally(const LineAnalysis& la, Summary& sum) {
  sum.set_diagnostic("count_evaluations",
                     std::max(0.0, sum.diagnostic("count_evaluations")) + static_cast<double>(la.evaluations()));
}

/// The lowest k modes of one whirl direction (rad/s) and, where `points` are given, each mode's
/// planar shape w(x) there (the null vector of the line's dynamic stiffness, dtfm/src/shapes.cpp);
/// a mode that does not reproduce on the second discretization is said in `problems`.
WhirlBranch branch(const Scene& s, const ModelOptions& mo, const SolveControls& ctl, const Whirling& w, int k,
                   Summary& sum, std::string& problems, const std::vector<std::array<double, 2>>& points = {}) {
  Line line(s, mo, ctl, w);
  const ModeList ml = line.la.modes(k);
  if (!ml.count_consistent && problems.empty())
    problems = fmt::format("{} whirl at spin {:g} rad/s: {}", w.sense > 0 ? "forward" : "backward", w.spin,
                           ml.count_message);
  WhirlBranch b{ml.omega_rad_s, {}};
  if (!points.empty() && !ml.omega_rad_s.empty())
    for (const auto& m : line.la.mode_shapes(ml, points, {dofs::Uz}, {false, false, false}).values) b.shape.push_back(m.at(0));
  tally(line.la, sum);
  return b;
}

int count_below(const Scene& s, const ModelOptions& mo, const SolveControls& ctl, const Whirling& w, double omega,
                Summary& sum) {
  Line line(s, mo, ctl, w);
  const int n = line.la.count_below(omega * omega);
  tally(line.la, sum);
  return n;
}

/// The whirl roots at `spin`, in the scene's frame, with their orbits at `points` (if any).
std::vector<WhirlRoot> roots_at(const Scene& s, const ModelOptions& mo, const SolveControls& ctl, double spin, int k,
                                Summary& sum, std::string& problems, const std::vector<std::array<double, 2>>& points) {
  return axisymmetric_whirl(
      spin, s.rotor->frame == Rotor::Frame::Rotating, k,
      [&](int sense, int n) { return branch(s, mo, ctl, {sense, spin, false}, n, sum, problems, points); },
      [&](double omega) { return count_below(s, mo, ctl, {+1, spin, false}, omega, sum); });
}

/// Critical speeds of one whirl direction: every one up to `top` and the next above (where the
/// direction has one: a forward whirl's may be finitely many).
std::vector<double> synchronous(const Scene& s, const ModelOptions& mo, const SolveControls& ctl, int sense, double top,
                                double scale, Summary& sum, std::string& problems) {
  const Whirling w{sense, 0.0, true};
  const int below = count_below(s, mo, ctl, w, top, sum);
  const int far = count_below(s, mo, ctl, w, 100.0 * std::max(top, scale), sum);
  const int n = std::min(far, below + 1);
  return n > 0 ? branch(s, mo, ctl, w, n, sum, problems).omega : std::vector<double>{};
}

}  // namespace

std::string rotor_refusal(const Scene& s) {
  if (!rotor_held(s))
    return "dtfm solves rotors on supports that hold them (a free rotor's rigid whirl is not solved yet)";
  if (!axisymmetric_shaft(s))
    return "dtfm solves axisymmetric shafts (Iy = Iz): each whirl direction is then a real planar prism line; an "
           "asymmetric shaft couples the planes through Coriolis terms in the rotating frame (exact, rfem and "
           "difference_eq model it)";
  return "";
}

Campbell rotor_campbell(const Scene& s, const ModelOptions& mo, const SolveControls& ctl, Summary& sum) {
  Campbell c;
  const int k = s.request.modes;
  std::string problems;
  c.frame = to_string(s.rotor->frame);
  // Orbits where [request.shapes] asks: an axisymmetric shaft's whirl is a circle of its line's shape.
  std::vector<std::array<double, 2>> points;
  if (s.request.shapes) {
    points = s.shape_points();
    for (const auto& p : points) c.orbit_points_m.push_back(p[0]);
    c.orbit_note = "circles (w = -+ i v) of each whirl line's mode shape at its frequency: the null vector of the "
                   "prism line's dynamic stiffness, the exact field between nodes";
  }
  for (double spin : s.rotor->spin) {
    bool unstable = false;
    c.points.push_back(campbell_point(spin, roots_at(s, mo, ctl, spin, k, sum, problems, points), k, unstable));
    if (unstable) c.unstable_spins.push_back(spin);
  }
  const double top = s.rotor->spin.back();
  const double scale = branch(s, mo, ctl, {+1, 0.0, false}, 1, sum, problems).omega.at(0);
  c.forward_criticals = synchronous(s, mo, ctl, +1, top, scale, sum, problems);
  c.backward_criticals = synchronous(s, mo, ctl, -1, top, scale, sum, problems);
  c.criticals_note = "synchronous whirl per direction (rotary inertias rho I -+ rho I_p, J_t -+ J_p) on the prism line, "
                     "bracketed by the Wittrick-Williams count: every critical speed up to the highest spin and the next "
                     "above";
  c.note = fmt::format("dtfm one-prism {} shaft: per whirl direction a planar prism line with rotary inertia rho I - s "
                       "rho I_p Omega / omega (discs J_t - s J_p Omega / omega), its segment dynamic stiffness counted "
                       "(Wittrick-Williams){}; undamped (material.loss_factor is not applied): growth rates 0",
                       to_string(s.theory),
                       s.rotor->frame == Rotor::Frame::Rotating ? "; rotating frame: omega_F - Omega, omega_B + Omega" : "");
  if (!problems.empty())
    sum.raise(Status::NumericalIssue, "dtfm: Campbell diagram: a whirl frequency's count did not reproduce on a second "
                                      "discretization (" + problems + ")");
  return c;
}

}  // namespace modalbench::dtfm::detail
