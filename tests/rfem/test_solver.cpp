// The RfemSolver behind the common interface: identity, meshes, refused input, every built-in
// scene on its default mesh (status, finiteness, diagnostics, speed), the modal FRF option.
#define BOOST_TEST_MODULE rfem_solver
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <ctime>
#include <filesystem>

#include "modalbench/rfem/rfem.hpp"
#include "solve_options.hpp"
#include "rfem_test_helpers.hpp"

using namespace modalbench;
using namespace modalbench::rfem;
using namespace rfem_test;

namespace {
std::vector<Scene> builtin_scenes() {
  std::vector<Scene> v;
  for (const auto& e : std::filesystem::directory_iterator(MODALBENCH_SCENES_DIR))
    if (e.path().extension() == ".toml") v.push_back(load_scene(e.path()));
  return v;
}

/// The unit vertical load at the scene's FRF excitation point and the vertical observer at its
/// observation point, on the model's coordinates.
struct FrfPoints {
  Eigen::Vector3d pe, po;
  Eigen::VectorXd f, g;
};
FrfPoints frf_points(const Scene& sc, const Model& m, const System& sys) {
  Vector6d fz = Vector6d::Zero();
  fz[2] = 1;
  const auto& fr = *sc.request.frf;
  FrfPoints out;
  out.pe = sc.is_beam() ? Eigen::Vector3d(fr.excite[0], 0, 0) : Eigen::Vector3d(fr.excite[0], fr.excite[1], 0);
  out.po = sc.is_beam() ? Eigen::Vector3d(fr.observe[0], 0, 0) : Eigen::Vector3d(fr.observe[0], fr.observe[1], 0);
  out.f = point_load(m, sys, out.pe, fz);
  out.g = point_observer(m, sys, out.po, 2);
  return out;
}
}  // namespace

BOOST_AUTO_TEST_CASE(identity_and_capabilities) {
  const RfemSolver s;
  BOOST_TEST(s.name() == "rfem");
  BOOST_TEST(!s.description().empty());
  for (const Scene& sc : builtin_scenes()) {
    const Capability c = s.supports(sc);
    // Frames: modes and statics (no FRF for frames yet).
    BOOST_TEST((c.modes && c.statics && (c.frf || sc.is_frame())), sc.name);
  }
}

BOOST_AUTO_TEST_CASE(meshes_are_valid_and_refine) {
  const RfemSolver s;
  for (const Scene& sc : builtin_scenes()) {
    BOOST_TEST_MESSAGE(sc.name << ": default " << testing::default_mesh(s, sc).spec());
    BOOST_CHECK_NO_THROW(RfemSolver::build_model(sc, testing::default_mesh(s, sc)));
    long prev = 0;
    for (const auto& m : s.meshes(sc, Options{}).ladder) {
      const long dofs = RfemSolver::build_model(sc, m).body_dofs();
      BOOST_TEST(dofs > prev);
      prev = dofs;
    }
    BOOST_TEST(s.meshes(sc, Options{}).ladder.size() >= 4u);
  }
}

// A plate mesh of multiples of 8 grows by the least half-integer factor at least the one asked
// that keeps its counts multiples of 8 (uniform coarsenings of each other, for the extrapolation).
BOOST_AUTO_TEST_CASE(plate_refinement_steps_along_the_graded_sequence) {
  // A plate without probes, point supports or masses: one step of 56 x 40 x {1, 1.5, 2, 3, 4, ...}
  // at a time, whatever factor is asked (each mesh and the one before it uniform coarsenings, at
  // most 1.5 apart), in up to 6 steps. With probes: the least factor of 1.5, 2, 2.5, ... at least
  // the one asked that keeps the counts multiples of 8, in up to 3 steps.
  const RfemSolver s;
  Scene plate = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml");
  auto finer = [&](const std::string& mesh, double factor) {
    return s.meshes(plate, Options{}).finer_than(Discretization::parse(mesh), factor)->spec();
  };
  BOOST_TEST(finer("112x80", 1.29) == "168x120");  // 1.5 keeps 8 | 168, 120
  BOOST_TEST(finer("56x40", 1.29) == "112x80");    // 84 x 60 is not: 2
  BOOST_TEST(finer("112x80", 2.2) == "280x200");   // 2.5
  BOOST_TEST(finer("56x40", 2.2) == "168x120");    // 2.5 gives 140 x 100: 3
  BOOST_TEST(finer("56x40", 4.0) == "224x160");
  BOOST_TEST(s.meshes(plate, Options{}).refinement_steps == 3);
  plate.request.probes.clear();
  std::string m = "56x40";
  for (const char* next : {"84x60", "112x80", "168x120", "224x160", "336x240", "448x320"}) {
    BOOST_TEST(finer(m, 1.1) == next);
    BOOST_TEST(finer(m, 4.0) == next);
    m = next;
  }
  BOOST_TEST(finer("128x128", 1.2) == "192x192");
  BOOST_TEST(finer("96x96", 1.2) == "128x128");
  BOOST_TEST(!s.meshes(plate, Options{}).finer_than(Discretization::parse("1600x1200"), 1.5).has_value());  // 2400 > 2000
  BOOST_TEST(s.meshes(plate, Options{}).refinement_steps == 6);
  plate.masses.push_back(PointMass{});
  BOOST_TEST(finer("56x40", 1.29) == "112x80");
  const Scene beam = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  BOOST_TEST(s.meshes(beam, Options{}).finer_than(Discretization::parse("64"), 1.5)->spec() == "96");
  BOOST_TEST(s.meshes(beam, Options{}).refinement_steps == 3);
}

