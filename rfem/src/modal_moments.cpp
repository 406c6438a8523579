// The bending moments of rfem modes at points of a beam, by the statics' own route: a mode q at
// omega^2 is the static response of the model to its inertia loads omega^2 M q (K q = omega^2 M q),
// so its support reactions (support_forces) and the equilibrium of the free body left of each point
// (equilibrium.hpp) give its moment there, as they give the statics' (reactions.cpp).
#include <fmt/format.h>

#include "analysis_detail.hpp"
#include "modalbench/equilibrium.hpp"
#include "modalbench/rfem/analysis.hpp"

namespace modalbench::rfem::detail {

namespace {

/// The mode's inertia loads omega^2 M q on the RFEs (M is diagonal over each RFE's DOFs), as point
/// actions at their centres and as the same loads of a scene without any other load.
std::vector<PointAction> inertia_loads(const Model& model, const Eigen::VectorXd& q, double lambda, Scene& body) {
  const int na = model.dofs_per_element();
  std::vector<PointAction> actions;
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const RigidElement& el = model.elements[e];
    Vector6d act = Vector6d::Zero();
    for (int a = 0; a < na; ++a) {
      const int d = model.active[static_cast<std::size_t>(a)];
      const double v = q[static_cast<Eigen::Index>(e) * na + a];
      act[d] = lambda * (d < 3 ? el.mass : el.inertia[d - 3]) * v;
    }
    actions.emplace_back(el.centre, act);
    PointLoad p;
    p.x = el.centre.x();
    p.Fx = act[0], p.Fy = act[1], p.Fz = act[2], p.Mx = act[3], p.My = act[4], p.Mz = act[5];
    body.loads.push_back(p);
  }
  return actions;
}

}  // namespace

std::optional<std::vector<std::vector<double>>> modal_moments(const Scene& s, const Model& model, const System& sys,
                                                              const Eigen::MatrixXd& Z, const Eigen::VectorXd& lambda,
                                                              long count, const std::vector<std::array<double, 2>>& at,
                                                              std::string& why) {
  Scene body = s;  // the scene's structure with the inertia loads only
  body.line_loads.clear();
  body.gravity.reset();
  std::vector<std::vector<double>> out;
  for (long k = 0; k < count; ++k) {
    const Eigen::VectorXd z = Z.col(k);
    body.loads.clear();
    const std::vector<PointAction> actions = inertia_loads(model, sys.T * z, std::max(0.0, lambda[k]), body);
    const SupportForces sf = support_forces(model, sys, z, actions);
    if (!(sf.residual <= 1e-8)) {
      why = fmt::format("the constraint forces of mode {} balance the model only to {:.2g}", k + 1, sf.residual);
      return std::nullopt;
    }
    std::vector<Reaction> reactions;
    for (const SupportForce& f : sf.forces) {
      const Sde& sd = model.sdes[static_cast<std::size_t>(f.sde)];
      reactions.push_back({"", {sd.point.x(), 0.0}, {f.force.x(), f.force.y(), f.force.z()},
                           {f.moment.x(), f.moment.y(), f.moment.z()}});
    }
    std::vector<double> mk;
    for (const auto& p : at) mk.push_back(free_body_forces(body, reactions, p[0]).My);
    out.push_back(std::move(mk));
  }
  return out;
}

}  // namespace modalbench::rfem::detail
