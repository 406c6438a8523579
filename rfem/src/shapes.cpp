// Mode shapes of the rfem model at the scene's sample points, with their modal quantities.

#include <fmt/format.h>

#include "analysis_detail.hpp"
#include "modalbench/rfem/rfem.hpp"

namespace modalbench::rfem {

ModeShapes sample_shapes(const Scene& s, const Model& model, const System& sys, const Eigen::MatrixXd& Z,
                         const Eigen::VectorXd& lambda, long count) {
  ModeShapes out;
  out.points = s.shape_points();
  out.components = s.shape_components();
  const int na = model.dofs_per_element();
  std::vector<int> local;  // index of each component among the model's active DOFs (-1: absent)
  for (int c : out.components) local.push_back(model.local_index(c));
  // Interpolation weights of every sample point (the model's consistent displacement field).
  std::vector<std::vector<std::pair<int, double>>> weights;
  for (const auto& p : out.points)
    weights.push_back(point_weights(model, s.is_beam() ? Eigen::Vector3d(p[0], 0, 0) : Eigen::Vector3d(p[0], p[1], 0)));
  for (int d = 0; d < 3; ++d) out.directions[static_cast<std::size_t>(d)] = model.local_index(d) >= 0;
  for (const auto& e : model.elements) out.total_mass += e.mass;
  for (long k = 0; k < count; ++k) {
    const Eigen::VectorXd q = sys.T * Z.col(k);
    std::vector<std::vector<double>> mode(out.components.size(), std::vector<double>(out.points.size(), 0.0));
    for (std::size_t c = 0; c < out.components.size(); ++c) {
      if (local[c] < 0) continue;
      for (std::size_t p = 0; p < out.points.size(); ++p)
        for (auto [e, w] : weights[p]) mode[c][p] += w * q[static_cast<long>(e) * na + local[c]];
    }
    // phi' M phi and phi' M r_d over the RFEs' lumped masses.
    double gm = 0;
    std::array<double, 3> gamma{0, 0, 0};
    for (std::size_t e = 0; e < model.elements.size(); ++e) {
      const auto& el = model.elements[e];
      for (int a = 0; a < na; ++a) {
        const int d = model.active[static_cast<std::size_t>(a)];
        const double v = q[static_cast<long>(e) * na + a];
        const double mass = d < 3 ? el.mass : el.inertia[d - 3];
        gm += mass * v * v;
        if (d < 3) gamma[static_cast<std::size_t>(d)] += el.mass * v;
      }
    }
    out.values.push_back(std::move(mode));
    out.generalized_mass.push_back(gm);
    out.participation.push_back(gamma);
  }
  out.note = "rfem eigenvectors, orthonormal in the RFE mass matrix (repeated frequencies: an orthonormal basis of the "
             "eigenspace), sampled by (bi)linear interpolation of the RFE centres' motion";
  if (s.is_beam() && s.request.shapes && s.request.shapes->moments) {
    std::string why;
    if (auto m = detail::modal_moments(s, model, sys, Z, lambda, count, out.points, why)) {
      out.moments = std::move(*m);
      out.note += "; moments My by the free body of each mode under its inertia loads and support reactions";
    } else {
      out.note += "; no moments: " + why;
    }
  }
  finish_mode_shapes(out);
  return out;
}

}  // namespace modalbench::rfem