BOOST_AUTO_TEST_CASE(bad_meshes_are_input_errors) {
  const RfemSolver s;
  const Scene beam = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  const Scene plate = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml");
  for (const auto& [sc, spec] : std::vector<std::pair<Scene, std::string>>{
           {beam, "64x2"}, {beam, "-"}, {plate, "20"}, {plate, "1x5"}, {plate, "10x6x2"}}) {
    const Result r = s.solve(sc, Discretization::parse(spec), testing::own_error_study());
    BOOST_TEST_MESSAGE(spec << ": " << r.summary.message);
    BOOST_TEST((r.summary.status == Status::InvalidInput));
    BOOST_TEST(r.summary.message.find("--mesh") != std::string::npos);
    BOOST_TEST(r.summary.message.find(sc.source) != std::string::npos);
  }
  // A mesh so coarse that the supports hold everything is refused, not solved with zero DOFs.
  Scene cc = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/lasecka_elastic_beam.toml");
  cc.theory = Theory::EulerBernoulli;
  cc.x0 = Support::named("clamped");
  cc.xL = Support::named("clamped");
  const Result r = s.solve(cc, Discretization{{1}}, testing::own_error_study());
  BOOST_TEST((r.summary.status == Status::InvalidInput));
}

BOOST_AUTO_TEST_CASE(builtin_scenes_solve_on_the_default_mesh) {
  const RfemSolver s;
  for (const Scene& sc : builtin_scenes()) {
    const Result r = s.solve(sc, testing::default_mesh(s, sc), testing::as_without_mesh());
    BOOST_TEST_MESSAGE(sc.name << " [" << testing::default_mesh(s, sc).spec() << "]: " << to_string(r.summary.status) << " in "
                               << r.summary.total_time_s << " s; " << r.summary.method);
    BOOST_TEST(r.ok());
    BOOST_TEST(r.summary.unknowns > 0);
    BOOST_TEST(r.summary.max_backward_error < 1e-8);
    BOOST_TEST(static_cast<int>(r.frequencies_rad_s.size()) == sc.request.modes);
    BOOST_TEST(r.deflections.size() == sc.request.probes.size());
    if (sc.request.frf) BOOST_TEST(static_cast<int>(r.frf.size()) == sc.request.frf->points);
    BOOST_TEST(r.summary.timings_s.build > 0);
    if (sc.request.modes > 0) BOOST_TEST(r.summary.timings_s.modes > 0);
    if (!sc.request.probes.empty()) BOOST_TEST(r.summary.timings_s.statics > 0);
    if (sc.request.frf) BOOST_TEST(r.summary.timings_s.frf > 0);
    for (double w : r.frequencies_rad_s) BOOST_TEST(std::isfinite(w));
  }
}

