// Plate prism model: strips across the width, centred on lines and joined by spring layers
// (build_plate, in its parts: the lines and their operators, the layers, the short edges, the
// reflection, the rigid motions the edges leave free).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "modalbench/rigid_kinematics.hpp"
#include "prism_model_detail.hpp"

namespace modalbench::dtfm::detail {

namespace {

/// What build_plate's parts share: the scene's plate and the options.
struct PlateSpec {
  const Scene& s;
  const ModelOptions& opt;
  int n;            ///< strips
  double dl;        ///< b / n
  bool paper, kirchhoff;
  double E, G, nu, rho, kap, D, h;
};

/// The n + 1 lines (edge strips half wide) and the fields each carries: a long edge's hold removes
/// the fields it fixes.
void plate_lines(const PlateSpec& p, Assembly& as) {
  const Scene& s = p.s;
  const int n = p.n;
  const double dl = p.dl, h = p.h;
  // Which fields a long edge removes: a held translation removes w and theta_y (Kirchhoff:
  // theta_y = -w' = 0; Mindlin: the hard simply supported edge), a held rotation theta_x.
  auto active_at = [&](const Support& sp) {
    std::vector<int> act;
    if (!std::isinf(sp.translational)) act.push_back(Uz);
    if (!std::isinf(sp.rotational)) act.push_back(Rx);
    if (!std::isinf(sp.translational)) act.push_back(Ry);
    return act;
  };
  for (int j = 0; j <= n; ++j) {
    const double w = (j == 0 || j == n) ? 0.5 * dl : dl;
    const std::vector<int> act =
        j == 0 ? active_at(s.y0) : (j == n ? active_at(s.yB) : std::vector<int>{Uz, Rx, Ry});
    as.add_prism({j * dl, 0.0, w, h}, act);
  }
}

/// Each line's strip: its stiffness and mass per unit length, the rigid motion's kinetic energy
/// about its line, its section weights and the long edges' springs.
void plate_line_operators(const PlateSpec& p, PrismModel& mdl, Assembly& as) {
  const Scene& s = p.s;
  const int n = p.n;
  const bool paper = p.paper, kirchhoff = p.kirchhoff;
  const double dl = p.dl, E = p.E, G = p.G, nu = p.nu, rho = p.rho, kap = p.kap, D = p.D, h = p.h;
  for (int j = 0; j <= n; ++j) {
    const double w = mdl.prisms[j].width;
    std::array<double, 6> stiff, mass;
    stiff.fill(kInf);
    mass.fill(0.0);
    if (paper) {
      stiff[Uz] = kap * G * h * w;
      stiff[Rx] = G * (w * h * h * h + h * w * w * w) / 12.0;
      stiff[Ry] = E * w * h * h * h / 12.0;
      mass[Rx] = rho * (w * h * h * h + h * w * w * w) / 12.0;
      mass[Ry] = rho * w * h * h * h / 12.0;
    } else {
      stiff[Uz] = kirchhoff ? kInf : kap * G * h * w;
      // Bending: 1/2 D (k_x^2 + k_y^2 + 2 nu k_x k_y) = 1/2 D (1 - nu^2) k_x^2 + 1/2 D (k_y + nu k_x)^2;
      // the strip keeps the first part (a free long edge then relaxes to the beam value).
      stiff[Rx] = 0.5 * D * (1.0 - nu) * w;
      stiff[Ry] = D * (1.0 - nu * nu) * w;
      mass[Rx] = mass[Ry] = kirchhoff ? 0.0 : rho * h * h * h / 12.0 * w;
    }
    mass[Uz] = rho * h * w;
    as.prism_operator(j, stiff, mass);
    if (!paper && as.at(j, Uz) >= 0 && as.at(j, Rx) >= 0) {
      // The strip's kinetic energy is that of its rigid motion about its line,
      // rho h int (w + theta_x (y - y_j))^2 dy over its extent (the paper's rho I_0x): the width
      // term also cancels the leading dispersion error of the layer scheme across the width.
      const double lo = j == 0 ? 0.0 : -0.5 * dl, hi = j == n ? 0.0 : 0.5 * dl;
      const double s1 = 0.5 * (hi * hi - lo * lo), s2 = (hi * hi * hi - lo * lo * lo) / 3.0;
      const int kw = as.at(j, Uz), kt = as.at(j, Rx);
      mdl.M(kt, kt) += rho * h * s2;
      mdl.M(kw, kt) += rho * h * s1;
      mdl.M(kt, kw) += rho * h * s1;
    } else if (!paper && as.at(j, Rx) >= 0) {
      const double lo = j == 0 ? 0.0 : -0.5 * dl, hi = j == n ? 0.0 : 0.5 * dl;
      mdl.M(as.at(j, Rx), as.at(j, Rx)) += rho * h * (hi * hi * hi - lo * lo * lo) / 3.0;
    }
    for (int d : {Uz, Rx, Ry})
      if (as.at(j, d) >= 0) mdl.section_weights(as.at(j, d), as.at(j, d)) = w;
    // Supports along the long edges act on the edge lines (springs per unit length).
    const Support* edge = j == 0 ? &s.y0 : (j == n ? &s.yB : nullptr);
    if (edge) {
      if (as.at(j, Uz) >= 0) mdl.Q1(as.at(j, Uz), as.at(j, Uz)) += edge->translational;
      if (as.at(j, Rx) >= 0) mdl.Q1(as.at(j, Rx), as.at(j, Rx)) += edge->rotational;
    }
  }
}

/// The layers between neighbouring lines.
void plate_layers(const PlateSpec& p, PrismModel& mdl, Assembly& as) {
  const ModelOptions& opt = p.opt;
  const int n = p.n;
  const bool paper = p.paper, kirchhoff = p.kirchhoff;
  const double dl = p.dl, E = p.E, G = p.G, nu = p.nu, kap = p.kap, D = p.D, h = p.h;
  // Layers between lines j and j + 1: springs (transverse shear, bending across the width,
  // twist) from the attachment kinematics, then the Poisson and twist cross terms.
  const double k_shear = paper ? kap * G * h / dl
                               : (kirchhoff ? opt.kirchhoff_penalty * 12.0 * D / (dl * dl * dl) : kap * G * h / dl);
  const double k_bend = paper ? E * h * h * h / (12.0 * dl) : D / dl;
  const double k_twist = paper ? G * h * h * h / (12.0 * dl) : 0.5 * D * (1.0 - nu) / dl;
  for (int j = 0; j < n; ++j) {
    Vector6d k;
    k << 0.0, 0.0, k_shear, k_bend, k_twist, 0.0;
    const Eigen::Vector3d ra(0, 0.5 * dl, 0), rb(0, -0.5 * dl, 0);
    as.scatter(mdl.Q1, j, j + 1, sde_stiffness(ra, rb, Eigen::Matrix3d::Identity(), k));
    if (paper) continue;
    // 1/2 D dl (k_y + nu k_x,avg)^2 with k_x = -theta_y', k_y = (theta_x,b - theta_x,a) / dl: the
    // spring D / dl above, the cross term nu D dl k_x,avg k_y and 1/2 D nu^2 dl k_x,avg^2;
    // twist D (1 - nu) / 2 * dl * a * b_avg with a = -(theta_y,b - theta_y,a) / dl, b = theta_x'.
    Eigen::MatrixXd X12 = Eigen::MatrixXd::Zero(12, 12), P12 = Eigen::MatrixXd::Zero(12, 12);
    for (int side : {0, 6}) {
      X12(side + Ry, Rx) += 0.5 * nu * D;
      X12(side + Ry, 6 + Rx) -= 0.5 * nu * D;
      X12(side + Rx, Ry) += 0.25 * D * (1.0 - nu);
      X12(side + Rx, 6 + Ry) -= 0.25 * D * (1.0 - nu);
      for (int other : {0, 6}) P12(side + Ry, other + Ry) += 0.25 * D * nu * nu * dl;
    }
    as.scatter(mdl.X, j, j + 1, X12);
    as.scatter(as.P, j, j + 1, P12);
  }
}

/// A short edge x = 0 or a: per line, springs per unit length times the line's width.
EndCondition plate_short_edge(const Support& sp, const char* where, const PrismModel& mdl, const Assembly& as, int n) {
  const int m = mdl.m;
  std::vector<Eigen::VectorXd> cols;
  std::vector<double> k;
  auto add = [&](int f, double v) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(m);
    e[f] = 1.0;
    cols.push_back(e);
    k.push_back(v);
  };
  for (int j = 0; j <= n; ++j) {
    const double w = mdl.prisms[j].width;
    if (as.at(j, Uz) >= 0) add(as.at(j, Uz), std::isinf(sp.translational) ? kInf : sp.translational * w);
    // A held edge line also holds the strip's twist (Kirchhoff: theta_x = dw/dy = 0 along it).
    if (as.at(j, Rx) >= 0 && std::isinf(sp.translational)) add(as.at(j, Rx), kInf);
    if (as.at(j, Ry) >= 0) add(as.at(j, Ry), std::isinf(sp.rotational) ? kInf : sp.rotational * w);
  }
  Eigen::MatrixXd T(m, static_cast<Eigen::Index>(cols.size()));
  for (std::size_t i = 0; i < cols.size(); ++i) T.col(static_cast<Eigen::Index>(i)) = cols[i];
  return make_end(T, k, false, m, std::string(where) + ": " + sp.kind);
}

/// The reflection y -> b - y, where both long edges are alike.
void plate_reflection(PrismModel& mdl, const Assembly& as, int n) {
  const int m = mdl.m;
  Reflection R;
  R.perm.resize(m);
  R.sign.resize(m);
  bool ok = true;
  for (int k = 0; k < m && ok; ++k) {
    const int j = mdl.field_prism[k], d = mdl.field_dof[k];
    R.perm[k] = as.at(n - j, d);
    R.sign[k] = d == Rx ? -1 : +1;
    ok = R.perm[k] >= 0;
  }
  if (ok) {
    mdl.reflections.push_back(R);
    if (!reflections_commute(mdl)) mdl.reflections.clear();
  }
}

/// Rigid-body motions w = a0 + a1 x / a + a2 y / b left free by the edges: a held translation
/// along an edge fixes w there (two conditions), a held rotation its normal slope.
void plate_rigid_motions(const Scene& s, PrismModel& mdl) {
  std::vector<Eigen::RowVector3d> rows;
  bool spring = false;
  auto edge = [&](const Support& sp, Eigen::RowVector3d at, Eigen::RowVector3d along, Eigen::RowVector3d normal) {
    for (double k : {sp.translational, sp.rotational}) spring = spring || (k != 0.0 && !std::isinf(k));
    if (std::isinf(sp.translational)) rows.insert(rows.end(), {at, along});
    if (std::isinf(sp.rotational)) rows.push_back(normal);
  };
  edge(s.x0, {1, 0, 0}, {0, 0, 1}, {0, 1, 0});
  edge(s.xL, {1, 1, 0}, {0, 0, 1}, {0, 1, 0});
  edge(s.y0, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  edge(s.yB, {1, 0, 1}, {0, 1, 0}, {0, 0, 1});
  if (!spring) {
    Eigen::MatrixXd Cm(static_cast<Eigen::Index>(rows.size()), 3);
    for (std::size_t i = 0; i < rows.size(); ++i) Cm.row(static_cast<Eigen::Index>(i)) = rows[i];
    mdl.rigid_body_motions = 3 - (rows.empty() ? 0 : static_cast<int>(Eigen::FullPivLU<Eigen::MatrixXd>(Cm).rank()));
  }
}

}  // namespace

PrismModel build_plate(const Scene& s, int n, const ModelOptions& opt) {
  PrismModel mdl;
  mdl.kind = SceneKind::Plate;
  mdl.layers = opt.layers == LayerModel::Staggered ? LayerModel::Consistent : opt.layers;
  const bool paper = mdl.layers == LayerModel::Paper;
  const double a = s.geometry.length, b = s.geometry.width, h = s.geometry.height;
  const auto& mat = s.material;
  const double E = mat.E, G = mat.G, nu = mat.nu, rho = mat.rho, kap = mat.kappa, D = s.plate_D();
  const bool kirchhoff = s.theory == Theory::Kirchhoff && !paper;
  const double dl = b / n;
  mdl.length = a;
  mdl.ny = n + 1;
  mdl.nz = 1;
  const PlateSpec spec{s, opt, n, dl, paper, kirchhoff, E, G, nu, rho, kap, D, h};
  Assembly as(mdl);
  plate_lines(spec, as);
  as.allocate();
  plate_line_operators(spec, mdl, as);
  plate_layers(spec, mdl, as);
  as.finish_compliance();
  mdl.ends[0] = plate_short_edge(s.x0, "x0", mdl, as, n);
  mdl.ends[1] = plate_short_edge(s.xL, "xL", mdl, as, n);
  mdl.rigid_motions = Eigen::MatrixXd(mdl.m, 0);
  plate_reflection(mdl, as, n);
  build_classes(mdl, std::vector<ModeFamily>(1u << mdl.reflections.size(), ModeFamily::Plate), {});
  mdl.description = fmt::format("{} strips ({} lines y = j b/{}, edge strips half wide; w, theta_x, theta_y), "
                                "{} layers, {} strips",
                                n, n + 1, n, to_string(mdl.layers),
                                paper ? "Timoshenko (beam moduli)" : (kirchhoff ? "Kirchhoff" : "Mindlin"));
  if (kirchhoff)
    mdl.notes.push_back(fmt::format("Kirchhoff plate: strips rigid in transverse shear; the layers' transverse shear "
                                    "is a penalty {:g} x 12 D / dy^3",
                                    opt.kirchhoff_penalty));
  mdl.lambda_scale = D / (rho * h) * std::pow(std::numbers::pi / std::max(a, b), 4);
  mdl.translation_scale = h;
  plate_rigid_motions(s, mdl);
  auto holds = [](const Support& e) { return std::isinf(e.translational) || std::isinf(e.rotational); };
  if (holds(s.y0) || holds(s.yB)) {
    Scene free = s;
    free.y0 = free.yB = Support{};
    mdl.free_long_edges = std::make_shared<const PrismModel>(build_plate(free, n, opt));
  }
  return mdl;
}

}  // namespace modalbench::dtfm::detail
