// The prism operator of Eq. (32): symmetries, the paper's single-prism matrices (34)-(36),
// (39), the layer blocks of (38) from the attachment kinematics, energy positivity, and the
// symmetry classes.
#define BOOST_TEST_MODULE dtfm_model
#include <boost/test/unit_test.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>
#include <vector>

#include "modalbench/dtfm/prism_model.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"
#include "modalbench/rigid_kinematics.hpp"

using namespace modalbench;
using namespace modalbench::dtfm;

namespace {

Scene beam_scene(Physics physics, double width = 0.25) {
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  s.physics = physics;
  s.geometry.width = width;
  s.loads.clear();
  return s;
}

Scene plate_scene(Theory theory) {
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml");
  s.theory = theory;
  return s;
}

double asym(const Eigen::MatrixXd& A) { return (A - A.transpose()).norm() / std::max(A.norm(), 1e-300); }
double skew_defect(const Eigen::MatrixXd& A) { return (A + A.transpose()).norm() / std::max(A.norm(), 1e-300); }

/// The energy quadratic form over (e, q): [[P, X], [X^T, Q1]] must be positive semidefinite.
double min_energy_eigenvalue(const PrismModel& m) {
  const Eigen::MatrixXd P = -m.A20();
  Eigen::MatrixXd E(2 * m.m, 2 * m.m);
  E << P, m.X, m.X.transpose(), m.Q1;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (E + E.transpose()));
  return es.eigenvalues().minCoeff() / es.eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(operator_form)

// A02, A20, A00 symmetric and A10 skew for every layer model, beams (plane and spatial) and
// plates; the energy is positive semidefinite and A02 positive.
BOOST_AUTO_TEST_CASE(symmetric_and_skew_for_all_models) {
  struct Case {
    Scene scene;
    const char* mesh;
  };
  std::vector<Case> cases = {{beam_scene(Physics::Planar), "1x4"},
                             {beam_scene(Physics::Spatial, 0.2), "3x2"},
                             {beam_scene(Physics::Bending), "1x3"},
                             {plate_scene(Theory::Mindlin), "7"}};
  for (auto& c : cases)
    for (LayerModel lm : {LayerModel::Consistent, LayerModel::Staggered, LayerModel::Paper}) {
      if (lm == LayerModel::Staggered && c.scene.is_beam()) continue;  // rigid prism shear: no A20
      ModelOptions o;
      o.layers = lm;
      const PrismModel m = build_model(c.scene, Discretization::parse(c.mesh), o);
      BOOST_TEST_CONTEXT(c.scene.name << " " << c.mesh << " " << to_string(lm)) {
        BOOST_TEST(asym(m.A02()) < 1e-15);
        BOOST_TEST(asym(m.A20()) < 1e-13);
        BOOST_TEST(asym(m.A00()) < 1e-13);
        BOOST_TEST(skew_defect(m.A10()) < 1e-13);
        BOOST_TEST(min_energy_eigenvalue(m) > -1e-12);
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(m.A02());
        BOOST_TEST(es.eigenvalues().minCoeff() > 0.0);
      }
    }
}

// The Hamiltonian state matrix gives symmetric segment matrices: checked on the operator by
// J A + (J A)^T = 0 with J the symplectic unit.
BOOST_AUTO_TEST_CASE(state_matrix_is_hamiltonian) {
  for (const char* mesh : {"1x1", "1x4"}) {
    const PrismModel m = build_model(beam_scene(Physics::Planar), Discretization::parse(mesh));
    const Eigen::MatrixXd A = m.state_matrix(3.0e7);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * m.m, 2 * m.m);
    J.topRightCorner(m.m, m.m).setIdentity();
    J.bottomLeftCorner(m.m, m.m) = -Eigen::MatrixXd::Identity(m.m, m.m);
    const Eigen::MatrixXd JA = J * A;
    BOOST_TEST((JA - JA.transpose()).norm() / JA.norm() < 1e-14);
  }
}