// A gross-error check (units, supports, loads), not an accuracy test: the default meshes are
// chosen for speed; convergence is tested in test_beam and test_plate.
BOOST_AUTO_TEST_CASE(default_mesh_agrees_with_exact_solver) {
  const RfemSolver rf;
  const exact::ExactSolver ex;
  for (const Scene& sc : builtin_scenes()) {
    const Result a = rf.solve(sc, testing::default_mesh(rf, sc), testing::own_error_study()), b = ex.solve(sc, {}, testing::own_error_study());
    if (!b.ok()) continue;
    const std::size_t k = std::min(a.frequencies_rad_s.size(), b.frequencies_rad_s.size());
    for (std::size_t i = 0; i < k; ++i) BOOST_TEST(rel(a.frequencies_rad_s[i], b.frequencies_rad_s[i]) < 5e-2);
    for (std::size_t i = 0; i < std::min(a.deflections.size(), b.deflections.size()); ++i)
      BOOST_TEST(std::abs(a.deflections[i].w - b.deflections[i].w) < 5e-2 * std::abs(b.deflections[i].w) + 1e-15);
  }
}

BOOST_AUTO_TEST_CASE(modal_frf_option) {
  const Scene sc = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  Options o = testing::own_error_study();
  o.backend = {{"frf_modes", "40"}};
  const RfemSolver s;
  const Result modal = s.solve(sc, Discretization{{64}}, o), direct = s.solve(sc, Discretization{{64}}, testing::own_error_study());
  BOOST_REQUIRE(modal.ok());
  BOOST_TEST(modal.summary.method.find("modal superposition over 40 modes") != std::string::npos);
  BOOST_TEST(static_cast<int>(modal.frequencies_rad_s.size()) == sc.request.modes);  // still the requested 6
  BOOST_REQUIRE(modal.frf.size() == direct.frf.size());
  // Below the first resonance the truncated modal sum is close to the direct solve.
  for (std::size_t i = 0; i < modal.frf.size() && modal.frf[i].omega_rad_s < 5000; ++i)
    BOOST_TEST(std::abs(modal.frf[i].receptance - direct.frf[i].receptance) < 1e-2 * std::abs(direct.frf[i].receptance));
}

// The solver's FRF on a small model comes from the complete spectral decomposition: it must equal
// one sparse solve per frequency (frf_direct) to rounding, away from resonances.
BOOST_AUTO_TEST_CASE(complete_spectrum_frf_equals_per_frequency_solves) {
  for (const char* file : {"/paper_ss_plate.toml", "/paper_fixed_beam.toml"}) {
    Scene sc = load_scene(std::string(MODALBENCH_SCENES_DIR) + file);
    sc.material.loss_factor = 0.01;
    const RfemSolver s;
    // Small enough (<= 80 free coordinates) for the complete decomposition to be chosen.
    const Discretization mesh = sc.is_beam() ? Discretization{{32}} : Discretization{{6, 4}};
    const Result r = s.solve(sc, mesh, testing::own_error_study());
    BOOST_REQUIRE(r.ok());
    BOOST_TEST(r.summary.method.find("complete spectral decomposition") != std::string::npos);
    const Model m = RfemSolver::build_model(sc, mesh);
    const System sys = assemble(m);
    const FrfPoints at = frf_points(sc, m, sys);
    std::vector<double> omegas;
    for (std::size_t i = 0; i < r.frf.size(); i += 37) omegas.push_back(r.frf[i].omega_rad_s);
    const FrfResult d = frf_direct(m, sys, at.f, at.g, omegas);
    BOOST_REQUIRE(d.omega.size() == omegas.size());
    // The solver adds the singular part of the point response (the same at every frequency).
    const double singular = point_correction(m, at.po, 2, at.pe, 2);
    for (std::size_t k = 0; k < omegas.size(); ++k) {
      const std::complex<double> direct = d.receptance[k] + singular;
      BOOST_TEST(std::abs(direct - r.frf[37 * k].receptance) <= 1e-8 * std::abs(direct));
    }
  }
}

