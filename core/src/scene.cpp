#include "modalbench/scene.hpp"

#include "modalbench/gauss_legendre.hpp"

#include <Eigen/Dense>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace modalbench {

InputError::InputError(std::string source, std::string key, std::string reason)
    : std::runtime_error(fmt::format("{}: {}: {}", source.empty() ? "<scene>" : source,
                                     key.empty() ? "<file>" : key, reason)),
      source_(std::move(source)),
      key_(std::move(key)),
      reason_(std::move(reason)) {}

std::string to_string(SceneKind k) {
  switch (k) {
    case SceneKind::Beam: return "beam";
    case SceneKind::Plate: return "plate";
    case SceneKind::Frame: return "frame";
  }
  return "?";
}
std::string to_string(Physics p) {
  switch (p) {
    case Physics::Bending: return "bending";
    case Physics::Planar: return "planar";
    case Physics::Spatial: return "spatial";
    case Physics::Lateral: return "lateral";
  }
  return "?";
}
std::string to_string(Rotor::Frame f) { return f == Rotor::Frame::Stationary ? "stationary" : "rotating"; }
std::string to_string(Theory t) {
  switch (t) {
    case Theory::EulerBernoulli: return "euler-bernoulli";
    case Theory::Timoshenko: return "timoshenko";
    case Theory::Kirchhoff: return "kirchhoff";
    case Theory::Mindlin: return "mindlin";
  }
  return "?";
}

Support Support::named(const std::string& kind) {
  Support s;
  s.kind = kind;
  if (kind == "free") return s;
  if (kind == "clamped") {
    s.translational = s.rotational = s.axial = s.torsional = kRigid;
  } else if (kind == "pinned") {
    // A hinge with a fork: translations and twist held, bending rotations free.
    s.translational = s.axial = s.torsional = kRigid;
  } else if (kind == "guided") {
    // Sliding clamp: transverse translation free, bending rotation held; axial and twist held.
    s.rotational = s.axial = s.torsional = kRigid;
  } else {
    throw std::invalid_argument("unknown support '" + kind +
                                "' (expected free, pinned, clamped, guided, or a table of springs)");
  }
  return s;
}

Section rectangular_section(double width, double height) {
  Section s{};
  s.A = width * height;
  s.Iy = width * height * height * height / 12.0;
  s.Iz = height * width * width * width / 12.0;
  s.Ip = s.Iy + s.Iz;
  // Saint-Venant constant of a rectangle (long side c, short side t):
  // J = c t^3 / 3 * (1 - 192 t / (pi^5 c) * sum_{n odd} tanh(n pi c / (2 t)) / n^5).
  const double c = std::max(width, height), t = std::min(width, height);
  // (n^5 is exact in double for these n, as pow gives it; tanh rounds to 1 beyond 19.1.)
  double sum = 0;
  for (int n = 1; n < 200; n += 2) {
    const double arg = n * std::numbers::pi * c / (2 * t), n5 = static_cast<double>(n) * n * n * n * n;
    sum += (arg > 20.0 ? 1.0 : std::tanh(arg)) / n5;
  }
  s.J = c * t * t * t / 3.0 * (1.0 - 192.0 * t / (std::pow(std::numbers::pi, 5) * c) * sum);
  return s;
}

Section circular_section(double d) { return tube_section(d, 0.0); }

Section tube_section(double D, double d) {
  const double pi = std::numbers::pi, D2 = D * D, d2 = d * d;
  Section s{};
  s.A = pi * (D2 - d2) / 4.0;
  s.Iy = s.Iz = pi * (D2 * D2 - d2 * d2) / 64.0;
  s.J = s.Ip = s.Iy + s.Iz;
  return s;
}

Section section_properties(const Geometry& g, const SectionSpec& sp) {
  switch (sp.shape) {
    case SectionShape::Rectangle: return rectangular_section(g.width, g.height);
    case SectionShape::Circle: return circular_section(sp.diameter);
    case SectionShape::Tube: return tube_section(sp.diameter, sp.inner_diameter);
    case SectionShape::General: return Section{sp.A, sp.Iy, sp.Iz, sp.J, sp.Iy + sp.Iz};
  }
  return rectangular_section(g.width, g.height);
}

