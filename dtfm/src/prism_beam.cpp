// Beam prism model: the section cut into ny x nz prisms joined by spring layers (build_beam).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "modalbench/rigid_kinematics.hpp"
#include "prism_model_detail.hpp"

namespace modalbench::dtfm::detail {

namespace {

const char* dof_name(int d) {
  static const char* names[] = {"u", "v", "w", "theta_x", "theta_y", "theta_z"};
  return names[d];
}

Eigen::Vector3d point(double y, double z) { return Eigen::Vector3d(0.0, y, z); }

/// The section's division: ny x nz prisms of dy x dz, numbered row (z) by row.
struct Grid {
  int ny = 1, nz = 1;
  double dy = 0, dz = 0;
  int prism_at(int iy, int iz) const { return iz * ny + iy; }
};

/// The spring layers' moduli (plane stress across a layer for the consistent model).
struct LayerModuli {
  double G = 0, Gs = 0, En = 0, nu = 0;
  bool consistent = false;
};

/// The fields each prism carries under the scene's physics; a plane problem keeps one prism
/// across the width (`ny`, with a note). Throws where a section other than a rectangle is cut.
std::vector<int> beam_fields(const Scene& s, int ny_req, int nz, int& ny, PrismModel& mdl) {
  std::vector<int> active;
  if (s.physics == Physics::Lateral) {
    // A rotor's lateral model: one prism (build_model refuses a cut section), bending in both planes.
    active = {Uy, Uz, Ry, Rz};
  } else if (s.physics != Physics::Spatial) {
    if (ny_req > 1)
      mdl.notes.push_back(fmt::format("physics '{}' is a plane x-z problem: the {} prisms across the width move "
                                      "together, so the model is 1x{} (the width division changes nothing)",
                                      to_string(s.physics), ny_req, nz));
    ny = 1;
    if (s.physics == Physics::Bending && nz == 1) active = {Uz, Ry};
    else active = {Ux, Uz, Ry};
  } else {
    active = {Ux, Uy, Uz, Rx, Ry, Rz};
  }
  if (ny * nz > 1 && s.cross_section.shape != SectionShape::Rectangle)
    throw InputError("command line", "--mesh",
                     fmt::format("a {} section is one prism (1x1): dtfm cuts only rectangular sections into prisms "
                                 "(got {}x{})",
                                 to_string(s.cross_section.shape), ny_req, nz));
  return active;
}

/// Each prism's stiffness and mass per slot, and its section weights.
void prism_operators(const Scene& s, const ModelOptions& opt, const Grid& g, PrismModel& mdl, Assembly& as) {
  const auto& mat = s.material;
  const int ny = g.ny, nz = g.nz;
  const bool eb = s.theory == Theory::EulerBernoulli;
  const bool paper = opt.layers == LayerModel::Paper;
  // One prism is the whole section, whatever its shape; more cut a rectangle into rectangles.
  const Section sec = ny * nz == 1 ? s.section() : rectangular_section(g.dy, g.dz);
  const double E = mat.E, G = mat.G, rho = mat.rho, kap = mat.kappa;
  // Shear of a prism in a plane across which the section is cut: the layers resolve the
  // shear-stress distribution there, so no shear coefficient (Consistent) or no prism shear
  // at all (Staggered); the printed model keeps kappa.
  auto prism_kappa = [&](int n_across) {
    if (eb) return kInf;
    if (n_across == 1 || paper) return kap;
    return opt.layers == LayerModel::Staggered ? kInf : 1.0;
  };
  const double kz = prism_kappa(nz), ky = prism_kappa(ny);
  const double torsion = paper ? sec.Ip : sec.J;
  const std::array<double, 6> stiff = {E * sec.A, ky * G * sec.A, kz * G * sec.A, G * torsion, E * sec.Iy, E * sec.Iz};
  const std::array<double, 6> mass = {rho * sec.A, rho * sec.A, rho * sec.A, rho * sec.Ip,
                                      eb ? 0.0 : rho * sec.Iy, eb ? 0.0 : rho * sec.Iz};
  for (int p = 0; p < static_cast<int>(mdl.prisms.size()); ++p) {
    as.prism_operator(p, stiff, mass);
    const std::array<double, 6> w = {sec.A, sec.A, sec.A, sec.Ip, sec.Iy, sec.Iz};
    for (int d = 0; d < 6; ++d)
      if (as.at(p, d) >= 0) mdl.section_weights(as.at(p, d), as.at(p, d)) = w[d];
  }
}

/// The spring layer between neighbouring prisms a and b (normal_z: across z), with the consistent
/// model's cross terms.
void add_layer(PrismModel& mdl, Assembly& as, const LayerModuli& lm, int a, int b, bool normal_z) {
  const double G = lm.G, Gs = lm.Gs, En = lm.En, nu = lm.nu;
  const double gauss = 0.5 / std::sqrt(3.0);
  const auto& ga = mdl.prisms[a];
  const auto& gb = mdl.prisms[b];
  const Eigen::Vector3d ca = point(ga.y, ga.z), cb = point(gb.y, gb.z);
  const Eigen::Vector3d P = 0.5 * (ca + cb);
  const double delta = (cb - ca).norm();
  const double t = normal_z ? ga.width : ga.height;  // the layer's extent in the section
  Vector6d k;
  if (normal_z) k << Gs * t / delta, Gs * t / delta, En * t / delta, En * t * t * t / (12 * delta), 0.0,
      G * t * t * t / (12 * delta);
  else k << Gs * t / delta, En * t / delta, Gs * t / delta, En * t * t * t / (12 * delta),
      G * t * t * t / (12 * delta), 0.0;
  as.scatter(mdl.Q1, a, b, sde_stiffness(P - ca, P - cb, Eigen::Matrix3d::Identity(), k));
  if (!lm.consistent) return;
  // Cross terms, integrated over the layer by 2-point Gauss (exact: every factor is linear
  // in s): G int (x-jump)(mean out-of-plane shear of the prisms) ds, and the Poisson terms
  // E' nu int (normal jump)(mean eps_xx) ds + 1/2 E' nu^2 delta int (mean eps_xx)^2 ds.
  Eigen::MatrixXd X12 = Eigen::MatrixXd::Zero(12, 12), P12 = Eigen::MatrixXd::Zero(12, 12);
  const int normal = normal_z ? Uz : Uy;
  for (double sg : {-gauss * t, gauss * t}) {
    const Eigen::Vector3d Pg = P + (normal_z ? Eigen::Vector3d(0, sg, 0) : Eigen::Vector3d(0, 0, sg));
    Eigen::Matrix<double, 1, 12> Jx, Jn;
    const Matrix6d Da = attachment(Pg - ca), Db = attachment(Pg - cb);
    Jx.leftCols<6>() = -Da.row(Ux);
    Jx.rightCols<6>() = Db.row(Ux);
    Jn.leftCols<6>() = -Da.row(normal);
    Jn.rightCols<6>() = Db.row(normal);
    Eigen::Matrix<double, 12, 1> Es = Eigen::Matrix<double, 12, 1>::Zero(), Ex = Es;
    for (int side = 0; side < 2; ++side) {
      const auto& g = side == 0 ? ga : gb;
      const int o = 6 * side;
      if (normal_z) {  // gamma_xz(y) = w' + theta_y + theta_x' (y - y_c)
        Es[o + Uz] = 0.5;
        Es[o + Rx] = 0.5 * (Pg.y() - g.y);
      } else {  // gamma_xy(z) = v' - theta_z - theta_x' (z - z_c)
        Es[o + Uy] = 0.5;
        Es[o + Rx] = -0.5 * (Pg.z() - g.z);
      }
      // eps_xx(y, z) = u' + theta_y' (z - z_c) - theta_z' (y - y_c)
      Ex[o + Ux] = 0.5;
      Ex[o + Ry] = 0.5 * (Pg.z() - g.z);
      Ex[o + Rz] = -0.5 * (Pg.y() - g.y);
    }
    const double w = 0.5 * t;
    X12 += G * w * Es * Jx + En * nu * w * Ex * Jn;
    P12 += En * nu * nu * delta * w * Ex * Ex.transpose();
  }
  as.scatter(mdl.X, a, b, X12);
  as.scatter(as.P, a, b, P12);
}

/// The spring layers between all neighbouring prisms.
void add_layers(const Scene& s, const ModelOptions& opt, const Grid& g, PrismModel& mdl, Assembly& as) {
  const auto& mat = s.material;
  const bool paper = opt.layers == LayerModel::Paper;
  const double E = mat.E, G = mat.G, kap = mat.kappa;
  // Spring layers between neighbours (Eq. (25) from the attachment kinematics) and, for the
  // consistent model, the cross terms of gamma_xz (z-layers) and gamma_xy (y-layers) and the
  // Poisson coupling. Normal strains split exactly as (plane stress across the layer)
  //   W = 1/2 E eps_xx^2 + 1/2 E' (eps_nn + nu eps_xx)^2,   E' = E / (1 - nu^2):
  // the prisms keep the first term, the layer the second (with eps_xx the prisms' mean at the
  // layer), so a free lateral surface relaxes to uniaxial stress and a clamp stiffens.
  const bool consistent = opt.layers == LayerModel::Consistent;
  LayerModuli lm;
  lm.G = G;
  lm.Gs = paper ? kap * G : G;
  lm.En = consistent ? E / (1.0 - mat.nu * mat.nu) : E;
  lm.nu = consistent ? mat.nu : 0.0;
  lm.consistent = consistent;
  for (int iz = 0; iz < g.nz; ++iz)
    for (int iy = 0; iy < g.ny; ++iy) {
      if (iy + 1 < g.ny) add_layer(mdl, as, lm, g.prism_at(iy, iz), g.prism_at(iy + 1, iz), false);
      if (iz + 1 < g.nz) add_layer(mdl, as, lm, g.prism_at(iy, iz), g.prism_at(iy, iz + 1), true);
    }
}

/// The end condition of support sp: a rigid end plate over the model's rigid motions `motions`.
EndCondition beam_end(const Support& sp, const char* where, const std::vector<int>& motions, const PrismModel& mdl) {
  const int m = mdl.m;
  if (sp.is_free()) return make_end(Eigen::MatrixXd(m, 0), {}, false, m, std::string(where) + ": free");
  const double springs[6] = {sp.axial, sp.translational, sp.translational, sp.torsional, sp.rotational,
                             sp.rotational};
  Eigen::MatrixXd T(m, static_cast<Eigen::Index>(motions.size()));
  std::vector<double> k;
  for (std::size_t i = 0; i < motions.size(); ++i) {
    T.col(static_cast<Eigen::Index>(i)) = mdl.rigid_motions.col(motions[i]);
    k.push_back(springs[motions[i]]);
  }
  return make_end(T, k, true, m, std::string(where) + ": " + sp.kind + " (rigid end plate)");
}

/// The section's rigid motions over the fields and the two ends' conditions.
void beam_ends(const Scene& s, int nz, PrismModel& mdl) {
  // Rigid section motions (about the centroid) over the fields: D(c_i) rows of active slots.
  const int m = mdl.m;
  mdl.rigid_motions = Eigen::MatrixXd::Zero(m, 6);
  for (int k = 0; k < m; ++k) {
    const auto& g = mdl.prisms[mdl.field_prism[k]];
    mdl.rigid_motions.row(k) = attachment(point(g.y, g.z)).row(mdl.field_dof[k]);
  }
  // Which rigid motions exist in this model.
  std::vector<int> motions;
  if (s.physics == Physics::Spatial) motions = {0, 1, 2, 3, 4, 5};
  else if (s.physics == Physics::Lateral) motions = {1, 2, 4, 5};
  else if (s.physics == Physics::Bending && nz == 1) motions = {2, 4};
  else motions = {0, 2, 4};
  mdl.ends[0] = beam_end(s.x0, "x0", motions, mdl);
  mdl.ends[1] = beam_end(s.xL, "xL", motions, mdl);
}

/// Adds the section's reflection z -> -z (about_z) or y -> -y where it acts on the active fields;
/// whether it does.
bool add_reflection(bool about_z, const Grid& grid, const Assembly& as, PrismModel& mdl) {
  static const int sz[6] = {+1, +1, -1, -1, -1, +1};  // z -> -z: w, theta_x, theta_y flip
  static const int sy[6] = {+1, -1, +1, -1, +1, -1};  // y -> -y: v, theta_x, theta_z flip
  const int m = mdl.m, ny = grid.ny, nz = grid.nz;
  Reflection R;
  R.perm.resize(m);
  R.sign.resize(m);
  bool nontrivial = false;
  for (int k = 0; k < m; ++k) {
    const int p = mdl.field_prism[k], d = mdl.field_dof[k];
    const int iy = p % ny, iz = p / ny;
    const int q = about_z ? grid.prism_at(iy, nz - 1 - iz) : grid.prism_at(ny - 1 - iy, iz);
    R.perm[k] = as.at(q, d);
    R.sign[k] = about_z ? sz[d] : sy[d];
    nontrivial = nontrivial || R.perm[k] != k || R.sign[k] < 0;
  }
  if (nontrivial) mdl.reflections.push_back(R);
  return nontrivial;
}

/// The section's reflections and the symmetry classes they split the fields into, by family.
void beam_symmetry(const Grid& grid, const Assembly& as, PrismModel& mdl) {
  // Reflections z -> -z and y -> -y (only those that act on the active fields).
  const bool has_y = add_reflection(false, grid, as, mdl);
  const bool has_z = add_reflection(true, grid, as, mdl);
  if (!reflections_commute(mdl)) {
    mdl.reflections.clear();
    mdl.notes.push_back("section reflections do not commute with the operator: no symmetry split");
  }
  // Families by parity (y, z): (+,+) axial, (+,-) bending x-z, (-,+) bending x-y, (-,-) torsion.
  std::vector<ModeFamily> fam;
  std::vector<std::vector<int>> rigid_cols;
  const int nr = static_cast<int>(mdl.reflections.size());
  for (int c = 0; c < (1 << nr); ++c) {
    int py = +1, pz = +1, bit = 0;
    if (has_y && nr > 0) py = (c & (1 << bit++)) ? -1 : +1;
    if (has_z && bit < nr) pz = (c & (1 << bit)) ? -1 : +1;
    if (nr == 0) {
      fam.push_back(ModeFamily::Unknown);
      rigid_cols.push_back({});
      continue;
    }
    if (py > 0 && pz > 0) { fam.push_back(ModeFamily::Axial); rigid_cols.push_back({0}); }
    else if (py > 0) { fam.push_back(ModeFamily::BendingXZ); rigid_cols.push_back({2, 4}); }
    else if (pz > 0) { fam.push_back(ModeFamily::BendingXY); rigid_cols.push_back({1, 5}); }
    else { fam.push_back(ModeFamily::Torsion); rigid_cols.push_back({3}); }
  }
  build_classes(mdl, fam, rigid_cols);
}

/// The model's description and its eigenvalue and translation scales.
void describe_beam(const Scene& s, const ModelOptions& opt, const Grid& g, const std::vector<int>& active,
                   PrismModel& mdl) {
  const double L = s.geometry.length, Bw = s.geometry.width, Hh = s.geometry.height;
  const double E = s.material.E, rho = s.material.rho;
  const bool eb = s.theory == Theory::EulerBernoulli;
  std::string fields;
  for (int d : active) fields += (fields.empty() ? "" : ", ") + std::string(dof_name(d));
  const char* planes = s.physics == Physics::Spatial   ? "spatial"
                       : s.physics == Physics::Lateral ? "lateral: x-z and x-y"
                                                       : "plane x-z";
  mdl.description = fmt::format("{}x{} prisms ({}; {} per prism: {}), {} layers, {} prisms", g.ny, g.nz, planes,
                                active.size(), fields, to_string(opt.layers), eb ? "Euler-Bernoulli" : "Timoshenko");
  const double Iy = Bw * Hh * Hh * Hh / 12.0, Iz = Hh * Bw * Bw * Bw / 12.0;
  const double Imin = carries_xy(s.physics) ? std::min(Iy, Iz) : Iy;
  mdl.lambda_scale = std::pow(std::numbers::pi / L, 4) * E * Imin / (rho * Bw * Hh);
  mdl.translation_scale = std::min(g.dz, carries_xy(s.physics) ? g.dy : g.dz);
}

}  // namespace

PrismModel build_beam(const Scene& s, int ny_req, int nz, const ModelOptions& opt) {
  PrismModel mdl;
  mdl.kind = SceneKind::Beam;
  mdl.layers = opt.layers;
  const double L = s.geometry.length, Bw = s.geometry.width, Hh = s.geometry.height;
  int ny = ny_req;
  const std::vector<int> active = beam_fields(s, ny_req, nz, ny, mdl);
  mdl.length = L;
  mdl.ny = ny;
  mdl.nz = nz;
  const Grid g{ny, nz, Bw / ny, Hh / nz};
  Assembly as(mdl);
  for (int iz = 0; iz < nz; ++iz)
    for (int iy = 0; iy < ny; ++iy)
      as.add_prism({-Bw / 2 + (iy + 0.5) * g.dy, -Hh / 2 + (iz + 0.5) * g.dz, g.dy, g.dz}, active);
  as.allocate();
  prism_operators(s, opt, g, mdl, as);
  add_layers(s, opt, g, mdl, as);
  as.finish_compliance();
  beam_ends(s, nz, mdl);
  beam_symmetry(g, as, mdl);
  describe_beam(s, opt, g, active, mdl);
  return mdl;
}

}  // namespace modalbench::dtfm::detail