// Issue 14 (4): the projected sweep against one sparse solve per frequency. Every sample kept
// from the projection must lie within its own error bound of the direct solve (the bound is a
// proof, not a fit: it must hold everywhere, above the rounding of the two solves), and within
// 0.05 dB; a target no sample can meet
// sends every sample to the direct solve. Plate (corner coordinates), a Euler-Bernoulli beam
// (rigid shear by multipliers: constraint forces in the residual) and a free-free beam (rigid
// modes: the sample at w = 0 is singular), damped and undamped.
BOOST_AUTO_TEST_CASE(projected_frf_is_within_its_bound_of_the_direct_solve) {
  struct Case {
    const char* file;
    Discretization mesh;
    double eta;
    bool free;
  };
  for (const Case& c : {Case{"/paper_ss_plate.toml", Discretization{{40, 24}}, 0.01, false},
                        Case{"/paper_ss_plate.toml", Discretization{{40, 24}}, 0.0, false},
                        Case{"/lasecka_elastic_beam.toml", Discretization{{400}}, 0.02, false},
                        Case{"/lasecka_elastic_beam.toml", Discretization{{400}}, 0.02, true}}) {
    BOOST_TEST_CONTEXT(c.file << " eta " << c.eta << (c.free ? " free-free" : "")) {
      Scene sc = load_scene(std::string(MODALBENCH_SCENES_DIR) + c.file);
      sc.material.loss_factor = c.eta;
      if (c.free) sc.x0 = sc.xL = Support::named("free");
      if (!sc.request.frf) {
        FrfRequest fr;
        fr.excite = {0.3 * sc.geometry.length, 0.0};
        fr.observe = {0.8 * sc.geometry.length, 0.0};
        fr.omega_min = 0.0;
        fr.omega_max = 3000.0;
        fr.points = 200;
        sc.request.frf = fr;
      }
      const Model m = RfemSolver::build_model(sc, c.mesh);
      const System sys = assemble(m);
      const auto& fr = *sc.request.frf;
      const FrfPoints at = frf_points(sc, m, sys);
      const Eigen::VectorXd& f = at.f;
      const Eigen::VectorXd& g = at.g;
      std::vector<double> omegas;
      for (int i = 0; i < fr.points; ++i) omegas.push_back(fr.omega_min + (fr.omega_max - fr.omega_min) * i / (fr.points - 1));
      ProjectedFrfOptions po_opt;
      po_opt.target = 1e-3;
      FrfResult p;
      BOOST_REQUIRE(frf_projected(m, sys, f, g, omegas, po_opt, p));
      const FrfResult d = frf_direct(m, sys, f, g, p.omega);
      BOOST_REQUIRE(d.omega.size() == p.omega.size());
      BOOST_REQUIRE(p.error_bounds.size() == p.omega.size());
      BOOST_TEST(p.omega.size() + p.skipped == omegas.size());
      if (c.free) BOOST_TEST(p.skipped == 1);  // w = 0 on the free body
      long from_projection = 0;
      for (std::size_t k = 0; k < p.omega.size(); ++k) {
        const double err = std::abs(p.receptance[k] - d.receptance[k]) / std::abs(d.receptance[k]);
        BOOST_TEST(std::abs(20 * std::log10(std::abs(p.receptance[k]) / std::abs(d.receptance[k]))) < 0.05);
        if (std::isnan(p.error_bounds[k])) continue;
        ++from_projection;
        // Above the rounding of the two solves (1e-8 relative: both are floating-point solves of a
        // system whose condition near a resonance is 1 / eta), the bound must hold.
        BOOST_TEST(err <= p.error_bounds[k] + 1e-8, "w = " << p.omega[k] << ": error " << err << " above its bound "
                                                            << p.error_bounds[k]);
        BOOST_TEST(p.error_bounds[k] <= po_opt.target);
      }
      BOOST_TEST(from_projection > 0.9 * static_cast<double>(p.omega.size()));
      // A target no projection meets: every sample is solved directly.
      po_opt.target = 1e-300;
      FrfResult all_direct;
      BOOST_REQUIRE(frf_projected(m, sys, f, g, omegas, po_opt, all_direct));
      BOOST_TEST(all_direct.direct_samples == static_cast<long>(all_direct.omega.size()));
    }
  }
}

BOOST_AUTO_TEST_CASE(free_plate_statics_is_a_mechanism) {
  Scene sc = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_ss_plate.toml");
  sc.x0 = sc.xL = sc.y0 = sc.yB = Support::named("free");
  sc.request.frf.reset();
  const Result r = RfemSolver().solve(sc, Discretization{{10, 6}}, testing::own_error_study());
  BOOST_TEST((r.summary.status == Status::InvalidInput));
  BOOST_TEST(r.summary.message.find("mechanism") != std::string::npos);
  BOOST_TEST(r.frequencies_rad_s.size() == 8u);  // the modes are still computed ...
  BOOST_TEST(r.frequencies_rad_s[0] == 0.0);     // ... the rigid ones as exact zeros
  BOOST_TEST((r.mode_families[0] == ModeFamily::Rigid));
}

