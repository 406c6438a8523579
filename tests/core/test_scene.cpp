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
  BOOST_TEST(!s.notes.empty());  // the kappa default is stated
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
