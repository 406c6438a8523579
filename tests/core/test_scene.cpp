// Scene parsing and validation: every rule names the file, the key and the reason.
#define BOOST_TEST_MODULE scene
#include <boost/test/unit_test.hpp>

#include <regex>

#include "modalbench/scene.hpp"

using namespace modalbench;

namespace {

const std::string kBase = R"(
[scene]
name = "t"
kind = "beam"
physics = "bending"
theory = "timoshenko"
[geometry]
length = 2.0
width = 0.1
height = 0.2
[material]
E = 2.0e11
G = 8.0e10
rho = 7800.0
kappa = 0.85
[supports]
x0 = "clamped"
xL = { translational = 1.0e9, rotational = inf }
[[loads]]
x = 1.0
Fz = -1000.0
[request]
modes = 4
probes = [0.5, 2.0]
frf = { excite = 0.5, observe = 1.5, omega_min = 0.0, omega_max = 1000.0, points = 10 }
)";

const std::string kPlate = R"(
[scene]
name = "p"
kind = "plate"
physics = "bending"
theory = "kirchhoff"
[geometry]
length = 1.0
width = 0.6
height = 0.03
[material]
E = 2.0e11
nu = 0.3
rho = 8000.0
[supports]
x0 = "pinned"
xL = "pinned"
y0 = "clamped"
yB = { translational = 1e6, rotational = 0.0 }
[request]
modes = 3
probes = [[0.5, 0.3]]
)";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  BOOST_REQUIRE_MESSAGE(pos != std::string::npos, "test setup: '" << from << "' not in base scene");
  return s.replace(pos, from.size(), to);
}

// Parsing must fail with an InputError whose key is `key` and whose reason matches `reason`.
void expect_error(const std::string& text, const std::string& key, const std::string& reason) {
  try {
    parse_scene(text, "bad.toml");
    BOOST_ERROR("accepted an invalid scene (expected " << key << ": " << reason << ")");
  } catch (const InputError& e) {
    BOOST_TEST(e.source() == "bad.toml");
    BOOST_TEST(e.key() == key, "key: got '" << e.key() << "', want '" << key << "' (" << e.what() << ")");
    BOOST_TEST(std::regex_search(e.reason(), std::regex(reason)),
               "reason: got '" << e.reason() << "', want /" << reason << "/");
    BOOST_TEST(std::string(e.what()).find("bad.toml") == 0u);
  }
}

}  // namespace

BOOST_AUTO_TEST_SUITE(valid)

BOOST_AUTO_TEST_CASE(beam_values_read) {
  const Scene s = parse_scene(kBase, "ok.toml");
  BOOST_TEST(s.name == "t");
  BOOST_TEST(s.is_beam());
  BOOST_TEST((s.theory == Theory::Timoshenko));
  BOOST_TEST(s.material.nu == 0.25, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.x0.translational == kRigid);
  BOOST_TEST(s.xL.translational == 1e9);
  BOOST_TEST(s.xL.rotational == kRigid);
  BOOST_TEST(s.loads.size() == 1u);
  BOOST_TEST(s.loads[0].Fz == -1000.0);
  BOOST_TEST(s.request.modes == 4);
  BOOST_TEST(s.request.probes.size() == 2u);
  BOOST_TEST(s.request.frf.has_value());
  BOOST_TEST(s.request.frf->points == 10);
}