// A beam on near-mechanism springs (K = kL^3/EI = Kr = 1e-6 at both ends, 128 segments): the
// Lanczos pairs of its near-rigid heave and rocking modes missed the backward-error check (1.1e-9)
// and the auto path took the dense one (refined). They are now taken by Rayleigh-Ritz in the
// rigid-motion subspace (said in the method), or the Lanczos pairs are refined by subspace steps
// on the shift-invert operator (said in the method), or, failing both, by the dense fall-back
// (said in `fallbacks`); each passes the check. The frequencies agree with the exact beam to
// discretization error.
BOOST_AUTO_TEST_CASE(near_mechanism_falls_back_to_the_refined_dense_path) {
  Scene s = parse_scene(R"(
[scene]
name = "near-mechanism"
kind = "beam"
physics = "bending"
theory = "euler-bernoulli"
[geometry]
length = 1.0
width = 0.01
height = 0.01
[material]
E = 2.0e11
nu = 0.3
rho = 7850.0
[supports]
x0 = { translational = 1.6666666666666667e-4, rotational = 1.6666666666666667e-4 }
xL = { translational = 1.6666666666666667e-4, rotational = 1.6666666666666667e-4 }
[request]
modes = 6
)",
                        "near-mechanism");
  const Result r = RfemSolver().solve(s, Discretization::parse("128"), testing::own_error_study());
  BOOST_TEST_REQUIRE(r.ok(), r.summary.message);
  BOOST_TEST(r.summary.max_backward_error <= 1e-10);
  const bool ritz = r.summary.method.find("near-rigid mode(s) on the soft support springs") != std::string::npos;
  const bool refined = r.summary.method.find("Lanczos") != std::string::npos &&
                       r.summary.method.find("refined by") != std::string::npos;
  BOOST_TEST((ritz || refined ||
              (r.summary.fallbacks.size() == 1u && r.summary.fallbacks[0].find("Lanczos") != std::string::npos)),
             r.summary.method);
  const Result ex = exact::ExactSolver().solve(s, {}, testing::own_error_study());
  BOOST_TEST_REQUIRE(ex.ok(), ex.summary.message);
  for (std::size_t i = 0; i < 6; ++i)
    BOOST_TEST(std::abs(r.frequencies_rad_s[i] / ex.frequencies_rad_s[i] - 1) < 2e-3, "mode " << i + 1);
}

// More modes than the mesh has (issue 54: a time history's doubling of modes ran past the default
// mesh's unknowns, and shift-invert Lanczos refused with numerical-issue): every mode of the model,
// by the dense solver, said in a warning. The lowest agree with the same mesh's Lanczos solve, and
// every one satisfies its own eigen-equation (the backward error).
BOOST_AUTO_TEST_CASE(more_modes_than_the_mesh_has_are_all_of_them) {
  Scene s = beam_scene(Physics::Bending, Theory::EulerBernoulli, springs(inf, 0), springs(inf, 0));
  s.request.modes = 400;  // 96 segments: 95 bending modes
  const Result all = RfemSolver().solve(s, Discretization::parse("96"), testing::own_error_study());
  BOOST_TEST_REQUIRE(to_string(all.summary.status) == "success", all.summary.message);
  BOOST_TEST(all.frequencies_rad_s.size() < 400u);
  BOOST_TEST(all.frequencies_rad_s.size() >= 90u);
  BOOST_TEST(all.summary.method.find("dense") != std::string::npos, all.summary.method);
  bool said = false;
  for (const auto& w : all.summary.warnings) said = said || w.find("flexible modes exist in this model") != std::string::npos;
  BOOST_TEST(said);
  BOOST_TEST(all.summary.max_backward_error <= 1e-10);
  s.request.modes = 6;
  Options lanczos = testing::own_error_study();
  lanczos.backend = {{"eigen", "shift-invert"}};
  const Result six = RfemSolver().solve(s, Discretization::parse("96"), lanczos);
  BOOST_TEST_REQUIRE(six.ok(), six.summary.message);
  for (std::size_t i = 0; i < 6; ++i)
    BOOST_TEST(std::abs(all.frequencies_rad_s[i] / six.frequencies_rad_s[i] - 1) <= 1e-9, "mode " << i + 1);
}
