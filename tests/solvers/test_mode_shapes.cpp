// Mode shapes from every back-end (result.hpp, ModeShapes): the defining equations (boundary
// conditions, closed forms, orthonormality in each model's own mass), agreement by MAC, modal
// quantities against closed forms, pairing of coincident modes, and the ParaView export.
#define BOOST_TEST_MODULE mode_shapes
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>

#include "modalbench/harness/comparison.hpp"
#include "solve_options.hpp"
#include "modalbench/harness/vtk.hpp"
#include "modalbench/registry.hpp"
#include "modalbench/rfem/builders.hpp"
#include "temp_dir.hpp"

using namespace modalbench;

namespace {

constexpr double pi = std::numbers::pi;

Scene scene(const std::string& file) { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + file); }

Scene with_shapes(Scene s, int nx, int ny = 1) {
  s.request.shapes = ShapeRequest{nx, ny};
  return s;
}

Scene beam(Theory theory, const char* x0, const char* xL, int modes, int nx) {
  Scene s = scene("paper_fixed_beam.toml");
  s.name = "test-beam";
  s.theory = theory;
  s.geometry = {1.0, 0.1, 0.1};
  s.material.E = 2.1e11;
  s.material.G = 8.1e10;
  s.material.nu = s.material.E / (2 * s.material.G) - 1;
  s.material.rho = 7850;
  s.x0 = Support::named(x0);
  s.xL = Support::named(xL);
  s.loads.clear();
  s.request.probes.clear();
  s.request.frf.reset();
  s.request.modes = modes;
  s.request.shapes = ShapeRequest{nx, 1};
  validate(s);
  return s;
}

