// The assembled rfem system: symmetry, definiteness and the right null space, exact
// elimination of held DOFs, the Euler-Bernoulli basis, rigid-link constraints and their
// dependencies, the Sturm count, and the reciprocity of point loads and probes.
#define BOOST_TEST_MODULE rfem_model
#include <boost/test/unit_test.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <initializer_list>
#include <limits>

#include "modalbench/rfem/factor.hpp"
#include "rfem_test_helpers.hpp"

using namespace modalbench;
using namespace modalbench::rfem;
using namespace rfem_test;

namespace {

Eigen::MatrixXd dense(const SpMat& A) { return Eigen::MatrixXd(A); }

/// Largest of the given components (global axes) of the relative motion of the two RFEs an SDE
/// joins, at the SDE's point, over every SDE between RFEs, under body motion q.
double largest_link_motion(const Model& m, const Eigen::VectorXd& q, std::initializer_list<int> comps) {
  const int na = m.dofs_per_element();
  auto body = [&](int e) {
    Vector6d v = Vector6d::Zero();
    for (int k = 0; k < na; ++k) v[m.active[static_cast<std::size_t>(k)]] = q[static_cast<long>(e) * na + k];
    return v;
  };
  double worst = 0;
  for (const Sde& sd : m.sdes) {
    if (sd.b == kGround) continue;
    const Vector6d rel = attached_motion(sd.point - m.elements[static_cast<std::size_t>(sd.b)].centre, body(sd.b)) -
                         attached_motion(sd.point - m.elements[static_cast<std::size_t>(sd.a)].centre, body(sd.a));
    for (int c : comps) worst = std::max(worst, std::abs(rel[c]));
  }
  return worst;
}

/// Orthonormal basis of the null space of the constraint rows (identity without constraints).
Eigen::MatrixXd constraint_basis(const System& sys) {
  if (sys.m() == 0) return Eigen::MatrixXd::Identity(sys.n(), sys.n());
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(dense(sys.G).transpose());
  const Eigen::MatrixXd Q = qr.householderQ();
  return Q.rightCols(sys.n() - qr.rank());
}

/// Generalized eigenvalues of the constrained pencil (ascending), by a dense solver.
Eigen::VectorXd dense_eigenvalues(const System& sys) {
  const Eigen::MatrixXd N = constraint_basis(sys);
  const Eigen::MatrixXd K = N.transpose() * dense(sys.K) * N, M = N.transpose() * dense(sys.M) * N;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M, Eigen::EigenvaluesOnly);
  return es.eigenvalues();
}

int count_zero(const Eigen::VectorXd& lambda) {
  const double scale = lambda.cwiseAbs().maxCoeff();
  int c = 0;
  for (long i = 0; i < lambda.size(); ++i) c += std::abs(lambda[i]) < 1e-9 * scale;
  return c;
}

void check_symmetric_psd(const System& sys) {
  const Eigen::MatrixXd K = dense(sys.K), M = dense(sys.M);
  BOOST_TEST((K - K.transpose()).norm() <= 1e-13 * K.norm());
  BOOST_TEST((M - M.transpose()).norm() <= 1e-13 * M.norm());
  Eigen::LLT<Eigen::MatrixXd> llt(M);
  BOOST_TEST((llt.info() == Eigen::Success));  // M positive definite
  const Eigen::VectorXd lam = dense_eigenvalues(sys);
  BOOST_TEST(lam.minCoeff() >= -1e-10 * lam.maxCoeff());  // K positive semi-definite on G z = 0
}

}  // namespace

BOOST_AUTO_TEST_SUITE(assembled_system)

