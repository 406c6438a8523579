#include "modalbench/dtfm/prism_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

#include "modalbench/rigid_kinematics.hpp"

namespace modalbench::dtfm {

std::string to_string(LayerModel l) {
  switch (l) {
    case LayerModel::Consistent: return "consistent";
    case LayerModel::Staggered: return "staggered";
    case LayerModel::Paper: return "paper";
  }
  return "?";
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using dofs::Rx;
using dofs::Ry;
using dofs::Rz;
using dofs::Ux;
using dofs::Uy;
using dofs::Uz;

const char* dof_name(int d) {
  static const char* names[] = {"u", "v", "w", "theta_x", "theta_y", "theta_z"};
  return names[d];
}

/// Collects the operator over the active fields; matrices over two prisms use the 6-slot
/// (u, v, w, theta_x, theta_y, theta_z) layout of rigid_kinematics and are scattered here.
struct Assembly {
  PrismModel& mdl;
  std::vector<std::array<int, 6>> index;  // per prism and slot: field index or -1

  explicit Assembly(PrismModel& m) : mdl(m) {}

  void add_prism(const PrismGeometry& g, const std::vector<int>& active) {
    std::array<int, 6> idx;
    idx.fill(-1);
    const int p = static_cast<int>(mdl.prisms.size());
    for (int d : active) {
      idx[d] = static_cast<int>(mdl.field_prism.size());
      mdl.field_prism.push_back(p);
      mdl.field_dof.push_back(d);
    }
    index.push_back(idx);
    mdl.prisms.push_back(g);
  }

  Eigen::MatrixXd P;       // stiffness of the deformable strains (rows/columns: strain of field k)
  std::vector<char> rigid; // strains held at zero (Euler-Bernoulli / Kirchhoff shear)

  void allocate() {
    const int m = static_cast<int>(mdl.field_prism.size());
    mdl.m = m;
    mdl.M = mdl.C = mdl.S = mdl.X = mdl.Q1 = Eigen::MatrixXd::Zero(m, m);
    mdl.section_weights = Eigen::MatrixXd::Zero(m, m);
    P = Eigen::MatrixXd::Zero(m, m);
    rigid.assign(m, 0);
  }

  /// C = P^-1 over the deformable strains, 0 on the rigid ones.
  void finish_compliance() {
    std::vector<int> f;
    for (int k = 0; k < mdl.m; ++k)
      if (!rigid[k]) f.push_back(k);
    Eigen::MatrixXd Pf(f.size(), f.size());
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t j = 0; j < f.size(); ++j) Pf(i, j) = P(f[i], f[j]);
    const Eigen::MatrixXd Cf = Pf.ldlt().solve(Eigen::MatrixXd::Identity(Pf.rows(), Pf.cols()));
    for (std::size_t i = 0; i < f.size(); ++i)
      for (std::size_t j = 0; j < f.size(); ++j) mdl.C(f[i], f[j]) = 0.5 * (Cf(i, j) + Cf(j, i));
  }

  int at(int prism, int slot) const { return index[prism][slot]; }

  /// x-strains of one prism: e_k = q_k' + S q with S(v, theta_z) = -1, S(w, theta_y) = +1;
  /// `stiffness` per slot (inf: rigid), `mass` per slot.
  void prism_operator(int p, const std::array<double, 6>& stiffness, const std::array<double, 6>& mass) {
    for (int d = 0; d < 6; ++d) {
      const int k = at(p, d);
      if (k < 0) continue;
      if (std::isinf(stiffness[d])) rigid[k] = 1;
      else P(k, k) += stiffness[d];
      mdl.M(k, k) = mass[d];
    }
    if (at(p, Uy) >= 0 && at(p, Rz) >= 0) mdl.S(at(p, Uy), at(p, Rz)) = -1.0;
    if (at(p, Uz) >= 0 && at(p, Ry) >= 0) mdl.S(at(p, Uz), at(p, Ry)) = 1.0;
  }

  /// Adds a 12 x 12 matrix over [prism a slots; prism b slots] to `target` (rows and columns
  /// both fields, or rows = strains of the same slots for X).
  void scatter(Eigen::MatrixXd& target, int a, int b, const Eigen::MatrixXd& K12) {
    int ids[12];
    for (int d = 0; d < 6; ++d) {
      ids[d] = at(a, d);
      ids[6 + d] = at(b, d);
    }
    for (int i = 0; i < 12; ++i) {
      if (ids[i] < 0) continue;
      for (int j = 0; j < 12; ++j)
        if (ids[j] >= 0) target(ids[i], ids[j]) += K12(i, j);
    }
  }
};

Eigen::Vector3d point(double y, double z) { return Eigen::Vector3d(0.0, y, z); }

/// End condition from motions T (m x r) with springs k (inf = held). `hold_rest`: everything
/// outside span(T) is held (rigid end plate); otherwise T must be unit vectors (per field).
EndCondition make_end(const Eigen::MatrixXd& T, const std::vector<double>& k, bool hold_rest, int m,
                      std::string text) {
  EndCondition e;
  e.text = std::move(text);
  if (!hold_rest) {
    // Per-field conditions: admissible = every field not held.
    std::vector<int> free_fields;
    std::vector<double> springs;
    std::vector<char> held(m, 0);
    std::vector<double> spring(m, 0.0);
    for (Eigen::Index c = 0; c < T.cols(); ++c) {
      Eigen::Index f = 0;
      T.col(c).cwiseAbs().maxCoeff(&f);
      if (std::isinf(k[c])) held[f] = 1;
      else spring[f] += k[c];
    }
    for (int f = 0; f < m; ++f)
      if (!held[f]) {
        free_fields.push_back(f);
        springs.push_back(spring[f]);
      }
    e.N = Eigen::MatrixXd::Zero(m, static_cast<Eigen::Index>(free_fields.size()));
    e.K = Eigen::MatrixXd::Zero(e.N.cols(), e.N.cols());
    for (std::size_t i = 0; i < free_fields.size(); ++i) {
      e.N(free_fields[i], static_cast<Eigen::Index>(i)) = 1.0;
      e.K(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) = springs[i];
    }
    return e;
  }
  std::vector<int> cols;
  for (Eigen::Index c = 0; c < T.cols(); ++c)
    if (!std::isinf(k[c]) && T.col(c).norm() > 0) cols.push_back(static_cast<int>(c));
  Eigen::MatrixXd Tf(m, static_cast<Eigen::Index>(cols.size()));
  Eigen::VectorXd kf(static_cast<Eigen::Index>(cols.size()));
  for (std::size_t i = 0; i < cols.size(); ++i) {
    Tf.col(static_cast<Eigen::Index>(i)) = T.col(cols[i]);
    kf[static_cast<Eigen::Index>(i)] = k[cols[i]];
  }
  if (Tf.cols() == 0) {
    e.N = Eigen::MatrixXd(m, 0);
    e.K = Eigen::MatrixXd(0, 0);
    return e;
  }
  // Tf = N R (thin QR): a = R r, springs 1/2 r^T diag(k) r = 1/2 a^T R^-T diag(k) R^-1 a.
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(Tf);
  e.N = qr.householderQ() * Eigen::MatrixXd::Identity(m, Tf.cols());
  const Eigen::MatrixXd R = e.N.transpose() * Tf;
  const Eigen::MatrixXd Rinv = R.inverse();
  e.K = Rinv.transpose() * kf.asDiagonal() * Rinv;
  e.K = 0.5 * (e.K + e.K.transpose());
  return e;
}

/// Symmetry classes from commuting reflections: orbit sums of unit vectors with signs.
void build_classes(PrismModel& mdl, const std::vector<ModeFamily>& families_by_class,
                   const std::vector<std::vector<int>>& family_rigid_columns) {
  const int m = mdl.m;
  const int nr = static_cast<int>(mdl.reflections.size());
  const int nclass = 1 << nr;
  // Group elements: products of subsets of reflections, applied as (Pi q)_k = s_k q_{perm_k}.
  auto apply = [&](int r, const Eigen::VectorXd& v) {
    Eigen::VectorXd out(m);
    const auto& R = mdl.reflections[r];
    for (int k = 0; k < m; ++k) out[k] = R.sign[k] * v[R.perm[k]];
    return out;
  };
  std::vector<std::vector<Eigen::VectorXd>> basis(nclass);
  std::vector<char> seen(m, 0);
  for (int k = 0; k < m; ++k) {
    if (seen[k]) continue;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(m);
    e[k] = 1.0;
    // Images under every group element g (subset mask), for each character c.
    std::vector<Eigen::VectorXd> images(nclass);
    for (int g = 0; g < nclass; ++g) {
      Eigen::VectorXd v = e;
      for (int r = 0; r < nr; ++r)
        if (g & (1 << r)) v = apply(r, v);
      images[g] = v;
      for (int j = 0; j < m; ++j)
        if (v[j] != 0.0) seen[j] = 1;
    }
    for (int c = 0; c < nclass; ++c) {
      Eigen::VectorXd sum = Eigen::VectorXd::Zero(m);
      for (int g = 0; g < nclass; ++g) {
        int chi = 1;
        for (int r = 0; r < nr; ++r)
          if ((g & (1 << r)) && (c & (1 << r))) chi = -chi;
        sum += chi * images[g];
      }
      if (sum.norm() > 1e-12) basis[c].push_back(sum.normalized());
    }
  }
  mdl.classes.clear();
  for (int c = 0; c < nclass; ++c) {
    if (basis[c].empty()) continue;
    FieldClass fc;
    for (int r = 0; r < nr; ++r) fc.parity.push_back((c & (1 << r)) ? -1 : +1);
    fc.V = Eigen::MatrixXd(m, static_cast<Eigen::Index>(basis[c].size()));
    for (std::size_t i = 0; i < basis[c].size(); ++i) fc.V.col(static_cast<Eigen::Index>(i)) = basis[c][i];
    fc.family = families_by_class.empty() ? ModeFamily::Unknown : families_by_class[c];
    if (!family_rigid_columns.empty() && mdl.rigid_motions.cols() == 6) {
      const auto& cols = family_rigid_columns[c];
      fc.family_motions = Eigen::MatrixXd(m, static_cast<Eigen::Index>(cols.size()));
      for (std::size_t i = 0; i < cols.size(); ++i)
        fc.family_motions.col(static_cast<Eigen::Index>(i)) = mdl.rigid_motions.col(cols[i]);
    }
    mdl.classes.push_back(std::move(fc));
  }
}

/// Checks that each reflection commutes with every operator and end condition; drops them all
/// otherwise (then a single class holds everything).
bool reflections_commute(const PrismModel& mdl) {
  for (const auto& R : mdl.reflections) {
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(mdl.m, mdl.m);
    for (int k = 0; k < mdl.m; ++k) P(k, R.perm[k]) = R.sign[k];
    for (const Eigen::MatrixXd* A : {&mdl.M, &mdl.C, &mdl.S, &mdl.X, &mdl.Q1}) {
      const double scale = A->norm() + 1e-300;
      if ((P * *A - *A * P).norm() > 1e-10 * scale) return false;
    }
    for (const auto& e : mdl.ends) {
      // span(N) invariant and springs commuting: compare the projected spring operators.
      const Eigen::MatrixXd Ks = e.N * e.K * e.N.transpose(), Pn = e.N * e.N.transpose();
      if ((P * Pn - Pn * P).norm() > 1e-10 * (Pn.norm() + 1)) return false;
      if ((P * Ks - Ks * P).norm() > 1e-10 * (Ks.norm() + 1e-300)) return false;
    }
  }
  return true;
}

// ------------------------------------------------------------------------------------------
// Beams

PrismModel build_beam(const Scene& s, int ny_req, int nz, const ModelOptions& opt) {
  PrismModel mdl;
  mdl.kind = SceneKind::Beam;
  mdl.layers = opt.layers;
  const double L = s.geometry.length, Bw = s.geometry.width, Hh = s.geometry.height;
  const auto& mat = s.material;
  int ny = ny_req;
  std::vector<int> active;
  if (s.physics != Physics::Spatial) {
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
  mdl.length = L;
  mdl.ny = ny;
  mdl.nz = nz;
  const double dy = Bw / ny, dz = Hh / nz;
  Assembly as(mdl);
  for (int iz = 0; iz < nz; ++iz)
    for (int iy = 0; iy < ny; ++iy)
      as.add_prism({-Bw / 2 + (iy + 0.5) * dy, -Hh / 2 + (iz + 0.5) * dz, dy, dz}, active);
  as.allocate();
  auto prism_at = [&](int iy, int iz) { return iz * ny + iy; };

  const bool eb = s.theory == Theory::EulerBernoulli;
  const bool paper = opt.layers == LayerModel::Paper;
  const Section sec = rectangular_section(dy, dz);
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

  // Spring layers between neighbours (Eq. (25) from the attachment kinematics) and, for the
  // consistent model, the cross terms of gamma_xz (z-layers) and gamma_xy (y-layers) and the
  // Poisson coupling. Normal strains split exactly as (plane stress across the layer)
  //   W = 1/2 E eps_xx^2 + 1/2 E' (eps_nn + nu eps_xx)^2,   E' = E / (1 - nu^2):
  // the prisms keep the first term, the layer the second (with eps_xx the prisms' mean at the
  // layer), so a free lateral surface relaxes to uniaxial stress and a clamp stiffens.
  const bool consistent = opt.layers == LayerModel::Consistent;
  const double Gs = paper ? kap * G : G;
  const double En = consistent ? E / (1.0 - mat.nu * mat.nu) : E;
  const double nu = consistent ? mat.nu : 0.0;
  const double gauss = 0.5 / std::sqrt(3.0);
  auto layer = [&](int a, int b, bool normal_z) {
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
    if (!consistent) return;
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
  };
  for (int iz = 0; iz < nz; ++iz)
    for (int iy = 0; iy < ny; ++iy) {
      if (iy + 1 < ny) layer(prism_at(iy, iz), prism_at(iy + 1, iz), false);
      if (iz + 1 < nz) layer(prism_at(iy, iz), prism_at(iy, iz + 1), true);
    }
  as.finish_compliance();

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
  else if (s.physics == Physics::Bending && nz == 1) motions = {2, 4};
  else motions = {0, 2, 4};
  auto end = [&](const Support& sp, const char* where) {
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
  };
  mdl.ends[0] = end(s.x0, "x0");
  mdl.ends[1] = end(s.xL, "xL");

  // Reflections z -> -z and y -> -y (only those that act on the active fields).
  auto reflection = [&](bool about_z) {
    static const int sz[6] = {+1, +1, -1, -1, -1, +1};  // z -> -z: w, theta_x, theta_y flip
    static const int sy[6] = {+1, -1, +1, -1, +1, -1};  // y -> -y: v, theta_x, theta_z flip
    Reflection R;
    R.perm.resize(m);
    R.sign.resize(m);
    bool nontrivial = false;
    for (int k = 0; k < m; ++k) {
      const int p = mdl.field_prism[k], d = mdl.field_dof[k];
      const int iy = p % ny, iz = p / ny;
      const int q = about_z ? prism_at(iy, nz - 1 - iz) : prism_at(ny - 1 - iy, iz);
      R.perm[k] = as.at(q, d);
      R.sign[k] = about_z ? sz[d] : sy[d];
      nontrivial = nontrivial || R.perm[k] != k || R.sign[k] < 0;
    }
    if (nontrivial) mdl.reflections.push_back(R);
    return nontrivial;
  };
  const bool has_y = reflection(false);
  const bool has_z = reflection(true);
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

  std::string fields;
  for (int d : active) fields += (fields.empty() ? "" : ", ") + std::string(dof_name(d));
  mdl.description = fmt::format("{}x{} prisms ({}; {} per prism: {}), {} layers, {} prisms", ny, nz,
                                s.physics == Physics::Spatial ? "spatial" : "plane x-z", active.size(), fields,
                                to_string(opt.layers), eb ? "Euler-Bernoulli" : "Timoshenko");
  const double Iy = Bw * Hh * Hh * Hh / 12.0, Iz = Hh * Bw * Bw * Bw / 12.0;
  const double Imin = s.physics == Physics::Spatial ? std::min(Iy, Iz) : Iy;
  mdl.lambda_scale = std::pow(std::numbers::pi / L, 4) * E * Imin / (rho * Bw * Hh);
  mdl.translation_scale = std::min(dz, s.physics == Physics::Spatial ? dy : dz);
  return mdl;
}

// ------------------------------------------------------------------------------------------
// Plates

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
  // Which fields a long edge removes: a held translation removes w and theta_y (Kirchhoff:
  // theta_y = -w' = 0; Mindlin: the hard simply supported edge), a held rotation theta_x.
  auto active_at = [&](const Support& sp) {
    std::vector<int> act;
    if (!std::isinf(sp.translational)) act.push_back(Uz);
    if (!std::isinf(sp.rotational)) act.push_back(Rx);
    if (!std::isinf(sp.translational)) act.push_back(Ry);
    return act;
  };
  Assembly as(mdl);
  for (int j = 0; j <= n; ++j) {
    const double w = (j == 0 || j == n) ? 0.5 * dl : dl;
    const std::vector<int> act =
        j == 0 ? active_at(s.y0) : (j == n ? active_at(s.yB) : std::vector<int>{Uz, Rx, Ry});
    as.add_prism({j * dl, 0.0, w, h}, act);
  }
  as.allocate();
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
  as.finish_compliance();
  // Short edges x = 0, a: per line, springs per unit length times the line's width.
  const int m = mdl.m;
  auto end = [&](const Support& sp, const char* where) {
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
  };
  mdl.ends[0] = end(s.x0, "x0");
  mdl.ends[1] = end(s.xL, "xL");
  mdl.rigid_motions = Eigen::MatrixXd(m, 0);
  // Reflection y -> b - y when both long edges are alike.
  {
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
  return mdl;
}

}  // namespace

// ------------------------------------------------------------------------------------------

Eigen::MatrixXd PrismModel::A20() const {
  for (int k = 0; k < m; ++k)
    if (!(C(k, k) > 0)) throw std::logic_error("A20 does not exist: a strain is rigid (Euler-Bernoulli/Kirchhoff)");
  const Eigen::MatrixXd P = C.inverse();
  return -0.5 * (P + P.transpose());
}

Eigen::MatrixXd PrismModel::A10() const {
  const Eigen::MatrixXd P = -A20();
  const Eigen::MatrixXd R = P * S + X;
  return R.transpose() - R;
}

Eigen::MatrixXd PrismModel::A00() const {
  const Eigen::MatrixXd P = -A20();
  return S.transpose() * P * S + S.transpose() * X + X.transpose() * S + Q1;
}

Eigen::MatrixXd PrismModel::state_matrix(double lambda) const {
  const Eigen::MatrixXd St = S + C * X;
  const Eigen::MatrixXd Qt = Q1 - X.transpose() * C * X;
  Eigen::MatrixXd A(2 * m, 2 * m);
  A.topLeftCorner(m, m) = -St;
  A.topRightCorner(m, m) = C;
  A.bottomLeftCorner(m, m) = Qt - lambda * M;
  A.bottomRightCorner(m, m) = St.transpose();
  return A;
}

int PrismModel::field(int prism, int dof) const {
  for (int k = 0; k < m; ++k)
    if (field_prism[k] == prism && field_dof[k] == dof) return k;
  return -1;
}

namespace {
/// The two strip lines around y and the weight of the upper one.
void plate_bracket(const PrismModel& mdl, double y, int& j0, double& t) {
  const int n = static_cast<int>(mdl.prisms.size()) - 1;
  const double dl = mdl.prisms[1].y - mdl.prisms[0].y;
  j0 = std::clamp(static_cast<int>(std::floor(y / dl)), 0, n - 1);
  t = std::clamp((y - mdl.prisms[j0].y) / dl, 0.0, 1.0);
}

/// H = sum over prisms of D_i^T Lambda_i D_i over all six slots (the section's rigid-motion metric).
Matrix6d section_metric(const PrismModel& mdl) {
  Matrix6d H = Matrix6d::Zero();
  for (const auto& g : mdl.prisms) {
    const Section sec = rectangular_section(g.width, g.height);
    Vector6d w;
    w << sec.A, sec.A, sec.A, sec.Ip, sec.Iy, sec.Iz;
    const Matrix6d D = attachment(Eigen::Vector3d(0, g.y, g.z));
    H += D.transpose() * w.asDiagonal() * D;
  }
  return H;
}
}  // namespace

Eigen::VectorXd PrismModel::load_vector(const PointLoad& load) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(m);
  if (kind == SceneKind::Plate) {
    int j0;
    double t;
    plate_bracket(*this, load.y, j0, t);
    const int k0 = field(j0, Uz), k1 = field(j0 + 1, Uz);
    if (k0 >= 0) f[k0] += (1.0 - t) * load.Fz;
    if (k1 >= 0) f[k1] += t * load.Fz;
    return f;
  }
  Vector6d F;
  F << load.Fx, load.Fy, load.Fz, load.Mx, load.My, load.Mz;
  const Vector6d r = section_metric(*this).ldlt().solve(F);
  return section_weights * rigid_motions * r;
}