// A uniform prism is the same read from either end: with the fields' parities P (w, v even;
// slopes, axial displacement odd), R A R = -A for R = diag(P, -P). The segment solver finds P and
// uses it (segment_dynamic_stiffness.hpp); here R A R + A is checked entry by entry.
BOOST_AUTO_TEST_CASE(uniform_prisms_are_symmetric_end_for_end) {
  std::vector<PrismModel> models;
  models.push_back(build_model(beam_scene(Physics::Planar), Discretization::parse("2x2")));
  models.push_back(build_model(beam_scene(Physics::Spatial), Discretization::parse("2x2")));
  models.push_back(build_model(plate_scene(Theory::Kirchhoff), Discretization::parse("10")));
  models.push_back(build_model(plate_scene(Theory::Mindlin), Discretization::parse("10")));
  for (std::size_t i = 0; i < models.size(); ++i) {
    const Eigen::MatrixXd A = models[i].state_matrix(3.0e7);
    const auto p = reflection_signs(A);
    BOOST_TEST_REQUIRE(p.has_value(), "model " << i);
    Eigen::VectorXd r(2 * models[i].m);
    r << *p, -*p;
    const Eigen::MatrixXd RAR = r.asDiagonal() * A * r.asDiagonal();
    BOOST_TEST((RAR + A).cwiseAbs().maxCoeff() == 0.0, "model " << i);
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(paper_matrices)

// One spatial prism in the printed model: A02r = diag(rho A, rho A, rho A, rho I0x, rho Iyx,
// rho Izx), A20r = -diag(EA, kGA, kGA, G I0x, E Iyx, E Izx), A10r and A_sr of Eqs. (36), (39).
BOOST_AUTO_TEST_CASE(single_prism_eqs_34_to_39) {
  const Scene s = beam_scene(Physics::Spatial, 0.2);
  ModelOptions o;
  o.layers = LayerModel::Paper;
  const PrismModel m = build_model(s, Discretization::parse("1x1"), o);
  BOOST_REQUIRE(m.m == 6);
  const double E = s.material.E, G = s.material.G, rho = s.material.rho, k = s.material.kappa;
  const double b = 0.2, h = 0.25, A = b * h, Iy = b * h * h * h / 12, Iz = h * b * b * b / 12, I0 = Iy + Iz;
  Eigen::VectorXd d02(6), d20(6);
  d02 << rho * A, rho * A, rho * A, rho * I0, rho * Iy, rho * Iz;
  d20 << -E * A, -k * G * A, -k * G * A, -G * I0, -E * Iy, -E * Iz;
  BOOST_TEST((m.A02() - Eigen::MatrixXd(d02.asDiagonal())).norm() < 1e-12 * d02.norm());
  BOOST_TEST((m.A20() - Eigen::MatrixXd(d20.asDiagonal())).norm() < 1e-12 * d20.norm());
  Eigen::MatrixXd A10 = Eigen::MatrixXd::Zero(6, 6), As = Eigen::MatrixXd::Zero(6, 6);
  A10(1, 5) = k * G * A;
  A10(2, 4) = -k * G * A;
  A10(4, 2) = k * G * A;
  A10(5, 1) = -k * G * A;
  As(4, 4) = As(5, 5) = k * G * A;
  BOOST_TEST((m.A10() - A10).norm() < 1e-12 * A10.norm());
  BOOST_TEST((m.A00() - As).norm() < 1e-12 * As.norm());
}

namespace {
/// The printed layer blocks A_rrk, A_rpk of Eq. (38) for stiffnesses c1..c6 (Eq. (25)) and
/// offsets s_r = P - c_r, s_p = P - c_p (components 2, 3 = y, z). `printed` keeps the
/// printed a_rpk42, a_rpk43, a_rpk44, which use s_pk where the kinematics gives s_rk.
std::pair<Eigen::MatrixXd, Eigen::MatrixXd> paper_blocks(const double c[6], double sr2, double sr3, double sp2,
                                                         double sp3, bool printed) {
  const double c1 = c[0], c2 = c[1], c3 = c[2], c4 = c[3], c5 = c[4], c6 = c[5];
  Eigen::MatrixXd Arr = Eigen::MatrixXd::Zero(6, 6), Arp = Eigen::MatrixXd::Zero(6, 6);
  Arr(0, 0) = c1, Arr(0, 4) = c1 * sr3, Arr(0, 5) = -c1 * sr2;
  Arr(1, 1) = c2, Arr(1, 3) = -c2 * sr3;
  Arr(2, 2) = c3, Arr(2, 3) = c3 * sr2;
  Arr(3, 3) = c4 + c2 * sr3 * sr3 + c3 * sr2 * sr2;
  Arr(4, 4) = c5 + c1 * sr3 * sr3, Arr(4, 5) = -c1 * sr2 * sr3;
  Arr(5, 5) = c6 + c1 * sr2 * sr2;
  Arr = Eigen::MatrixXd(Arr.selfadjointView<Eigen::Upper>());
  const double q3 = printed ? sp3 : sr3, q2 = printed ? sp2 : sr2;
  Arp(0, 0) = -c1, Arp(0, 4) = -c1 * sp3, Arp(0, 5) = c1 * sp2;
  Arp(1, 1) = -c2, Arp(1, 3) = c2 * sp3;
  Arp(2, 2) = -c3, Arp(2, 3) = -c3 * sp2;
  Arp(3, 1) = c2 * q3, Arp(3, 2) = -c3 * q2, Arp(3, 3) = -c4 - c2 * q3 * sp3 - c3 * q2 * sp2;
  Arp(4, 0) = -c1 * sr3, Arp(4, 4) = -c5 - c1 * sr3 * sp3, Arp(4, 5) = c1 * sr3 * sp2;
  Arp(5, 0) = c1 * sr2, Arp(5, 4) = c1 * sr2 * sp3, Arp(5, 5) = -c6 - c1 * sr2 * sp2;
  return {Arr, Arp};
}
}  // namespace

// Two prisms joined by one layer: the layer's part of A00 is the printed A_rrk, A_rpk of
// Eq. (38) with Eq. (25)'s stiffnesses and s_rk = P - c_r, once the printed a_rpk42, a_rpk43,
// a_rpk44 are read with s_rk where they print s_pk (docs/sources.md, P6; the printed form is not
// symmetric). Side by side (y-normal layer; c as printed) and stacked (z-normal; c permuted).
BOOST_AUTO_TEST_CASE(layer_blocks_eq_38) {
  const Scene s = beam_scene(Physics::Spatial, 0.25);
  ModelOptions o;
  o.layers = LayerModel::Paper;
  const double E = s.material.E, G = s.material.G, k = s.material.kappa;
  {
    const PrismModel m = build_model(s, Discretization::parse("2x1"), o);
    BOOST_REQUIRE(m.m == 12);
    const double dy = 0.125, dz = 0.25;
    const double c[6] = {k * G * dz / dy, E * dz / dy, k * G * dz / dy, E * dz * dz * dz / (12 * dy),
                         G * dz * dz * dz / (12 * dy), 0.0};
    const auto [Arr, Arp] = paper_blocks(c, dy / 2, 0.0, -dy / 2, 0.0, false);
    BOOST_TEST((m.Q1.topLeftCorner(6, 6) - Arr).norm() < 1e-12 * Arr.norm());
    BOOST_TEST((m.Q1.topRightCorner(6, 6) - Arp).norm() < 1e-12 * Arp.norm());
    BOOST_TEST((m.Q1.bottomLeftCorner(6, 6) - Arp.transpose()).norm() < 1e-12 * Arp.norm());
  }
  {
    const PrismModel m = build_model(s, Discretization::parse("1x2"), o);
    BOOST_REQUIRE(m.m == 12);
    const double dy = 0.25, dz = 0.125;
    // Normal z: shear along x and y, normal along z, bending about x, twist about z.
    const double c[6] = {k * G * dy / dz, k * G * dy / dz, E * dy / dz, E * dy * dy * dy / (12 * dz), 0.0,
                         G * dy * dy * dy / (12 * dz)};
    const auto [Arr, Arp] = paper_blocks(c, 0.0, dz / 2, 0.0, -dz / 2, false);
    BOOST_TEST((m.Q1.topLeftCorner(6, 6) - Arr).norm() < 1e-12 * Arr.norm());
    BOOST_TEST((m.Q1.topRightCorner(6, 6) - Arp).norm() < 1e-12 * Arp.norm());
    const auto printed = paper_blocks(c, 0.0, dz / 2, 0.0, -dz / 2, true);
    BOOST_TEST((printed.second - Arp).norm() > 1e-3 * Arp.norm());  // the typo matters here
    BOOST_TEST(asym(m.A00()) < 1e-13);
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(energy)

// Rigid section motions (constant along x) store no energy: A00 T = 0 and R T = 0 for every
// layer model (the layers see no jump, the prisms no strain).
BOOST_AUTO_TEST_CASE(rigid_motions_are_free) {
  for (LayerModel lm : {LayerModel::Consistent, LayerModel::Paper}) {
    ModelOptions o;
    o.layers = lm;
    const PrismModel m = build_model(beam_scene(Physics::Spatial, 0.2), Discretization::parse("3x2"), o);
    // Translations and the rotation about x carry no strain when constant (theta_y, theta_z
    // would need u linear in x).
    for (int c : {0, 1, 2, 3}) {
      const Eigen::VectorXd t = m.rigid_motions.col(c);
      BOOST_TEST_CONTEXT("layers " << to_string(lm) << ", motion " << c) {
        BOOST_TEST((m.A00() * t).norm() < 1e-9 * m.A00().norm() * t.norm());
      }
    }
  }
}

// Pure bending of the whole section (w = kappa x^2 / 2, theta_y = -w', u_i = z_i theta_y) in
// the Eq. (25) spring model stores exactly 1/2 E I kappa^2 per unit length at any x: the layers
// see no jump, the prisms their own bending plus axial strain (sum A_i z_i^2 + I_i = I).
BOOST_AUTO_TEST_CASE(pure_bending_energy_is_EI) {
  ModelOptions o;
  o.layers = LayerModel::Paper;
  const Scene s = beam_scene(Physics::Planar);
  const PrismModel m = build_model(s, Discretization::parse("1x5"), o);
  const double kappa = 1e-3, x = 0.3;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.m), qp = Eigen::VectorXd::Zero(m.m);
  for (int k = 0; k < m.m; ++k) {
    const double z = m.prisms[m.field_prism[k]].z;
    switch (m.field_dof[k]) {
      case dofs::Ux: q[k] = -z * kappa * x, qp[k] = -z * kappa; break;
      case dofs::Uz: q[k] = 0.5 * kappa * x * x, qp[k] = kappa * x; break;
      case dofs::Ry: q[k] = -kappa * x, qp[k] = -kappa; break;
      default: break;
    }
  }
  const Eigen::VectorXd e = qp + m.S * q;
  const double U = 0.5 * e.dot((-m.A20()) * e) + e.dot(m.X * q) + 0.5 * q.dot(m.Q1 * q);
  const double EI = s.material.E * s.geometry.width * std::pow(s.geometry.height, 3) / 12;
  BOOST_TEST(std::abs(U / (0.5 * EI * kappa * kappa) - 1.0) < 1e-12);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(symmetry)

// The classes' bases are orthonormal, span the fields, and block-diagonalise every operator.
BOOST_AUTO_TEST_CASE(classes_block_diagonalise) {
  for (auto [scene, mesh] : {std::pair{beam_scene(Physics::Spatial, 0.2), "3x2"},
                             std::pair{beam_scene(Physics::Planar), "1x3"}, std::pair{plate_scene(Theory::Kirchhoff), "6"}}) {
    const PrismModel m = build_model(scene, Discretization::parse(mesh));
    Eigen::MatrixXd V(m.m, 0);
    for (const auto& c : m.classes) {
      Eigen::MatrixXd W(m.m, V.cols() + c.V.cols());
      W << V, c.V;
      V = W;
    }
    BOOST_TEST_CONTEXT(scene.name << " " << mesh) {
      BOOST_TEST(V.cols() == m.m);
      BOOST_TEST((V.transpose() * V - Eigen::MatrixXd::Identity(m.m, m.m)).norm() < 1e-12);
      for (const Eigen::MatrixXd* A : {&m.M, &m.C, &m.S, &m.X, &m.Q1}) {
        Eigen::MatrixXd B = V.transpose() * *A * V;
        int off = 0;
        for (const auto& c : m.classes) {
          const int n = static_cast<int>(c.V.cols());
          B.block(off, off, n, n).setZero();
          off += n;
        }
        BOOST_TEST(B.norm() <= 1e-12 * (A->norm() + 1e-300));
      }
    }
  }
  // Four classes for a spatial beam (axial, two bending planes, torsion), two for a plane one.
  BOOST_TEST(build_model(beam_scene(Physics::Spatial, 0.2), Discretization::parse("2x2")).classes.size() == 4u);
  BOOST_TEST(build_model(beam_scene(Physics::Planar), Discretization::parse("1x2")).classes.size() == 2u);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(meshes)

BOOST_AUTO_TEST_CASE(bad_meshes_are_input_errors) {
  const Scene beam = beam_scene(Physics::Bending);
  const Scene plate = plate_scene(Theory::Kirchhoff);
  for (const char* bad : {"2x2x2", "65x1"}) BOOST_CHECK_THROW(build_model(beam, Discretization::parse(bad)), InputError);
  for (const char* bad : {"1", "3x3", "401"}) BOOST_CHECK_THROW(build_model(plate, Discretization::parse(bad)), InputError);
  try {
    build_model(plate, Discretization::parse("3x3"));
  } catch (const InputError& e) {
    BOOST_TEST(e.key() == "--mesh");
  }
  // Plane physics ignores the width division and says so.
  const PrismModel m = build_model(beam, Discretization::parse("4x2"));
  BOOST_TEST(m.ny == 1);
  BOOST_TEST(!m.notes.empty());
}

BOOST_AUTO_TEST_SUITE_END()