BOOST_AUTO_TEST_CASE(free_beams_have_exactly_the_rigid_null_space) {
  const Support free = Support::named("free");
  struct Case {
    Physics physics;
    Theory theory;
    int rigid;  // translations and rotations the active DOFs can show
  };
  for (const Case c : {Case{Physics::Bending, Theory::Timoshenko, 2}, Case{Physics::Planar, Theory::Timoshenko, 3},
                       Case{Physics::Spatial, Theory::Timoshenko, 6}, Case{Physics::Spatial, Theory::EulerBernoulli, 6}}) {
    const Model m = build_beam(beam_scene(c.physics, c.theory, free, free), 12);
    const System sys = assemble(m);
    check_symmetric_psd(sys);
    BOOST_TEST(count_zero(dense_eigenvalues(sys)) == c.rigid);
    const RigidModes rm = free_rigid_modes(m, sys);
    BOOST_TEST(rm.Z.cols() == c.rigid);
    const Eigen::MatrixXd KZ = sys.K * rm.Z;
    BOOST_TEST(KZ.norm() <= 1e-10 * dense(sys.K).norm() * rm.Z.norm());
    const Eigen::MatrixXd ZMZ = rm.Z.transpose() * (sys.M * rm.Z);
    BOOST_TEST((ZMZ - Eigen::MatrixXd::Identity(c.rigid, c.rigid)).norm() < 1e-10);
  }
}

BOOST_AUTO_TEST_CASE(free_plates_and_boxes_have_the_rigid_null_space) {
  const Support free = Support::named("free");
  for (Theory t : {Theory::Kirchhoff, Theory::Mindlin}) {
    PlateOptions o;
    o.nx = 6;
    o.ny = 4;
    const Model m = build_plate(plate_scene(t, free, free, free, free), o);
    const System sys = assemble(m);
    check_symmetric_psd(sys);
    BOOST_TEST(count_zero(dense_eigenvalues(sys)) == 3);  // w, rotations about x and y
    BOOST_TEST(free_rigid_modes(m, sys).Z.cols() == 3);
  }
  BoxSpec b;
  b.nx = 3;
  b.ny = 2;
  b.nz = 2;
  b.material = beam_scene(Physics::Bending, Theory::Timoshenko, Support::named("free"), Support::named("free")).material;
  const Model box = build_box(b);
  const System sys = assemble(box);
  check_symmetric_psd(sys);
  BOOST_TEST(count_zero(dense_eigenvalues(sys)) == 6);
  BOOST_TEST(free_rigid_modes(box, sys).Z.cols() == 6);
}

BOOST_AUTO_TEST_CASE(supports_remove_the_null_space) {
  const Model m = build_beam(
      beam_scene(Physics::Spatial, Theory::Timoshenko, Support::named("clamped"), Support::named("free")), 10);
  const System sys = assemble(m);
  Eigen::LLT<Eigen::MatrixXd> llt(dense(sys.K));
  BOOST_TEST((llt.info() == Eigen::Success));
  BOOST_TEST(free_rigid_modes(m, sys).Z.cols() == 0);
  // A single soft spring at one end leaves the rotation about that end free: one rigid mode.
  const Model m2 = build_beam(beam_scene(Physics::Bending, Theory::Timoshenko, springs(1e-3, 0), Support::named("free")), 10);
  const RigidModes rm = free_rigid_modes(m2, assemble(m2));
  BOOST_TEST(rm.Z.cols() == 1);
}

BOOST_AUTO_TEST_CASE(held_dofs_are_eliminated_not_penalised) {
  const int n = 10;
  const Scene s = beam_scene(Physics::Planar, Theory::Timoshenko, Support::named("pinned"), Support::named("clamped"));
  const Model m = build_beam(s, n);
  const System sys = assemble(m);
  // Pinned: u and w held; clamped: u, w, theta_y held. 3 (n + 1) - 5 coordinates remain.
  BOOST_TEST(sys.n() == 3 * (n + 1) - 5);
  BOOST_TEST(sys.held == 5);
  double kmax = 0;
  for (const Sde& sd : m.sdes)
    for (int c = 0; c < 6; ++c)
      if (std::isfinite(sd.stiffness[c])) kmax = std::max(kmax, sd.stiffness[c]);
  // Nothing stiffer than the stiffest spring times a kinematic factor of order one: no penalty.
  BOOST_TEST(dense(sys.K).cwiseAbs().maxCoeff() <= 10 * kmax);
  // The pinned end keeps only its rotation.
  std::vector<std::string> names;
  for (long i = 0; i < sys.n(); ++i) names.push_back(coordinate_name(m, sys, i));
  BOOST_TEST(std::count(names.begin(), names.end(), std::string("theta_y[rfe 0]")) == 1);
  BOOST_TEST(std::count(names.begin(), names.end(), std::string("w[rfe 0]")) == 0);
}