Deflection PrismModel::section_response(const Eigen::VectorXd& q, double y) const {
  Deflection d;
  if (kind == SceneKind::Plate) {
    int j0;
    double t;
    plate_bracket(*this, y, j0, t);
    auto value = [&](int dof) {
      const int k0 = field(j0, dof), k1 = field(j0 + 1, dof);
      return (k0 >= 0 ? (1.0 - t) * q[k0] : 0.0) + (k1 >= 0 ? t * q[k1] : 0.0);
    };
    d.w = value(Uz);
    d.theta_x = value(Rx);
    d.theta_y = value(Ry);
    return d;
  }
  const Vector6d r = section_metric(*this).ldlt().solve(Vector6d(rigid_motions.transpose() * section_weights * q));
  // Components the physics does not carry stay 0 (their rows are absent from rigid_motions).
  d.u = r[0];
  d.v = r[1];
  d.w = r[2];
  d.theta_x = r[3];
  d.theta_y = r[4];
  d.theta_z = r[5];
  return d;
}

Eigen::RowVectorXd PrismModel::w_observer(double y) const {
  if (kind == SceneKind::Plate) {
    int j0;
    double t;
    plate_bracket(*this, y, j0, t);
    Eigen::RowVectorXd o = Eigen::RowVectorXd::Zero(m);
    const int k0 = field(j0, Uz), k1 = field(j0 + 1, Uz);
    if (k0 >= 0) o[k0] = 1.0 - t;
    if (k1 >= 0) o[k1] = t;
    return o;
  }
  // Conjugate of a unit Fz: w_section = (load vector of Fz = 1)^T q.
  PointLoad unit;
  unit.Fz = 1.0;
  return load_vector(unit).transpose();
}