std::string to_string(Profile p) { return p == Profile::Linear ? "linear" : "exponential"; }

namespace {

/// A dimension at the fraction t of a piece: d0 at 0, d1 at 1, by the profile (d0 == d1 stays d0).
double vary(Profile p, double d0, double d1, double t) {
  if (d0 == d1) return d0;
  return p == Profile::Linear ? d0 + (d1 - d0) * t : d0 * std::pow(d1 / d0, t);
}

}  // namespace

Section Segment::properties() const {
  if (end) throw std::logic_error("Segment::properties() of a tapered piece: its section varies (properties_at)");
  return section_properties({x_to - x_from, width, height}, section);
}

Section Segment::properties_at(double x) const { return end ? uniform_at(x).properties() : properties(); }

Segment Segment::uniform_at(double x) const {
  if (!end) return *this;
  const double t = std::clamp((x - x_from) / (x_to - x_from), 0.0, 1.0);
  const Profile p = end->profile;
  const SectionSpec& a = section;
  const SectionSpec& b = end->section;
  Segment out = *this;
  out.end.reset();
  out.kappa_follows_shape = false;
  out.material.kappa = kappa_at(x);
  out.width = vary(p, width, end->width, t);
  out.height = vary(p, height, end->height, t);
  SectionSpec& at = out.section;
  at.diameter = vary(p, a.diameter, b.diameter, t);
  at.inner_diameter = vary(p, a.inner_diameter, b.inner_diameter, t);
  at.A = vary(p, a.A, b.A, t);
  at.Iy = vary(p, a.Iy, b.Iy, t);
  at.Iz = vary(p, a.Iz, b.Iz, t);
  at.J = vary(p, a.J, b.J, t);
  return out;
}

double Segment::kappa_at(double x) const {
  if (!kappa_follows_shape || !end) return material.kappa;
  const double t = std::clamp((x - x_from) / (x_to - x_from), 0.0, 1.0);
  const double D = vary(end->profile, section.diameter, end->section.diameter, t);
  const double d = vary(end->profile, section.inner_diameter, end->section.inner_diameter, t);
  return cowper_kappa_tube(material.nu, d / D);
}

Segment::Bounds Segment::bounds_on(double x0, double x1) const {
  Bounds out;
  if (!end) {
    out.weakest = out.heaviest = properties();
    out.kappa_lo = material.kappa;
    return out;
  }
  const Segment a = uniform_at(x0), b = uniform_at(x1);
  Segment lo = a, hi = a;
  const auto span = [](double& l, double& h, double u, double v) {
    l = std::min(u, v);
    h = std::max(u, v);
  };
  span(lo.width, hi.width, a.width, b.width);
  span(lo.height, hi.height, a.height, b.height);
  span(lo.section.diameter, hi.section.diameter, a.section.diameter, b.section.diameter);
  span(hi.section.inner_diameter, lo.section.inner_diameter, a.section.inner_diameter, b.section.inner_diameter);
  span(lo.section.A, hi.section.A, a.section.A, b.section.A);
  span(lo.section.Iy, hi.section.Iy, a.section.Iy, b.section.Iy);
  span(lo.section.Iz, hi.section.Iz, a.section.Iz, b.section.Iz);
  span(lo.section.J, hi.section.J, a.section.J, b.section.J);
  out.heaviest = hi.properties();
  out.kappa_lo = std::min(a.material.kappa, b.material.kappa);
  if (section.shape == SectionShape::Tube && !(lo.section.inner_diameter < lo.section.diameter)) {
    out.weakest_exists = false;
    return out;
  }
  out.weakest = lo.properties();
  if (kappa_follows_shape) out.kappa_lo = cowper_kappa_tube(material.nu, lo.section.inner_diameter / lo.section.diameter);
  return out;
}

double Segment::mass() const {
  if (!end) return material.rho * properties().A * length();
  return material.rho * gauss_legendre8::integrate([this](double x) { return properties_at(x).A; }, x_from, x_to, 16);
}