const std::vector<double>& comp(const ModeShapes& s, std::size_t mode, int dof) {
  for (std::size_t c = 0; c < s.components.size(); ++c)
    if (s.components[c] == dof) return s.values[mode][c];
  throw std::logic_error("no such component");
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

// The exact simply supported Euler-Bernoulli beam: w_k = sqrt(2 / (rho A L)) sin(k pi x / L).
BOOST_AUTO_TEST_CASE(exact_shapes_are_the_closed_form) {
  const Scene s = beam(Theory::EulerBernoulli, "pinned", "pinned", 5, 21);
  const Result r = make_default_registry().get("exact").solve(s, {}, testing::own_error_study());
  BOOST_REQUIRE(r.ok());
  const auto& ms = r.mode_shapes;
  BOOST_REQUIRE(ms.values.size() == 5u);
  const double m = s.material.rho * s.section().A * s.geometry.length;
  for (std::size_t k = 0; k < 5; ++k) {
    const auto& w = comp(ms, k, 2);
    const auto& th = comp(ms, k, 4);
    for (std::size_t p = 0; p < ms.points.size(); ++p) {
      const double x = ms.points[p][0], kk = static_cast<double>(k + 1) * pi;
      const double closed = std::sqrt(2.0 / m) * std::sin(kk * x), slope = std::sqrt(2.0 / m) * kk * std::cos(kk * x);
      BOOST_TEST(std::abs(std::abs(w[p]) - std::abs(closed)) < 1e-9 * std::sqrt(2.0 / m), "mode " << k + 1 << " x " << x);
      BOOST_TEST(std::abs(std::abs(th[p]) - std::abs(slope)) < 1e-8 * std::sqrt(2.0 / m) * kk);
    }
    BOOST_TEST(ms.generalized_mass[k] == 1.0);
  }
}

// Boundary conditions of the sampled exact shapes: clamped w = theta = 0, pinned w = 0.
BOOST_AUTO_TEST_CASE(exact_shapes_satisfy_the_boundary_conditions) {
  for (Theory t : {Theory::Timoshenko, Theory::EulerBernoulli}) {
    const Scene s = beam(t, "clamped", "pinned", 6, 31);
    const Result r = make_default_registry().get("exact").solve(s, {}, testing::own_error_study());
    BOOST_REQUIRE(r.ok());
    for (std::size_t k = 0; k < 6; ++k) {
      const auto& w = comp(r.mode_shapes, k, 2);
      const auto& th = comp(r.mode_shapes, k, 4);
      BOOST_TEST(std::abs(w.front()) < 1e-12 * max_abs(w));
      BOOST_TEST(std::abs(th.front()) < 1e-12 * max_abs(th));
      BOOST_TEST(std::abs(w.back()) < 1e-12 * max_abs(w));
    }
  }
}

// rfem and difference_eq shapes sampled at their own nodes are orthonormal in their own mass
// matrices (rfem: the RFE masses; difference_eq: the assembled Hermite consistent mass).
BOOST_AUTO_TEST_CASE(discrete_shapes_are_orthonormal_in_their_own_mass) {
  const int n = 40;
  const Scene s = beam(Theory::EulerBernoulli, "clamped", "free", 8, n + 1);
  const Registry reg = make_default_registry();
  {
    const Result r = reg.get("rfem").solve(s, Discretization{{n}}, testing::own_error_study());
    BOOST_REQUIRE(r.ok());
    const rfem::Model m = rfem::build_beam(s, n);
    for (std::size_t i = 0; i < 8; ++i)
      for (std::size_t j = 0; j < 8; ++j) {
        const auto &wi = comp(r.mode_shapes, i, 2), &wj = comp(r.mode_shapes, j, 2);
        const auto &ti = comp(r.mode_shapes, i, 4), &tj = comp(r.mode_shapes, j, 4);
        double g = 0;
        for (std::size_t e = 0; e <= static_cast<std::size_t>(n); ++e)
          g += m.elements[e].mass * wi[e] * wj[e] + m.elements[e].inertia[1] * ti[e] * tj[e];
        BOOST_TEST(std::abs(g - (i == j ? 1.0 : 0.0)) < 1e-10, "rfem modes " << i << ", " << j);
      }
  }
  {
    const Result r = reg.get("difference_eq").solve(s, Discretization{{n}}, testing::own_error_study());
    BOOST_REQUIRE(r.ok());
    const double a = s.geometry.length / n, rhoA = s.material.rho * s.section().A;
    const double M[4][4] = {{156, 22, 54, -13}, {22, 4, 13, -3}, {54, 13, 156, -22}, {-13, -3, -22, 4}};
    for (std::size_t i = 0; i < 8; ++i)
      for (std::size_t j = 0; j < 8; ++j) {
        const auto &wi = comp(r.mode_shapes, i, 2), &wj = comp(r.mode_shapes, j, 2);
        const auto &ti = comp(r.mode_shapes, i, 4), &tj = comp(r.mode_shapes, j, 4);
        double g = 0;
        for (int e = 0; e < n; ++e) {
          // (w, a slope) with slope = -theta_y.
          const double ui[4] = {wi[e], -a * ti[e], wi[e + 1], -a * ti[e + 1]};
          const double uj[4] = {wj[e], -a * tj[e], wj[e + 1], -a * tj[e + 1]};
          for (int p = 0; p < 4; ++p)
            for (int q = 0; q < 4; ++q) g += rhoA * a / 420.0 * ui[p] * M[p][q] * uj[q];
        }
        BOOST_TEST(std::abs(g - (i == j ? 1.0 : 0.0)) < 1e-10, "difference_eq modes " << i << ", " << j);
      }
  }
}

// MAC against the exact shapes on the first 6 modes, each back-end at its default mesh: the
// paper's fixed beam, the simply supported plate, the beam on elastic supports. One exception,
// a model difference rather than an error: dtfm's default 2x2 prisms are not the Timoshenko
// beam, and the deep beam's 6th mode differs between the two models (Table 1: 47173 rad/s for
// one prism, 41322 for four; 3D 43225, P8): MAC 0.757 there. Its first 5 are held to
// 0.999, and the one-prism dtfm (the Timoshenko beam itself) to 0.999 on all 6.
BOOST_AUTO_TEST_CASE(mac_against_exact_at_default_meshes) {
  const Registry reg = make_default_registry();
  struct Run {
    std::string backend;
    std::string mesh;  ///< "" = the back-end's default
    std::size_t modes;
  };
  struct Case {
    const char* file;
    std::vector<Run> runs;
  };
  const Case cases[] = {
      {"paper_fixed_beam.toml", {{"rfem", "", 6}, {"dtfm", "", 5}, {"dtfm", "1x1", 6}}},
      {"paper_ss_plate.toml", {{"rfem", "", 6}, {"dtfm", "", 6}}},
      {"lasecka_elastic_beam.toml", {{"rfem", "", 6}, {"difference_eq", "", 6}, {"dtfm", "", 6}}}};
  for (const Case& c : cases) {
    Scene s = scene(c.file);
    s.request.modes = std::max(s.request.modes, 6);
    s = with_shapes(s, s.is_beam() ? ShapeRequest::kBeamDefaultNx : ShapeRequest::kPlateDefaultNx,
                    s.is_beam() ? 1 : ShapeRequest::kPlateDefaultNy);
    const Result ex = reg.get("exact").solve(s, {}, testing::own_error_study());
    BOOST_REQUIRE(ex.ok());
    for (const auto& run : c.runs) {
      const Solver& sv = reg.get(run.backend);
      const Discretization mesh = run.mesh.empty() ? testing::default_mesh(sv, s) : Discretization::parse(run.mesh);
      const Result r = sv.solve(s, mesh, testing::own_error_study());
      BOOST_TEST_CONTEXT(c.file << " " << run.backend << " " << mesh.spec()) {
        BOOST_REQUIRE(r.ok());
        BOOST_REQUIRE(!r.mode_shapes.empty());
        // Paired as the harness pairs them (by MAC within families).
        const auto m = mac_matrix(ex.mode_shapes, r.mode_shapes, 0.0);
        const auto pair = match_modes_by_mac(ex.mode_families, r.mode_families, m);
        for (std::size_t k = 0; k < run.modes; ++k) {
          BOOST_REQUIRE(pair[k] >= 0);
          const double v = m[k][static_cast<std::size_t>(pair[k])];
          BOOST_TEST_MESSAGE(c.file << " " << run.backend << " " << mesh.spec() << " mode " << k + 1 << ": MAC " << v);
          BOOST_TEST(v >= 0.999, "mode " << k + 1 << ": MAC " << v);
        }
      }
    }
  }
}

// Effective masses of a cantilever: mode 1 carries 61.3 % of the mass (Euler-Bernoulli closed
// form 0.6131), and 100 modes carry all but 1 %.
BOOST_AUTO_TEST_CASE(cantilever_effective_masses) {
  const Registry reg = make_default_registry();
  const Scene s = beam(Theory::EulerBernoulli, "clamped", "free", 100, 11);
  for (const char* b : {"exact", "difference_eq", "rfem"}) {
    const Solver& sv = reg.get(b);
    const Discretization mesh = std::string(b) == "exact" ? Discretization{} : Discretization{{400}};
    // rfem: 100 modes of this beam by the dense eigensolver (its Lanczos path is flagged
    // not-converged here: the Sturm count finds 96 modes below its 100th).
    Options o = testing::own_error_study();
    if (std::string(b) == "rfem") o.backend = {{"eigen", "dense"}};
    const Result r = sv.solve(s, mesh, o);
    BOOST_TEST_CONTEXT(b) {
      BOOST_REQUIRE(r.ok());
      const auto& ms = r.mode_shapes;
      BOOST_TEST(std::abs(ms.total_mass - s.material.rho * s.section().A) < 1e-9 * ms.total_mass);
      BOOST_TEST(std::abs(ms.effective_mass[0][2] / ms.total_mass - 0.6131) < 1e-3);
      double sum = 0;
      for (const auto& e : ms.effective_mass) sum += e[2];
      BOOST_TEST(sum / ms.total_mass > 0.99);
      BOOST_TEST(sum / ms.total_mass <= 1.0 + 1e-9);
    }
  }
}

// A square-section spatial cantilever: coincident bending pairs, torsion and axial modes in
// between. The harness pairs every back-end's modes with the exact ones correctly: each pair
// of the same family, MAC near 1 and frequency errors small.
BOOST_AUTO_TEST_CASE(square_section_pairs_every_mode) {
  Scene s = scene("dtfm_spatial_beam.toml");
  s.geometry.width = s.geometry.height = 0.1;
  s.request.modes = 10;
  s.loads.clear();
  s.request.probes.clear();
  s.request.frf.reset();
  const Registry reg = make_default_registry();
  CompareOptions opt;
  opt.quick = true;
  const auto all = run_comparison({s}, reg, opt);
  BOOST_REQUIRE(all.size() == 1u);
  const auto& c = all[0];
  BOOST_REQUIRE(c.reference.source == "exact");
  int checked = 0;
  for (const auto& r : c.runs) {
    if (r.backend == "exact" || r.failed() || r.backend == "difference_eq") continue;
    if (&r != &c.runs.back() && (&r + 1)->backend == r.backend) continue;  // the finest of each ladder
    BOOST_TEST_CONTEXT(r.backend << " " << r.mesh.spec()) {
      BOOST_TEST(r.paired_by_mac);
      for (std::size_t i = 0; i < c.reference.families.size(); ++i) {
        const int j = r.match[i];
        BOOST_REQUIRE(j >= 0);
        BOOST_TEST((r.result.mode_families[static_cast<std::size_t>(j)] == c.reference.families[i]), "mode " << i + 1);
        BOOST_TEST(r.pair_mac[i] > 0.95, "mode " << i + 1);
        BOOST_TEST(r.frequency_errors[i] < 0.05, "mode " << i + 1);
      }
      ++checked;
    }
  }
  BOOST_TEST(checked >= 2);  // rfem and dtfm
}

// The ParaView file: valid XML with the sample points and one array per mode and component.
BOOST_AUTO_TEST_CASE(vtu_export_reads_back) {
  const modalbench_test::TempDir dir("modalbench_vtk");
  Scene s = with_shapes(scene("paper_ss_plate.toml"), 11, 7);
  const Result r = make_default_registry().get("rfem").solve(s, Discretization{{20, 12}}, testing::own_error_study());
  BOOST_REQUIRE(r.ok());
  const auto files = write_vtk(s, "rfem", r, dir.str());
  BOOST_REQUIRE(files.size() == 2u);  // modes and statics
  std::ifstream in(files[0]);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string x = ss.str();
  BOOST_TEST(x.rfind("<?xml", 0) == 0u);
  BOOST_TEST(x.find("<Piece NumberOfPoints=\"77\" NumberOfCells=\"60\">") != std::string::npos);
  auto count = [&](const std::string& pattern) {
    const std::regex re(pattern);
    return static_cast<long>(std::distance(std::sregex_iterator(x.begin(), x.end(), re), std::sregex_iterator()));
  };
  // Every opened element is closed.
  for (const std::string tag : {"VTKFile", "UnstructuredGrid", "Piece", "Points", "Cells", "PointData"})
    BOOST_TEST(count("<" + tag + "[ >]") == count("</" + tag + ">"), tag);
  // Per mode: the displacement vector and theta_x, theta_y.
  BOOST_TEST(count("Name=\"mode [0-9]+ ") == 3 * static_cast<long>(r.frequencies_rad_s.size()));
  BOOST_TEST(x.find("rad_s") != std::string::npos);
}

// A scene without a shape request pays nothing and gets no shapes.
BOOST_AUTO_TEST_CASE(no_request_no_shapes) {
  const Registry reg = make_default_registry();
  const Scene s = scene("paper_fixed_beam.toml");
  for (const Solver* sv : reg.all()) BOOST_TEST(sv->solve(s, testing::default_mesh(*sv, s), testing::own_error_study()).mode_shapes.empty(), sv->name());
}
