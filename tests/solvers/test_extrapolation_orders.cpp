// The Richardson values every meshed back-end reports beside its own (Result::extrapolated,
// core/include/modalbench/extrapolation.hpp): their observed order of convergence against the
// exact solution of the scene's theory is the one each back-end states (CoarserMesh::next_order),
// and every mode lies within its own estimate.
//   rfem beams (FV5, Lasecka, spatial cantilever) h^2 removed, h^3 left (the symmetric
//     clamped-clamped paper beam: h^4)
//   rfem plate (paper plate, Kirchhoff/Mindlin)  h^2 removed, h^3 left
//   dtfm plate strips (paper plate)              h^2 removed, h^4 left
//   difference_eq (Lasecka beam), consistent    h^4 removed, h^6 left; lumped: h^2 removed, h^4 left
#define BOOST_TEST_MODULE extrapolation_orders
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "modalbench/registry.hpp"

using namespace modalbench;

namespace {

const Registry& registry() {
  static const Registry r = make_default_registry();
  return r;
}

Scene frequencies_of(const std::string& file, std::optional<Theory> theory = std::nullopt) {
  Scene s = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + file);
  if (theory) s.theory = *theory;
  s.request.probes.clear();
  s.request.frf.reset();
  s.loads.clear();
  return s;
}

/// The largest relative error of the extrapolated frequencies against exact, after checking that
/// each mode is within its own estimate.
double extrapolated_error(const Scene& s, const std::string& backend, const std::string& mesh, MassModel mass = MassModel::Consistent) {
  Options o;
  o.mass = mass;
  const Result exact = registry().get("exact").solve(s, {}, Options{});
  BOOST_REQUIRE(exact.ok());
  const Result r = registry().get(backend).solve(s, Discretization::parse(mesh), o);
  BOOST_TEST_CONTEXT(backend << " " << mesh << ": " << r.extrapolated.note) {
    BOOST_REQUIRE(r.summary.status == Status::Success || r.summary.status == Status::NotConverged);
    const auto& x = r.extrapolated;
    BOOST_REQUIRE_EQUAL(x.frequencies_rad_s.size(), exact.frequencies_rad_s.size());
    double worst = 0, worst_mesh = 0;
    for (std::size_t i = 0; i < x.frequencies_rad_s.size(); ++i) {
      const double err = std::abs(x.frequencies_rad_s[i] / exact.frequencies_rad_s[i] - 1);
      BOOST_TEST_INFO("mode " << i + 1);
      BOOST_TEST(err <= x.frequency_errors[i]);
      worst = std::max(worst, err);
      worst_mesh = std::max(worst_mesh, std::abs(r.frequencies_rad_s[i] / exact.frequencies_rad_s[i] - 1));
    }
    // The extrapolation gained something overall (a single mode whose error terms nearly cancel
    // on the mesh may come out better unextrapolated: it is then one the meshes show as not yet
    // asymptotic, with the mesh's own estimate).
    BOOST_TEST(worst < 0.2 * worst_mesh);
    return worst;
  }
  return NAN;
}

void check_order(const Scene& s, const std::string& backend, const std::string& coarse, const std::string& fine, double lo,
                 double hi, MassModel mass = MassModel::Consistent) {
  const double e1 = extrapolated_error(s, backend, coarse, mass), e2 = extrapolated_error(s, backend, fine, mass);
  const double order = std::log2(e1 / e2);
  BOOST_TEST_MESSAGE(backend << " " << coarse << " -> " << fine << ": " << e1 << " -> " << e2 << ", order " << order);
  BOOST_TEST(order >= lo);
  BOOST_TEST(order <= hi);
}

}  // namespace

BOOST_AUTO_TEST_CASE(rfem_beams_extrapolated_at_third_order) {
  check_order(frequencies_of("nafems_fv5_deep_beam.toml"), "rfem", "64", "128", 2.8, 3.4);
  check_order(frequencies_of("lasecka_elastic_beam.toml"), "rfem", "128", "256", 2.8, 3.4);
  check_order(frequencies_of("dtfm_spatial_beam.toml"), "rfem", "128", "256", 2.8, 3.4);
  // The clamped-clamped paper beam, symmetric, loses its h^3 term too.
  check_order(frequencies_of("paper_fixed_beam.toml"), "rfem", "64", "128", 3.8, 4.2);
}

BOOST_AUTO_TEST_CASE(rfem_plate_extrapolated_at_third_order_kirchhoff_and_mindlin) {
  check_order(frequencies_of("paper_ss_plate.toml"), "rfem", "40x24", "80x48", 2.8, 3.6);
  check_order(frequencies_of("paper_ss_plate.toml", Theory::Mindlin), "rfem", "40x24", "80x48", 2.8, 3.6);
}

BOOST_AUTO_TEST_CASE(dtfm_plate_strips_extrapolated_at_fourth_order) {
  check_order(frequencies_of("paper_ss_plate.toml"), "dtfm", "16", "32", 3.8, 5.0);
}

BOOST_AUTO_TEST_CASE(difference_eq_extrapolated_at_sixth_order_consistent_fourth_lumped) {
  const Scene s = frequencies_of("lasecka_elastic_beam.toml");
  check_order(s, "difference_eq", "32", "64", 5.7, 6.3);
  // Lumped: the highest of the 8 modes reaches its asymptotic range later (mode 1: order 4.0 from
  // 32 elements on; the largest error over the modes: 3.7 from 64 to 128, 3.75 from 128 to 256).
  check_order(s, "difference_eq", "128", "256", 3.6, 4.4, MassModel::Lumped);
}

BOOST_AUTO_TEST_CASE(a_multi_prism_section_is_not_extrapolated_and_says_why) {
  // Its limit is 3D elasticity, not a known expansion: no next order is stated.
  const Scene s = frequencies_of("paper_fixed_beam.toml");
  const Result r = registry().get("dtfm").solve(s, Discretization::parse("4x4"), Options{});
  BOOST_TEST(r.extrapolated.frequencies_rad_s.empty());
  BOOST_TEST(r.extrapolated.note.find("next order") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(plates_with_other_edges_stay_within_their_estimates) {
  // The paper plate with its long edges clamped, then free (exact: Levy); rfem's mode 7 on 40 x 24
  // with clamped edges shows order 1.75 and was 6.2e-5 off for an estimate of 3.2e-5 before the
  // order's own uncertainty entered the estimate.
  for (const char* edge : {"clamped", "free"}) {
    Scene s = frequencies_of("paper_ss_plate.toml");
    s.y0 = s.yB = Support::named(edge);
    validate(s);
    BOOST_TEST_CONTEXT("long edges " << edge) {
      for (const char* mesh : {"40x24", "80x48"}) extrapolated_error(s, "rfem", mesh);
      for (const char* mesh : {"16", "32"}) extrapolated_error(s, "dtfm", mesh);
    }
  }
}

BOOST_AUTO_TEST_CASE(dtfm_strips_with_a_free_end_are_not_extrapolated) {
  // NAFEMS FV16's cantilever: the 32-strip values extrapolated were 1.7e-4 and 4.8e-4 off (modes 2
  // and 5) where the estimates said 1.8e-5 and 3.0e-5: no next order is stated for free strip ends.
  const Scene s = frequencies_of("nafems_fv16_cantilever_plate.toml");
  const Result r = registry().get("dtfm").solve(s, Discretization::parse("16"), Options{});
  BOOST_TEST(r.extrapolated.frequencies_rad_s.empty());
  BOOST_TEST(r.extrapolated.note.find("next order") != std::string::npos);
}