PrismModel build_model(const Scene& scene, const Discretization& mesh, const ModelOptions& options) {
  const auto bad = [&](const std::string& why) { throw InputError("command line", "--mesh", why); };
  if (scene.is_plate()) {
    if (mesh.counts.size() != 1)
      bad("the dtfm plate mesh is the number of strips across the width, e.g. 10 (got '" + mesh.spec() + "')");
    const int n = mesh.counts[0];
    if (n < 2 || n > 400) bad("the number of strips must lie in [2, 400] (got " + std::to_string(n) + ")");
    return build_plate(scene, n, options);
  }
  int ny = 0, nz = 0;
  if (mesh.counts.size() == 1) ny = nz = mesh.counts[0];
  else if (mesh.counts.size() == 2) {
    ny = mesh.counts[0];
    nz = mesh.counts[1];
  } else {
    bad("the dtfm beam mesh is NYxNZ prisms across the width and height, e.g. 2x2 (got '" + mesh.spec() + "')");
  }
  const int per = scene.physics == Physics::Spatial ? 6 : 3;
  const long fields = static_cast<long>(scene.physics == Physics::Spatial ? ny : 1) * nz * per;
  if (ny > 64 || nz > 64 || fields > 800)
    bad(fmt::format("{}x{} prisms give {} fields: at most 800 (and 64 prisms per side) are supported", ny, nz,
                    fields));
  return build_beam(scene, ny, nz, options);
}

}  // namespace modalbench::dtfm
