// LineAnalysis forced responses: static deflection under point loads and receptance FRFs.
#include "modalbench/dtfm/analysis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis_detail.hpp"
#include "modalbench/numerics/line_system.hpp"

namespace modalbench::dtfm {

namespace {
using detail::to_fields;
}  // namespace

std::vector<Deflection> LineAnalysis::statics(const std::vector<PointLoad>& loads,
                                              const std::vector<std::array<double, 2>>& probes) {
  std::vector<double> required;
  for (const auto& p : loads) required.push_back(p.x);
  for (const auto& p : probes) required.push_back(p[0]);
  const int m = model_.m;
  std::vector<Eigen::VectorXd> qp(probes.size(), Eigen::VectorXd::Zero(m));
  // Each class's share of the loads (physical units): a class is unloaded when its share is
  // rounding of the total (a moment at an end leaks 1e-17 of itself into other classes), not
  // when it is exactly 0.
  std::vector<double> share(lines_.size(), 0.0);
  double total_share = 0;
  for (std::size_t ci = 0; ci < lines_.size(); ++ci) {
    for (const auto& p : loads) share[ci] += (lines_[ci]->W.transpose() * model_.load_vector(p)).squaredNorm();
    total_share += share[ci];
  }
  for (const auto& line : lines_) {
    ClassLine& c = *line;
    if (!(share[static_cast<std::size_t>(c.index)] > 1e-24 * total_share)) continue;
    // A loaded class must be free of rigid-body motions (structurally, by its count just above
    // zero): its static solve would otherwise give rounding noise divided by rounding noise.
    {
      const double delta = kRigidThreshold * model_.lambda_scale;
      const Mesh near_zero = mesh_for(c, delta, {});
      if (const int rigid = count_det(c, delta, near_zero).count; rigid > 0)
        throw std::runtime_error(fmt::format(
            "mechanism: the supports leave {} rigid-body motion(s) of the loaded {} family free, or restrain them "
            "below 1e-10 of the model's stiffness scale, which dtfm cannot resolve ({} / {})",
            rigid,
            to_string(c.family), model_.ends[0].text, model_.ends[1].text));
    }
    const Mesh mesh = mesh_for(c, 0.0, required);
    const auto& x = mesh.x;
    const int nn = static_cast<int>(x.size());
    auto node = [&](double xx) {
      for (int i = 0; i < nn; ++i)
        if (std::abs(x[i] - xx) <= 1e-12 * model_.length) return i;
      return static_cast<int>(std::lower_bound(x.begin(), x.end(), xx) - x.begin());
    };
    Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nn) * c.mc);
    for (const auto& p : loads) {
      const int i = node(std::clamp(p.x, 0.0, model_.length));
      Eigen::VectorXd fc = c.W.transpose() * model_.load_vector(p) / c.sigma;
      if (i == 0) fc = c.ends[0].B.transpose() * fc;
      if (i == nn - 1) fc = c.ends[1].B.transpose() * fc;
      f.segment(static_cast<Eigen::Index>(i) * c.mc, c.mc) += fc;
    }
    const Assembled a = assemble(c, 0.0, mesh);
    Eigen::VectorXd d;
    // Rigid motions were excluded above, structurally: a failure here is numerical, not the
    // supports' (and no pivot-ratio test: a short piece is stiff, not singular).
    try {
      d = a.K.solve(f, 0.0);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(fmt::format("static solve of the {} family failed numerically: {}", to_string(c.family),
                                           e.what()));
    }
    const auto q = to_fields(c, d, nn);
    for (std::size_t j = 0; j < probes.size(); ++j) qp[j] += q[node(std::clamp(probes[j][0], 0.0, model_.length))];
  }
  std::vector<Deflection> out;
  for (std::size_t j = 0; j < probes.size(); ++j) {
    Deflection d = model_.section_response(qp[j], probes[j][1]);
    d.position = probes[j];
    out.push_back(d);
  }
  return out;
}