// Euler-Bernoulli by joint coordinates: any z gives zero shear at every joint. (By multipliers
// the same components are the constraint rows; test_beam checks that both agree.)
BOOST_AUTO_TEST_CASE(euler_bernoulli_joint_coordinates_make_shear_rigid_exactly) {
  const Scene s = beam_scene(Physics::Spatial, Theory::EulerBernoulli, Support::named("pinned"), springs(1e5, 1e4, 1e6, 1e3));
  BeamOptions o;
  o.rigid_shear = RigidShear::JointCoordinates;
  const Model m = build_beam(s, 9, o);
  const System sys = assemble(m);
  const Eigen::VectorXd q = sys.T * Eigen::VectorXd::Random(sys.n());
  BOOST_TEST(largest_link_motion(m, q, {1, 2}) <= 1e-14 * q.cwiseAbs().maxCoeff());  // transverse (shear)
  // By multipliers: one constraint per joint and bending plane.
  const System sm = assemble(build_beam(s, 9));
  BOOST_TEST(sm.m() == 2 * 9);
}

// Kirchhoff by corner coordinates: any z gives zero transverse shear at every side midpoint; the
// map z -> q has full column rank (the one null combination is gauged out) and spans exactly the
// space the multiplier form allows, for every kind of edge (held coordinates included).
BOOST_AUTO_TEST_CASE(kirchhoff_corner_coordinates_make_shear_rigid_exactly) {
  const Support c = Support::named("clamped"), p = Support::named("pinned"), f = Support::named("free"),
                g = Support::named("guided"), e = springs(1e9, 3e5);
  for (const auto& sup : {std::array<Support, 4>{f, f, f, f}, std::array<Support, 4>{p, p, p, p},
                          std::array<Support, 4>{c, c, c, c}, std::array<Support, 4>{p, c, g, f},
                          std::array<Support, 4>{e, c, f, g}}) {
    const Scene s = plate_scene(Theory::Kirchhoff, sup[0], sup[1], sup[2], sup[3]);
    for (auto [nx, ny] : {std::pair{6, 4}, {1, 1}, {2, 5}}) {
      PlateOptions o;
      o.nx = nx;
      o.ny = ny;
      const Model m = build_plate(s, o);
      const System sys = assemble(m);
      BOOST_TEST(sys.m() == 0);
      const Eigen::MatrixXd T = dense(sys.T);
      if (T.cols() > 0) BOOST_TEST(Eigen::FullPivLU<Eigen::MatrixXd>(T).rank() == T.cols());  // 1x1 clamped: all held
      const Eigen::VectorXd q = T * Eigen::VectorXd::Random(T.cols());
      BOOST_TEST(largest_link_motion(m, q, {2}) <= 1e-13 * q.cwiseAbs().maxCoeff());  // w at the side midpoints
      // The multiplier form: n - m independent motions, the same as the corner coordinates.
      PlateOptions om = o;
      om.rigid_shear = RigidShear::Multipliers;
      const System sm = assemble(build_plate(s, om));
      BOOST_TEST(sm.n() - sm.m() == sys.n());
    }
  }
}