bool Scene::has_tapered_pieces() const {
  return std::any_of(segments.begin(), segments.end(), [](const Segment& p) { return p.tapered(); });
}

double cowper_kappa_tube(double nu, double m) {
  const double q = (1.0 + m * m) * (1.0 + m * m);
  return 6.0 * (1.0 + nu) * q / ((7.0 + 6.0 * nu) * q + (20.0 + 12.0 * nu) * m * m);
}

std::string to_string(SectionShape s) {
  switch (s) {
    case SectionShape::Rectangle: return "rectangle";
    case SectionShape::Circle: return "circle";
    case SectionShape::Tube: return "tube";
    case SectionShape::General: return "general";
  }
  return "?";
}

std::vector<std::array<double, 2>> Scene::shape_points() const {
  std::vector<std::array<double, 2>> p;
  if (!request.shapes) return p;
  if (!request.shapes->points.empty()) return request.shapes->points;
  const int nx = request.shapes->nx, ny = is_plate() ? request.shapes->ny : 1;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      p.push_back({geometry.length * i / (nx - 1), is_plate() ? geometry.width * j / (ny - 1) : 0.0});
  return p;
}

std::vector<int> Scene::shape_components() const {
  if (is_plate()) return {2, 3, 4};
  switch (physics) {
    case Physics::Bending: return {2, 4};
    case Physics::Planar: return {0, 2, 4};
    case Physics::Spatial: return {0, 1, 2, 3, 4, 5};
    case Physics::Lateral: return {1, 2, 4, 5};
  }
  return {};
}

std::vector<PointLoad> Scene::all_point_loads() const {
  std::vector<PointLoad> out = loads;
  if (gravity)
    for (const PointMass& m : masses) {
      PointLoad p;
      p.x = m.x;
      p.y = m.y;
      p.Fx = m.mass * (*gravity)[0];
      p.Fy = m.mass * (*gravity)[1];
      p.Fz = m.mass * (*gravity)[2];
      out.push_back(p);
    }
  return out;
}

std::vector<Segment> Scene::beam_pieces() const {
  if (!segments.empty()) return segments;
  Segment one;
  one.x_to = geometry.length;
  one.width = geometry.width;
  one.height = geometry.height;
  one.section = cross_section;
  one.material = material;
  return {one};
}

std::vector<DistributedLoad> Scene::all_distributed_loads() const {
  std::vector<DistributedLoad> out = is_beam() ? line_loads : pressures;
  if (!gravity) return out;
  // The weight per length (beam: of each piece) or per area (plate), over the whole of it.
  auto weight = [&](double per, double x_from, double x_to) {
    DistributedLoad w;
    w.from = {x_from, 0.0};
    w.to = {x_to, geometry.width};
    w.qx = {per * (*gravity)[0], per * (*gravity)[0]};
    w.qy = {per * (*gravity)[1], per * (*gravity)[1]};
    w.qz = {per * (*gravity)[2], per * (*gravity)[2]};
    out.push_back(w);
  };
  if (is_plate()) {
    weight(material.rho * geometry.height, 0.0, geometry.length);
    return out;
  }
  for (const Segment& p : beam_pieces()) {
    if (!p.tapered()) {
      weight(p.material.rho * p.properties().A, p.x_from, p.x_to);
      continue;
    }
    // A tapered piece: the start's weight per length times A(x) / A(x_from).
    const double A0 = p.properties_at(p.x_from).A;
    weight(p.material.rho * A0, p.x_from, p.x_to);
    out.back().factor = [p, A0](double x) { return p.properties_at(x).A / A0; };
  }
  return out;
}

std::vector<std::pair<double, double>> load_gauss_points(const DistributedLoad& q, double lo, double hi,
                                                         int parts) {
  std::vector<std::pair<double, double>> out;
  if (!(hi > lo)) return out;
  if (!q.factor) {
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo), off = half / std::sqrt(3.0);
    return {{mid - off, half}, {mid + off, half}};
  }
  using gauss_legendre8::node, gauss_legendre8::weight;
  for (int k = 0; k < parts; ++k) {
    const double a = lo + (hi - lo) * k / parts, b = lo + (hi - lo) * (k + 1) / parts;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    for (std::size_t i = 0; i < node.size(); ++i) {
      out.emplace_back(mid - half * node[i], half * weight[i]);
      out.emplace_back(mid + half * node[i], half * weight[i]);
    }
  }
  return out;
}