BOOST_AUTO_TEST_CASE(plate_values_read) {
  const Scene s = parse_scene(kPlate, "ok.toml");
  BOOST_TEST(s.is_plate());
  BOOST_TEST(s.material.G == 2e11 / 2.6, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(s.material.kappa == 5.0 / 6.0, boost::test_tools::tolerance(1e-15));
  // The kappa default is stated only where the theory uses it (Mindlin, not Kirchhoff).
  BOOST_TEST(s.notes.empty());
  const Scene mindlin = parse_scene(replace(kPlate, "theory = \"kirchhoff\"", "theory = \"mindlin\""), "ok.toml");
  BOOST_TEST(!mindlin.notes.empty());
  BOOST_TEST(s.y0.rotational == kRigid);
  BOOST_TEST(s.yB.translational == 1e6);
  BOOST_TEST(s.request.probes[0][1] == 0.3);
}

BOOST_AUTO_TEST_CASE(named_supports) {
  BOOST_TEST(Support::named("free").is_free());
  const Support p = Support::named("pinned");
  BOOST_TEST((p.translational == kRigid && p.rotational == 0.0));
  const Support g = Support::named("guided");
  BOOST_TEST((g.translational == 0.0 && g.rotational == kRigid));
  BOOST_CHECK_THROW(Support::named("roller"), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(builtin_scenes_load) {
  for (const char* f : {"paper_fixed_beam.toml", "paper_ss_plate.toml", "lasecka_elastic_beam.toml"}) {
    const Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + f);
    BOOST_TEST(!s.name.empty());
  }
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(invalid)

BOOST_AUTO_TEST_CASE(unknown_keys) {
  expect_error(kBase + "[extra]\na = 1\n", "extra", "unknown key");
  expect_error(replace(kBase, "kappa = 0.85", "kappa = 0.85\nEE = 1.0"), "material.EE", "unknown key");
  expect_error(replace(kBase, "x = 1.0\nFz", "x = 1.0\nFq = 2.0\nFz"), "loads[0].Fq", "unknown key");
  expect_error(replace(kBase, "{ translational = 1.0e9,", "{ axial = 1.0, translational = 1.0e9,"),
               "supports.xL.axial", "unknown key");  // bending physics has no axial DOF
}

BOOST_AUTO_TEST_CASE(missing_keys) {
  expect_error(replace(kBase, "length = 2.0\n", ""), "geometry.length", "missing");
  expect_error(replace(kBase, "E = 2.0e11\n", ""), "material.E", "missing");
  expect_error(replace(kBase, "G = 8.0e10\n", ""), "material", "G or nu");
  expect_error(replace(kBase, "xL = { translational = 1.0e9, rotational = inf }\n", ""), "supports.xL", "missing");
  expect_error(replace(kBase, "translational = 1.0e9, ", ""), "supports.xL.translational", "missing");
  expect_error(replace(kBase, "[scene]\nname = \"t\"\n", "[scene]\n"), "scene.name", "missing");
  expect_error(replace(kBase, ", points = 10", ""), "request.frf.points", "missing");
}

// [backend.NAME] tables are read as text per back-end; the back-end validates them when it solves.
BOOST_AUTO_TEST_CASE(backend_tables) {
  const Scene s = parse_scene(kBase + "[backend.rfem]\neigen = \"dense\"\nsturm_check = false\ntolerance = 1e-12\n"
                                      "[backend.difference_eq]\nresidual_check_max_R = 100\n",
                              "ok.toml");
  BOOST_REQUIRE(s.backend_options.count("rfem") == 1u);
  const auto& r = s.backend_options.at("rfem");
  BOOST_REQUIRE(r.size() == 3u);
  BOOST_TEST((r[0].key == "eigen" && r[0].text == "dense"));
  BOOST_TEST((r[1].key == "sturm_check" && r[1].text == "false"));
  BOOST_TEST(std::stod(r[2].text) == 1e-12);
  BOOST_TEST(s.backend_options.at("difference_eq")[0].text == "100");
  expect_error(kBase + "[backend]\nrfem = 3\n", "backend.rfem", "table of options");
  expect_error(kBase + "[backend.rfem]\neigen = [1, 2]\n", "backend.rfem.eigen", "boolean, a number or a string");
}

BOOST_AUTO_TEST_CASE(wrong_types) {
  expect_error(replace(kBase, "length = 2.0", "length = \"2\""), "geometry.length", "number");
  expect_error(replace(kBase, "modes = 4", "modes = 4.5"), "request.modes", "integer");
  expect_error(replace(kBase, "x0 = \"clamped\"", "x0 = 3"), "supports.x0", "support name or a table");
  expect_error(replace(kBase, "probes = [0.5, 2.0]", "probes = 0.5"), "request.probes", "array");
}

BOOST_AUTO_TEST_CASE(non_positive_and_non_finite) {
  expect_error(replace(kBase, "length = 2.0", "length = 0.0"), "geometry.length", "> 0");
  expect_error(replace(kBase, "width = 0.1", "width = -0.1"), "geometry.width", "> 0");
  expect_error(replace(kBase, "rho = 7800.0", "rho = nan"), "material.rho", "NaN");
  expect_error(replace(kBase, "height = 0.2", "height = inf"), "geometry.height", "finite");
  expect_error(replace(kBase, "E = 2.0e11", "E = -2.0e11"), "material.E", "> 0");
  expect_error(replace(kBase, "translational = 1.0e9", "translational = -1.0"), "supports.xL.translational", ">= 0");
  expect_error(replace(kBase, "translational = 1.0e9", "translational = nan"), "supports.xL.translational", "NaN");
  expect_error(replace(kBase, "kappa = 0.85", "kappa = 0.0"), "material.kappa", "> 0");
  expect_error(replace(kBase, "Fz = -1000.0", "Fz = nan"), "loads[0].Fz", "NaN");
}

BOOST_AUTO_TEST_CASE(poisson_ratio_and_consistency) {
  expect_error(replace(kPlate, "nu = 0.3", "nu = 0.5"), "material.nu", "\\(-1, 0.5\\)");
  expect_error(replace(kPlate, "nu = 0.3", "nu = -1.0"), "material.nu", "\\(-1, 0.5\\)");
  expect_error(replace(kBase, "G = 8.0e10", "G = 8.0e10\nnu = 0.3"), "material.G", "inconsistent");
  expect_error(replace(kBase, "G = 8.0e10", "G = 5.0e10"), "material.G", "implies nu");  // nu = 1.0
}

// A plate so slender that its first modes lie closer than double precision resolves is refused
// by name (it ran past 60 s in rfem and dtfm at 3e67 m wide); a strip 1e6 times longer than wide
// is still a plate. The probe stays inside.
BOOST_AUTO_TEST_CASE(plates_beyond_double_precision_aspect) {
  expect_error(replace(kPlate, "width = 0.6", "width = 3e67"), "geometry.width", "3e\\+67 times longer than wide");
  expect_error(replace(replace(kPlate, "length = 1.0", "length = 5e34"), "probes = [[0.5, 0.3]]", "probes = [[1.0, 0.3]]"),
               "geometry.length", "below what double precision resolves");
  BOOST_CHECK_NO_THROW(parse_scene(replace(kPlate, "width = 0.6", "width = 1e6"), "ok.toml"));
}

BOOST_AUTO_TEST_CASE(unknown_names) {
  expect_error(replace(kBase, "x0 = \"clamped\"", "x0 = \"welded\""), "supports.x0", "unknown support 'welded'");
  expect_error(replace(kBase, "kind = \"beam\"", "kind = \"shell\""), "scene.kind", "unknown kind");
  expect_error(replace(kBase, "physics = \"bending\"", "physics = \"3d\""), "scene.physics", "unknown beam physics");
  expect_error(replace(kBase, "theory = \"timoshenko\"", "theory = \"kirchhoff\""), "scene.theory", "unknown beam theory");
  expect_error(replace(kPlate, "theory = \"kirchhoff\"", "theory = \"timoshenko\""), "scene.theory", "unknown plate theory");
  expect_error(replace(kPlate, "[supports]\n", "[supports]\nyC = \"free\"\n"), "supports.yC", "unknown key");
}

BOOST_AUTO_TEST_CASE(positions_and_requests) {
  expect_error(replace(kBase, "x = 1.0", "x = 2.5"), "loads[0].x", "\\[0, 2\\]");
  expect_error(replace(kBase, "probes = [0.5, 2.0]", "probes = [0.5, -0.1]"), "request.probes[1]", "\\[0, 2\\]");
  expect_error(replace(kPlate, "probes = [[0.5, 0.3]]", "probes = [[0.5, 0.7]]"), "request.probes[0][1]", "\\[0, 0.6\\]");
  expect_error(replace(kPlate, "probes = [[0.5, 0.3]]", "probes = [0.5]"), "request.probes[0]", "\\[x, y\\]");
  expect_error(replace(kBase, "omega_max = 1000.0", "omega_max = 0.0"), "request.frf.omega_max", "> omega_min");
  expect_error(replace(kBase, "points = 10", "points = 1"), "request.frf.points", "\\[2, 1000000\\]");
  expect_error(replace(kBase, "modes = 4", "modes = -1"), "request.modes", "\\[0, 100000\\]");
  expect_error(replace(kBase, "x = 1.0\nFz = -1000.0", "x = 1.0"), "loads[0]", "at least one component");
}

BOOST_AUTO_TEST_CASE(syntax_and_files) {
  expect_error("[scene\nname = 1", "line 1", "TOML syntax");
  BOOST_CHECK_THROW(load_scene("/nonexistent/scene.toml"), InputError);
  try {
    load_scene("/nonexistent/scene.toml");
  } catch (const InputError& e) {
    BOOST_TEST(e.source() == "/nonexistent/scene.toml");
    BOOST_TEST(e.reason() == "no such file");
  }
}

BOOST_AUTO_TEST_SUITE_END()

// Beam sections other than rectangles: properties against their closed forms (independent of
// the code: written out here), Cowper's shear coefficients, and every bad input named.
BOOST_AUTO_TEST_SUITE(sections)

const std::string kGeom = "[geometry]\nlength = 2.0\nwidth = 0.1\nheight = 0.2\n";

std::string with_section(const std::string& section, std::string base = kBase) {
  base = replace(base, kGeom, "[geometry]\nlength = 2.0\nsection = " + section + "\n");
  return replace(base, "kappa = 0.85\n", "");
}

BOOST_AUTO_TEST_CASE(circle_tube_general_properties) {
  const double pi = 3.14159265358979323846;
  const Scene c = parse_scene(with_section("{ shape = \"circle\", diameter = 0.04 }"), "c.toml");
  const Section sc = c.section();
  BOOST_TEST(sc.A == pi * 0.04 * 0.04 / 4, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(sc.Iy == pi * std::pow(0.04, 4) / 64, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(sc.Iz == sc.Iy);
  BOOST_TEST(sc.J == 2 * sc.Iy, boost::test_tools::tolerance(1e-14));  // J = Ip for a circle
  BOOST_TEST(sc.Ip == sc.J);
  BOOST_TEST(c.geometry.width == 0.04);
  BOOST_TEST(c.geometry.height == 0.04);
  // Cowper (1966), solid circle: 6 (1 + nu) / (7 + 6 nu) with nu = E / 2G - 1 = 0.25.
  BOOST_TEST(c.material.kappa == 6 * 1.25 / (7 + 6 * 0.25), boost::test_tools::tolerance(1e-14));

  const Scene t = parse_scene(with_section("{ shape = \"tube\", outer_diameter = 0.1, inner_diameter = 0.08 }"), "t.toml");
  const Section st = t.section();
  BOOST_TEST(st.A == pi * (0.01 - 0.0064) / 4, boost::test_tools::tolerance(1e-13));
  BOOST_TEST(st.Iy == pi * (1e-4 - std::pow(0.08, 4)) / 64, boost::test_tools::tolerance(1e-13));
  BOOST_TEST(st.J == pi * (1e-4 - std::pow(0.08, 4)) / 32, boost::test_tools::tolerance(1e-13));
  // Cowper, hollow circle, m = 0.8.
  const double m2 = 0.64, q = (1 + m2) * (1 + m2);
  BOOST_TEST(t.material.kappa == 6 * 1.25 * q / ((7 + 6 * 0.25) * q + (20 + 12 * 0.25) * m2),
             boost::test_tools::tolerance(1e-14));
  // A thin wall tends to Cowper's thin-walled tube, 2 (1 + nu) / (4 + 3 nu).
  BOOST_TEST(cowper_kappa_tube(0.25, 1.0) == 2 * 1.25 / (4 + 3 * 0.25), boost::test_tools::tolerance(1e-14));

  const Scene g = parse_scene(
      replace(with_section("{ shape = \"general\", area = 2e-3, Iy = 3e-6, Iz = 1e-6, J = 5e-7 }"), "[material]\n",
              "[material]\nkappa = 0.5\n"),
      "g.toml");
  const Section sg = g.section();
  BOOST_TEST(sg.A == 2e-3);
  BOOST_TEST(sg.Iy == 3e-6);
  BOOST_TEST(sg.Iz == 1e-6);
  BOOST_TEST(sg.J == 5e-7);
  BOOST_TEST(sg.Ip == 4e-6, boost::test_tools::tolerance(1e-14));
  BOOST_TEST(g.material.kappa == 0.5);

  // A rectangle written as a section is the shorthand's rectangle, kappa still 5/6 by default.
  const Scene r = parse_scene(with_section("{ shape = \"rectangle\", width = 0.1, height = 0.2 }"), "r.toml");
  const Section sr = r.section(), ref = rectangular_section(0.1, 0.2);
  BOOST_TEST(sr.A == ref.A);
  BOOST_TEST(sr.J == ref.J);
  BOOST_TEST(r.material.kappa == 5.0 / 6.0);
}

BOOST_AUTO_TEST_CASE(bad_sections_are_named) {
  expect_error(with_section("{ shape = \"tube\", outer_diameter = 0.1, inner_diameter = 0.1 }"),
               "geometry.section.inner_diameter", "below outer_diameter");
  expect_error(with_section("{ shape = \"tube\", outer_diameter = 0.1, inner_diameter = 0.2 }"),
               "geometry.section.inner_diameter", "below outer_diameter");
  expect_error(with_section("{ shape = \"tube\", outer_diameter = 0.1 }"), "geometry.section.inner_diameter", "missing");
  expect_error(with_section("{ shape = \"hexagon\", diameter = 0.1 }"), "geometry.section.shape", "unknown shape");
  expect_error(with_section("{ diameter = 0.1 }"), "geometry.section.shape", "missing");
  expect_error(with_section("{ shape = \"circle\", diameter = -0.1 }"), "geometry.section.diameter", "> 0");
  expect_error(with_section("{ shape = \"circle\", diameter = 0.1, width = 0.2 }"), "geometry.section.width",
               "unknown key");
  expect_error(replace(kBase, "height = 0.2\n", "height = 0.2\nsection = { shape = \"circle\", diameter = 0.1 }\n"),
               "geometry.width", "not both");
  expect_error(with_section("{ shape = \"general\", area = 2e-3, Iy = 3e-6, Iz = 1e-6, J = 5e-7 }"), "material.kappa",
               "general section under Timoshenko");
  expect_error(replace(kPlate, "height = 0.03\n", "height = 0.03\nsection = { shape = \"circle\", diameter = 0.1 }\n"),
               "geometry.section", "plate has no cross-section");
}

BOOST_AUTO_TEST_SUITE_END()

// A plate's rigid motions left free by its edges, from the supports' pattern alone.
BOOST_AUTO_TEST_CASE(free_plate_rigid_motions_by_pattern) {
  const Scene base = parse_scene(kPlate, "ok.toml");
  auto with = [&](const char* x0, const char* xL, const char* y0, const char* yB) {
    Scene s = base;
    s.x0 = Support::named(x0);
    s.xL = Support::named(xL);
    s.y0 = Support::named(y0);
    s.yB = Support::named(yB);
    return free_plate_rigid_motions(s);
  };
  const auto guided = with("guided", "guided", "guided", "guided");
  BOOST_TEST_REQUIRE(guided.size() == 1u);
  BOOST_TEST(guided[0] == "translation z");
  BOOST_TEST(with("free", "free", "free", "free").size() == 3u);
  BOOST_TEST(with("pinned", "pinned", "pinned", "pinned").empty());
  BOOST_TEST(with("clamped", "free", "free", "free").empty());  // a cantilever plate
  BOOST_TEST(with("pinned", "pinned", "free", "free").empty());  // two opposite pinned edges
  const auto one_pin = with("pinned", "free", "free", "free");  // turns about its pinned edge
  BOOST_TEST_REQUIRE(one_pin.size() == 1u);
  BOOST_TEST(one_pin[0] == "rotation about y (w linear in x)");
  BOOST_TEST(free_plate_rigid_motions(parse_scene(kBase, "beam.toml")).empty());
}