BOOST_AUTO_TEST_CASE(kirchhoff_constraints_drop_exactly_the_dependent_rows) {
  PlateOptions o;
  o.nx = 6;
  o.ny = 4;
  o.rigid_shear = RigidShear::Multipliers;
  const Support c = Support::named("clamped"), p = Support::named("pinned"), f = Support::named("free");
  {
    // Free plate: every rigid-shear link is independent.
    const System sys = assemble(build_plate(plate_scene(Theory::Kirchhoff, f, f, f, f), o));
    BOOST_TEST(sys.redundant == 0);
    BOOST_TEST(sys.m() == o.nx * (o.ny + 1) + o.ny * (o.nx + 1));
  }
  for (const auto& sup : {std::array<Support, 4>{c, c, c, c}, std::array<Support, 4>{p, p, c, f}}) {
    const System sys = assemble(build_plate(plate_scene(Theory::Kirchhoff, sup[0], sup[1], sup[2], sup[3]), o));
    BOOST_TEST(sys.redundant > 0);
    const Eigen::MatrixXd G = dense(sys.G);
    Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
    BOOST_TEST(lu.rank() == sys.m());  // what is left has full row rank
    for (long r = 0; r < sys.m(); ++r) BOOST_TEST(std::abs(G.row(r).norm() - 1.0) < 1e-12);
    // Dropping only dependent rows leaves the constraint space unchanged: compare with the rank
    // of all rigid links mapped to z (the rows the model states, before any is dropped).
    BOOST_TEST(sys.m() + sys.redundant == o.nx * (o.ny + 1) + o.ny * (o.nx + 1));
  }
}

BOOST_AUTO_TEST_CASE(sturm_count_equals_the_dense_count) {
  PlateOptions o;
  o.nx = 6;
  o.ny = 4;
  const Support p = Support::named("pinned"), c = Support::named("clamped");
  for (auto [t, shear] : {std::pair{Theory::Kirchhoff, RigidShear::Multipliers}, {Theory::Kirchhoff, RigidShear::JointCoordinates},
                          {Theory::Mindlin, RigidShear::Multipliers}}) {
    o.rigid_shear = shear;
    const System sys = assemble(build_plate(plate_scene(t, p, p, c, p), o));
    const Eigen::VectorXd lam = dense_eigenvalues(sys);
    KktLdlt ldlt;
    ldlt.analyze(SpMat(sys.K + sys.M), sys.G);
    for (int k : {1, 5, 9}) {
      const double mu = 0.5 * (lam[k - 1] + lam[k]);
      BOOST_REQUIRE(ldlt.factorize(SpMat(sys.K - mu * sys.M)));
      BOOST_TEST(ldlt.negative_count() == k);
    }
  }
}

BOOST_AUTO_TEST_CASE(supernodal_ldlt_counts_and_solves_on_a_plate_grid) {
  // A plate of 20 x 14 fragments is large enough for CHOLMOD's analysis to choose supernodes, so
  // KktLdlt takes its supernodal LDL': the Sturm count must equal the dense count of the
  // constrained pencil, with and without multipliers, and a solve at a shift below the spectrum
  // (A positive definite on G z = 0: a backward-stable factorization) must leave a residual at
  // the rounding of A.
  PlateOptions o;
  o.nx = 20;
  o.ny = 14;
  const Support p = Support::named("pinned"), c = Support::named("clamped");
  for (auto [t, shear] : {std::pair{Theory::Mindlin, RigidShear::Multipliers}, {Theory::Kirchhoff, RigidShear::Multipliers}}) {
    o.rigid_shear = shear;
    const System sys = assemble(build_plate(plate_scene(t, p, p, c, p), o));
    const Eigen::VectorXd lam = dense_eigenvalues(sys);
    KktLdlt ldlt;
    ldlt.analyze(SpMat(sys.K + sys.M), sys.G);
    BOOST_TEST_REQUIRE(ldlt.supernodal());
    for (int k : {1, 5, 9, 40}) {
      const double mu = 0.5 * (lam[k - 1] + lam[k]);
      BOOST_REQUIRE(ldlt.factorize(SpMat(sys.K - mu * sys.M)));
      BOOST_TEST(ldlt.negative_count() == k);
    }
    const SpMat A = sys.K + lam[0] * sys.M;  // sigma = -lambda_1
    BOOST_REQUIRE(ldlt.factorize(A));
    BOOST_TEST(ldlt.negative_count() == 0);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(sys.n(), -1.0, 2.0).array().sin().matrix();
    const Eigen::VectorXd x = ldlt.solve(b);
    // On G x = 0, A x - b is a combination of the constraint rows (the multipliers' forces).
    const Eigen::MatrixXd N = constraint_basis(sys);
    const Eigen::VectorXd r = N.transpose() * (A * x - b);
    const double scale = dense(A).cwiseAbs().colwise().sum().maxCoeff() * x.norm() + b.norm();
    BOOST_TEST(r.norm() <= 1e3 * std::numeric_limits<double>::epsilon() * scale);
    if (sys.m() > 0) BOOST_TEST((sys.G * x).norm() <= 1e3 * std::numeric_limits<double>::epsilon() * x.norm());
  }
}