std::vector<std::string> free_plate_rigid_motions(const Scene& s) {
  if (!s.is_plate()) return {};
  // Rigid motions w = a + b x + c y: rows of the constraints the edges put on (a, b, c).
  const double L = s.geometry.length, B = s.geometry.width;
  Eigen::MatrixXd rows(0, 3);
  auto add = [&](double a, double b, double c) {
    rows.conservativeResize(rows.rows() + 1, 3);
    rows.row(rows.rows() - 1) << a, b, c;
  };
  const std::array<std::pair<const Support*, double>, 2> xe = {{{&s.x0, 0.0}, {&s.xL, L}}};
  const std::array<std::pair<const Support*, double>, 2> ye = {{{&s.y0, 0.0}, {&s.yB, B}}};
  for (const auto& [sp, x] : xe) {
    if (sp->translational > 0) add(1.0, x, 0.0), add(0.0, 0.0, 1.0);  // w = 0 along x = const
    if (sp->rotational > 0) add(0.0, 1.0, 0.0);                      // dw/dx = 0 there
  }
  for (const auto& [sp, y] : ye) {
    if (sp->translational > 0) add(1.0, 0.0, y), add(0.0, 1.0, 0.0);
    if (sp->rotational > 0) add(0.0, 0.0, 1.0);
  }
  for (const PointSupport& p : s.point_supports) {
    if (p.support.translational > 0) add(1.0, p.x, p.y);                       // w = 0 there
    if (p.support.rotational > 0) add(0.0, 1.0, 0.0), add(0.0, 0.0, 1.0);      // both slopes
  }
  // The free motions span the null space of the rows; name its basis.
  Eigen::MatrixXd N = Eigen::MatrixXd::Identity(3, 3);
  if (rows.rows() > 0) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(rows);
    lu.setThreshold(1e-12);
    N = lu.kernel();
    if (lu.rank() == 3) return {};
  }
  static const char* names[3] = {"translation z", "rotation about y (w linear in x)", "rotation about x (w linear in y)"};
  std::vector<std::string> out;
  for (Eigen::Index j = 0; j < N.cols(); ++j) {
    std::string parts;
    for (int k = 0; k < 3; ++k)
      if (std::abs(N(k, j)) > 1e-12 * N.col(j).cwiseAbs().maxCoeff()) parts += (parts.empty() ? "" : " + ") + std::string(names[k]);
    out.push_back(parts);
  }
  return out;
}

double Scene::plate_D() const {
  const double h = geometry.height;
  return material.E * h * h * h / (12.0 * (1.0 - material.nu * material.nu));
}

std::pair<int, int> plate_half_waves(double a, double b, int k) {
  k = std::max(1, k);
  // Number of (m, n >= 1) with (m/a)^2 + (n/b)^2 <= lam, summed over the index of the shorter
  // side (few terms however elongated the plate: a 10 m x 1e-8 m strip made 1e9 of the other).
  const double s_long = std::max(a, b), s_short = std::min(a, b);
  auto count = [&](double lam) {
    double c = 0;
    for (int j = 1; j / s_short <= std::sqrt(lam) && c < 1e12 && j < 100000000; ++j)
      c += std::floor(s_long * std::sqrt(lam - (j / s_short) * (j / s_short)));
    return c;
  };
  double lo = 0, hi = 1.0 / (a * a) + 1.0 / (b * b);
  while (count(hi) < k) hi *= 4;
  for (int it = 0; it < 100 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (count(mid) >= k ? hi : lo) = mid;
  }
  const int m_max = static_cast<int>(std::floor(a * std::sqrt(std::max(0.0, hi - 1 / (b * b))) + 1e-9));
  const int n_max = static_cast<int>(std::floor(b * std::sqrt(std::max(0.0, hi - 1 / (a * a))) + 1e-9));
  return {std::max(1, m_max), std::max(1, n_max)};
}

}  // namespace modalbench
