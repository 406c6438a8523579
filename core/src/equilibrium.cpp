// Stress resultants from the equilibrium of the free body [0, x] (equilibrium.hpp).
#include "modalbench/equilibrium.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace modalbench {

namespace {

/// The sum of forces F and of their moments M about the cut at x.
struct FreeBody {
  double x = 0;
  std::array<double, 3> F{}, M{};
  void add(double at, const std::array<double, 3>& f, const std::array<double, 3>& couple) {
    const double arm = at - x;  // (arm e_x) x f = arm (0, -f_z, f_y)
    for (int k = 0; k < 3; ++k) F[k] += f[k];
    M[0] += couple[0];
    M[1] += -arm * f[2] + couple[1];
    M[2] += arm * f[1] + couple[2];
  }
};

}  // namespace

InternalForces free_body_forces(const Scene& s, const std::vector<Reaction>& reactions, double x) {
  FreeBody body{x, {}, {}};
  const double L = s.geometry.length;
  auto acts = [&](double at) { return x >= L ? at < L : at <= x; };  // x + 0; at the right end L - 0
  for (const Reaction& r : reactions)
    if (acts(r.position[0])) body.add(r.position[0], r.force, r.moment);
  for (const PointLoad& p : s.all_point_loads())
    if (acts(p.x)) body.add(p.x, {p.Fx, p.Fy, p.Fz}, {p.Mx, p.My, p.Mz});
  // The intensities over [lo, hi]: Gauss integrates the force and its moment (load_gauss_points).
  for (const DistributedLoad& q : s.all_distributed_loads()) {
    const double lo = q.from[0], hi = std::min(q.to[0], x);
    for (const auto& [at, w] : load_gauss_points(q, lo, hi))
      body.add(at, {q.at(q.qx, at) * w, q.at(q.qy, at) * w, q.at(q.qz, at) * w}, {});
  }
  // The cut exerts -F and -M on the left part; the conventions of result.hpp then give:
  InternalForces f;
  f.N = -body.F[0];
  f.Qy = body.F[1];
  f.Qz = body.F[2];
  f.T = -body.M[0];
  f.My = body.M[1];
  f.Mz = -body.M[2];
  return f;
}

}  // namespace modalbench