BOOST_AUTO_TEST_CASE(two_thread_supernodal_solves_leave_a_rounding_residual) {
  // A plate large enough for the solve to split into two subtrees on two threads: at a shift
  // below the spectrum (positive definite) the residual is at the rounding of A, and equal, to
  // rounding, as is that of the same matrix's simplicial LDL' (Eigen, AMD: an independent factor).
  PlateOptions o;
  o.nx = 100;
  o.ny = 70;
  const Support p = Support::named("pinned"), c = Support::named("clamped");
  const System sys = assemble(build_plate(plate_scene(Theory::Mindlin, p, p, c, p), o));
  KktLdlt ldlt;
  ldlt.analyze(SpMat(sys.K + sys.M), sys.G);
  BOOST_TEST_REQUIRE(ldlt.two_thread_solves());
  const SpMat A = sys.K + 1e3 * sys.M;
  BOOST_REQUIRE(ldlt.factorize(A));
  BOOST_TEST(ldlt.negative_count() == 0);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(sys.n(), -1.0, 2.0).array().sin().matrix();
  const Eigen::VectorXd x = ldlt.solve(b);
  double norm_a = 0;
  for (int j = 0; j < A.outerSize(); ++j) norm_a = std::max(norm_a, SpMat(A.col(j)).cwiseAbs().sum());
  const double eps = std::numeric_limits<double>::epsilon();
  BOOST_TEST((A * x - b).norm() <= 1e3 * eps * (norm_a * x.norm() + b.norm()));
  Eigen::SimplicialLDLT<SpMat> reference(A);
  BOOST_REQUIRE((reference.info() == Eigen::Success));
  const Eigen::VectorXd xr = reference.solve(b);
  BOOST_TEST((A * xr - b).norm() <= 1e3 * eps * (norm_a * xr.norm() + b.norm()));
}

BOOST_AUTO_TEST_CASE(point_loads_and_probes_are_reciprocal) {
  // Maxwell-Betti: w at B due to a unit force at A equals w at A due to a unit force at B, for
  // points inside cells and on cell boundaries.
  const Scene s = beam_scene(Physics::Bending, Theory::Timoshenko, springs(1e7, 0), Support::named("clamped"));
  const Model m = build_beam(s, 8);
  const System sys = assemble(m);
  const Eigen::Vector3d A(0.3, 0, 0), B(0.5625, 0, 0), C(0.0625, 0, 0);  // C: a cell boundary
  Vector6d fz = Vector6d::Zero();
  fz[2] = 1;
  auto response = [&](const Eigen::Vector3d& at, const Eigen::Vector3d& obs) {
    const StaticSolution st = solve_static(m, sys, point_load(m, sys, at, fz));
    BOOST_REQUIRE(st.ok);
    return point_observer(m, sys, obs, 2).dot(st.z);
  };
  BOOST_TEST(std::abs(response(A, B) - response(B, A)) <= 1e-12 * std::abs(response(A, B)));
  BOOST_TEST(std::abs(response(A, C) - response(C, A)) <= 1e-12 * std::abs(response(A, C)));
  BOOST_TEST(containing_elements(m, C).size() == 2u);
}

BOOST_AUTO_TEST_SUITE_END()