std::vector<std::complex<double>> LineAnalysis::receptance(std::array<double, 2> excite, std::array<double, 2> observe,
                                                           const std::vector<double>& omegas, double eta,
                                                           int* skipped, std::string* reason) {
  std::vector<std::complex<double>> H(omegas.size(), 0.0);
  if (skipped) *skipped = 0;
  auto why = [&](std::size_t s, const std::exception& e) {
    if (reason && reason->empty()) *reason = fmt::format("at {:.6g} rad/s: {}", omegas[s], e.what());
  };
  if (omegas.empty()) return H;
  PointLoad unit;
  unit.x = excite[0];
  unit.y = excite[1];
  unit.Fz = 1.0;
  const Eigen::VectorXd f_full = model_.load_vector(unit);
  const Eigen::RowVectorXd o_full = model_.w_observer(observe[1]);
  const double w_max = *std::max_element(omegas.begin(), omegas.end());
  const std::complex<double> cdamp(1.0, eta);
  std::vector<char> bad(omegas.size(), 0);
  for (const auto& line : lines_) {
    ClassLine& c = *line;
    const Eigen::VectorXd fc0 = c.W.transpose() * f_full / c.sigma;
    const Eigen::RowVectorXd oc = o_full * c.W;
    if (fc0.norm() == 0.0 || oc.norm() == 0.0) continue;
    const Mesh mesh = mesh_for(c, w_max * w_max, {excite[0], observe[0]});
    const auto& x = mesh.x;
    const int nn = static_cast<int>(x.size());
    auto node = [&](double xx) {
      for (int i = 0; i < nn; ++i)
        if (std::abs(x[i] - xx) <= 1e-12 * model_.length) return i;
      return 0;
    };
    const int ie = node(std::clamp(excite[0], 0.0, model_.length));
    const int io = node(std::clamp(observe[0], 0.0, model_.length));
    Eigen::VectorXd fc = fc0;
    if (ie == 0) fc = c.ends[0].B.transpose() * fc;
    if (ie == nn - 1) fc = c.ends[1].B.transpose() * fc;
    auto observe_at = [&](auto dnode) {
      using V = std::decay_t<decltype(dnode)>;
      V d = dnode;
      if (io == 0) d = c.ends[0].B.template cast<typename V::Scalar>() * d;
      if (io == nn - 1) d = c.ends[1].B.template cast<typename V::Scalar>() * d;
      return (oc.template cast<typename V::Scalar>() * d)(0);
    };
    for (std::size_t s = 0; s < omegas.size(); ++s) {
      const double lam = omegas[s] * omegas[s];
      if (eta == 0.0) {
        Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nn) * c.mc);
        f.segment(static_cast<Eigen::Index>(ie) * c.mc, c.mc) = fc;
        try {
          const Eigen::VectorXd d = assemble(c, lam, mesh).K.solve(f);
          H[s] += observe_at(Eigen::VectorXd(d.segment(static_cast<Eigen::Index>(io) * c.mc, c.mc)));
        } catch (const std::runtime_error& e) {
          bad[s] = 1;
          why(s, e);
        }
      } else {
        Eigen::VectorXcd f = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(nn) * c.mc);
        f.segment(static_cast<Eigen::Index>(ie) * c.mc, c.mc) = fc.cast<std::complex<double>>() / cdamp;
        try {
          const Eigen::VectorXcd d = assemble(c, std::complex<double>(lam) / cdamp, mesh).solve(f);
          H[s] += observe_at(Eigen::VectorXcd(d.segment(static_cast<Eigen::Index>(io) * c.mc, c.mc)));
        } catch (const std::runtime_error& e) {
          bad[s] = 1;
          why(s, e);
        }
      }
    }
  }
  for (std::size_t s = 0; s < omegas.size(); ++s) {
    if (bad[s]) {
      H[s] = std::numeric_limits<double>::quiet_NaN();
      if (skipped) ++*skipped;
    }
  }
  return H;
}

}  // namespace modalbench::dtfm
