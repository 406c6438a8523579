// LineAnalysis meshes: global nodes and base-piece length from the wavenumber bounds of a class line.
#include "modalbench/dtfm/analysis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "analysis_detail.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"

namespace modalbench::dtfm {

namespace {

/// Floating gcd of two lengths (Euclid with a tolerance); 0 if they are incommensurate.
double fgcd(double a, double b, double tol) {
  for (int it = 0; it < 64; ++it) {
    if (a < b) std::swap(a, b);
    if (b <= tol) return a;
    a = std::fmod(a, b);
    if (a <= tol || b - a <= tol) return b;
  }
  return 0.0;
}

}  // namespace

namespace {

void wavenumber_bounds(const Eigen::MatrixXd& A, double& re, double& im) {
  try {
    const Eigen::VectorXcd p = state_wavenumbers(A);
    for (Eigen::Index i = 0; i < p.size(); ++i) {
      re = std::max(re, std::abs(p[i].real()));
      im = std::max(im, std::abs(p[i].imag()));
    }
  } catch (const std::runtime_error&) {  // |p| <= any induced norm of A
    const double nrm = A.cwiseAbs().rowwise().sum().maxCoeff();
    re = std::max(re, nrm);
    im = std::max(im, nrm);
  }
}
}  // namespace

LineAnalysis::Mesh LineAnalysis::mesh_for(ClassLine& c, double lambda_max, const std::vector<double>& required,
                                          int min_nodes) {
  const double L = model_.length;
  if (c.re0 < 0) {
    c.re0 = c.im0 = 0;
    for (int k = 0; k < c.pieces(); ++k) wavenumber_bounds(c.state(0.0, k), c.re0, c.im0);
  }
  double re = c.re0, im = c.im0;
  if (lambda_max > 0)
    for (int k = 0; k < c.pieces(); ++k) wavenumber_bounds(c.state(lambda_max, k), re, im);
  // A whirl line's rotary term lambda rho I - s Omega sqrt(lambda) rho I_p is not monotone in
  // lambda (forward whirl: least at sqrt(lambda) = Omega I_p / 2 I): the bounds at the ends of the
  // range do not hold between them, so they are taken on a geometric sweep below lambda_max too.
  if (c.whirl != 0.0 && lambda_max > 0)
    for (double l = 0.5 * lambda_max; l > 1e-8 * lambda_max; l *= 0.5)
      for (int k = 0; k < c.pieces(); ++k) wavenumber_bounds(c.state(l, k), re, im);
  Mesh mesh;
  mesh.h_im = im > 0 ? ctl_.im_h / im : L;
  mesh.h_re = re > 0 ? ctl_.re_h / re : L;
  mesh.h_base = std::min({L, mesh.h_im, mesh.h_re});
  if (!(mesh.h_base > 0) || !std::isfinite(mesh.h_base)) throw std::runtime_error("dtfm: wavenumber bound is not finite");
  std::vector<double> breaks = {0.0, L};
  for (double x : required) breaks.push_back(std::clamp(x, 0.0, L));
  for (double x : c.required_nodes()) breaks.push_back(x);  // steps, supports, masses
  for (int i = 1; i < min_nodes; ++i) breaks.push_back(L * i / min_nodes);
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> b2;
  for (double x : breaks)
    if (b2.empty() || x - b2.back() > 1e-12 * L) b2.push_back(x);
  b2.back() = L;
  // Equal segments on a common spacing when the breakpoints are commensurate (one long
  // segment matrix per lambda); otherwise one per gap. Not on a spacing much shorter than the
  // base piece: a segment's stiffness grows like 1/h^3 against its inertia's h, so K(lambda)
  // resolves lambda only to eps / (k h)^4, and the count with it (a mass at 0.365 of a
  // cantilever made 200 segments of 5 mm: mode 1 6e-8 off, its bound 3e-10; fuzz seed 7).
  const double tol = 1e-9 * L;
  double unit = b2[1] - b2[0];
  for (std::size_t i = 1; i + 1 < b2.size() && unit > 0; ++i) unit = fgcd(unit, b2[i + 1] - b2[i], tol);
  const bool on_unit = unit > 1e-3 * L && unit >= 0.5 * mesh.h_base;
  mesh.x = {0.0};
  for (std::size_t g = 0; g + 1 < b2.size(); ++g) {
    const double len = b2[g + 1] - b2[g];
    const int n = on_unit ? std::max(1, static_cast<int>(std::lround(len / unit))) : 1;
    for (int j = 1; j < n; ++j) mesh.x.push_back(b2[g] + len * j / n);
    mesh.x.push_back(b2[g + 1]);
  }
  return mesh;
}

LineAnalysis::Mesh LineAnalysis::refined(const Mesh& mesh) {
  Mesh out = mesh;
  out.x = {mesh.x.front()};
  for (std::size_t i = 0; i + 1 < mesh.x.size(); ++i) {
    out.x.push_back(0.5 * (mesh.x[i] + mesh.x[i + 1]));
    out.x.push_back(mesh.x[i + 1]);
  }
  return out;
}

}  // namespace modalbench::dtfm
