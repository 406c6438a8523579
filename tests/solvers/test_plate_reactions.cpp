// Plate edge reactions: each edge's resultant as a hard support (its Kirchhoff effective shear plus
// half of each corner force at its ends, with the moment about the edge's middle), from exact (Levy
// strips in closed form, checked against closed forms in tests/exact/test_exact_plate.cpp) and
// from rfem, whose held edges and corners give them without multipliers (corner-value
// coordinates) or by the multipliers of the holds that are not redundant. rfem must converge to
// exact at second order on meshes of near-square cells; every back-end's reactions balance the
// loads. A rectangle: the split between its long and short edges is what a wrong treatment of the
// held chains' redundancy got wrong (5 %) while the totals balanced.
#define BOOST_TEST_MODULE plate_reactions
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "solve_options.hpp"
#include "solver_tests.hpp"

using namespace modalbench;
using namespace modalbench::solver_tests;

namespace {

std::string plate(const std::string& loads) { return steel_plate(loads, "modes = 0\nprobes = [[0.5, 0.4]]"); }

std::map<std::string, Reaction> by_name(const Result& r) {
  std::map<std::string, Reaction> out;
  for (const Reaction& e : r.reactions) out[e.support] = e;
  return out;
}

/// Forces and moments about the origin of the reactions plus the loads (force, x, y each).
void check_balance(const Result& r, const std::vector<std::array<double, 3>>& loads, double tol) {
  double fz = 0, mx = 0, my = 0, scale = 0;
  for (const auto& [F, x, y] : loads) {
    fz += F;
    mx += y * F;
    my -= x * F;
    scale += std::abs(F);
  }
  for (const Reaction& e : r.reactions) {
    fz += e.force[2];
    mx += e.moment[0] + e.position[1] * e.force[2];
    my += e.moment[1] - e.position[0] * e.force[2];
  }
  BOOST_TEST(std::abs(fz) <= tol * scale);
  BOOST_TEST(std::abs(mx) <= tol * scale);
  BOOST_TEST(std::abs(my) <= tol * scale);
}

Result rfem_at(const Scene& s, const std::string& mesh, const std::string& shear) {
  Options o = testing::own_error_study();
  o.backend = {{"plate_rigid_shear", shear}};
  const Result r = registry().get("rfem").solve(s, Discretization::parse(mesh), o);
  BOOST_TEST_REQUIRE((r.summary.status == Status::Success), mesh << ": " << r.summary.message);
  BOOST_TEST_REQUIRE(r.reactions.size() == 4u, mesh << ": " << r.summary.message);
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(rfem_edges_converge_to_exact_at_second_order) {
  const std::string text = plate("[[pressures]]\np = -1000.0");
  const Scene s = parse_scene(text, "uniform.toml");
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  BOOST_REQUIRE_EQUAL(ex.reactions.size(), 4u);
  check_balance(ex, {{-800.0, 0.5, 0.4}}, 1e-9);
  const auto exact = by_name(ex);
  // The long edges (y0, yB: 1 m) carry more than the short ones: 232.7 N against 167.3 N.
  BOOST_TEST(exact.at("y0").force[2] > 1.3 * exact.at("x0").force[2]);
  for (const std::string shear : {"corner-coordinates", "multipliers"}) {
    std::vector<std::map<std::string, Reaction>> runs;
    for (const std::string mesh : {"20x16", "40x32", "80x64"}) {
      const Result rf = rfem_at(s, mesh, shear);
      check_balance(rf, {{-800.0, 0.5, 0.4}}, 1e-8);
      runs.push_back(by_name(rf));
    }
    for (const std::string edge : {"x0", "xL", "y0", "yB"}) {
      const double ref = exact.at(edge).force[2];
      const double e1 = runs[0].at(edge).force[2] - ref, e2 = runs[1].at(edge).force[2] - ref,
                   e3 = runs[2].at(edge).force[2] - ref;
      BOOST_TEST_MESSAGE(shear << " " << edge << ": errors " << e1 << ", " << e2 << ", " << e3);
      // Second order: each halving of the cells divides the error by about 4.
      BOOST_TEST((e1 / e2 > 3.5 && e1 / e2 < 4.5), shear << " " << edge << ": ratio " << e1 / e2);
      BOOST_TEST((e2 / e3 > 3.5 && e2 / e3 < 4.5), shear << " " << edge << ": ratio " << e2 / e3);
      BOOST_TEST(std::abs(e3) < 2e-5 * 800.0, shear << " " << edge);
    }
  }
}

BOOST_AUTO_TEST_CASE(patch_and_point_force_agree_and_balance) {
  const std::string text =
      plate("[[pressures]]\np = -20000.0\nx = [0.55, 0.75]\ny = [0.3, 0.5]\n[[loads]]\nx = 0.2\ny = 0.6\nFz = -300.0");
  const Scene s = parse_scene(text, "patch.toml");
  const std::vector<std::array<double, 3>> loads = {{-800.0, 0.65, 0.4}, {-300.0, 0.2, 0.6}};
  const Result ex = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(ex.summary.status == Status::Success);
  check_balance(ex, loads, 1e-9);
  const Result coarse = rfem_at(s, "40x32", "corner-coordinates"), fine = rfem_at(s, "80x64", "corner-coordinates");
  check_balance(fine, loads, 1e-8);
  const auto e = by_name(ex), c = by_name(coarse), f = by_name(fine);
  for (const std::string edge : {"x0", "xL", "y0", "yB"}) {
    // Richardson at second order removes the leading error: what is left is far below it.
    const double richardson = f.at(edge).force[2] + (f.at(edge).force[2] - c.at(edge).force[2]) / 3;
    const double err = std::abs(richardson - e.at(edge).force[2]), lead = std::abs(f.at(edge).force[2] - e.at(edge).force[2]);
    BOOST_TEST_MESSAGE(edge << ": exact " << e.at(edge).force[2] << ", rfem 80x64 " << f.at(edge).force[2]
                            << ", extrapolated " << richardson);
    BOOST_TEST(err < 0.2 * lead + 1e-9 * 1100.0, edge);
    BOOST_TEST(lead < 2e-4 * 1100.0, edge);
    // The moments about the edges' middles (the patch is off-centre in x: y0 and yB have one).
    const int k = edge[0] == 'x' ? 0 : 1;
    BOOST_TEST(std::abs(f.at(edge).moment[k] - e.at(edge).moment[k]) < 2e-4 * 1100.0, edge);
  }
}

// dtfm: the short edges from their end conditions' forces, the long ones by the virtual work of
// their lines' rigid motions (dtfm/src/plate_reactions.cpp); strips converge at second order.
BOOST_AUTO_TEST_CASE(dtfm_edges_converge_to_exact_at_second_order) {
  const std::string text =
      plate("[[pressures]]\np = -20000.0\nx = [0.55, 0.75]\ny = [0.3, 0.5]\n[[loads]]\nx = 0.2\ny = 0.6\nFz = -300.0");
  const Scene s = parse_scene(text, "patch.toml");
  const std::vector<std::array<double, 3>> loads = {{-800.0, 0.65, 0.4}, {-300.0, 0.2, 0.6}};
  const auto ex = by_name(registry().get("exact").solve(s, {}, Options{}));
  std::vector<std::map<std::string, Reaction>> runs;
  for (const std::string mesh : {"16", "32", "64"}) {
    const Result r = registry().get("dtfm").solve(s, Discretization::parse(mesh), testing::own_error_study());
    BOOST_TEST_REQUIRE((r.summary.status == Status::Success), mesh << ": " << r.summary.message);
    BOOST_TEST_REQUIRE(r.reactions.size() == 4u);
    // Rounding of K d - f against the stiff strip layers: the solver warns above 1e-6.
    check_balance(r, loads, 1e-6);
    runs.push_back(by_name(r));
  }
  for (const std::string edge : {"x0", "xL", "y0", "yB"})
    for (const int comp : {-1, 1}) {  // the force, and the moment along the long edges
      if (comp == 1 && edge[0] == 'x') continue;
      auto value = [&](const std::map<std::string, Reaction>& m) {
        return comp < 0 ? m.at(edge).force[2] : m.at(edge).moment[1];
      };
      const double e1 = value(runs[0]) - value(ex), e2 = value(runs[1]) - value(ex), e3 = value(runs[2]) - value(ex);
      BOOST_TEST_MESSAGE(edge << (comp < 0 ? " Fz" : " My") << ": errors " << e1 << ", " << e2 << ", " << e3);
      BOOST_TEST((e1 / e2 > 3.3 && e1 / e2 < 4.7), edge << ": ratio " << e1 / e2);
      BOOST_TEST((e2 / e3 > 3.3 && e2 / e3 < 4.7), edge << ": ratio " << e2 / e3);
    }
}
