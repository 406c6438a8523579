// Spectrum slicing on the count, plain and polished on the determinant, on manufactured spectra.
#define BOOST_TEST_MODULE spectrum_slicing
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "modalbench/numerics/spectrum_slicing.hpp"

using namespace modalbench;

BOOST_AUTO_TEST_SUITE(slicing)

// A manufactured spectrum with a double and a triple eigenvalue: slicing returns each with
// its multiplicity, and values to the requested tolerance.
BOOST_AUTO_TEST_CASE(repeated_eigenvalues_keep_multiplicity) {
  const std::vector<double> spectrum = {0.5, 2.0, 2.0, 3.25, 7.0, 7.0, 7.0, 11.0};
  auto count = [&](double lam) {
    int n = 0;
    for (double s : spectrum) n += s < lam;
    return n;
  };
  SliceStats st;
  const auto got = slice_spectrum(count, 7, 0.0, 1.0, 1e-13, &st);
  BOOST_TEST(got.size() == 7u);
  for (std::size_t i = 0; i < got.size(); ++i) BOOST_TEST(std::abs(got[i] - spectrum[i]) < 1e-11);
  BOOST_TEST(st.count_evaluations > 0);
}

BOOST_AUTO_TEST_CASE(non_monotonic_count_is_an_error) {
  int calls = 0;
  auto bad = [&](double lam) { return lam <= 0 ? 0 : ((++calls % 2) ? 3 : 1); };
  BOOST_CHECK_THROW(slice_spectrum(bad, 2, 0.0, 1.0), std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()

BOOST_AUTO_TEST_SUITE(polished_slicing)

// A manufactured characteristic function with known roots (one double): the polished slicer
// returns every root to the tolerance, the double one twice, and uses few evaluations per root.
BOOST_AUTO_TEST_CASE(roots_of_a_manufactured_determinant) {
  const std::vector<double> roots = {0.7, 1.9, 2.05, 3.3, 3.3, 5.0, 8.25};
  long calls = 0;
  auto eval = [&](double lam) {
    ++calls;
    CountDet cd;
    for (double r : roots) {
      cd.count += r < lam;
      cd.log_abs_det += std::log(std::abs(lam - r));
    }
    cd.log_abs_det += 0.3 * lam;  // a smooth positive factor
    return cd;
  };
  SliceStats st;
  const auto got = slice_interval_polished(eval, 0.0, 9.0, 1e-12, 1e-14, &st);
  BOOST_REQUIRE(got.size() == roots.size());
  for (std::size_t i = 0; i < roots.size(); ++i) BOOST_TEST(std::abs(got[i] - roots[i]) < 1e-10 * roots[i]);
  BOOST_TEST(st.count_evaluations == calls);
  BOOST_TEST(calls < 25 * static_cast<long>(roots.size()));
}

// A determinant with a rounding floor, as K(lambda)'s: log |det| carries noise of 1e-9 relative
// (deterministic, from lambda's bits) on top of the roots' factors; the count stays exact. Each
// value must lie within the counts' bracket the polish reports (polish_floor_width), that bound
// must be honest and near the noise, and the polish must not keep sampling the noise (before the
// noise test it took 106 evaluations here, on to 1e-13 only because this count is exact where
// K's own rounds with its determinant).
BOOST_AUTO_TEST_CASE(determinant_with_a_rounding_floor) {
  const std::vector<double> roots = {0.7, 1.9, 2.05, 3.3, 5.0, 8.25};
  long calls = 0;
  auto noise = [](double lam) {
    std::uint64_t b;
    std::memcpy(&b, &lam, sizeof b);
    b ^= b >> 33;
    b *= 0xff51afd7ed558ccdULL;
    b ^= b >> 33;
    return static_cast<double>(b % 2000001) / 1e6 - 1.0;  // in [-1, 1]
  };
  auto eval = [&](double lam) {
    ++calls;
    CountDet cd;
    double det = 1;
    for (double r : roots) {
      cd.count += r < lam;
      det *= lam - r;
    }
    cd.log_abs_det = std::log(std::abs(det + 1e-9 * noise(lam))) + 0.3 * lam;
    return cd;
  };
  SliceStats st;
  const auto got = slice_interval_polished(eval, 0.0, 9.0, 1e-13, 1e-14, &st);
  BOOST_REQUIRE(got.size() == roots.size());
  double worst = 0;
  for (std::size_t i = 0; i < roots.size(); ++i) worst = std::max(worst, std::abs(got[i] - roots[i]) / roots[i]);
  BOOST_TEST_MESSAGE("worst relative error " << worst << ", reported floor width " << st.polish_floor_width
                                             << ", evaluations " << calls);
  BOOST_TEST(worst <= std::max(st.polish_floor_width, 1e-12));
  BOOST_TEST(st.polish_floor_width <= kPolishFloor);
  BOOST_TEST(calls < 14 * static_cast<long>(roots.size()));
}

BOOST_AUTO_TEST_CASE(non_monotonic_count_is_an_error) {
  int n = 0;
  auto bad = [&](double lam) {
    CountDet cd;
    cd.count = lam <= 0 ? 0 : ((++n % 2) ? 3 : 1);
    cd.log_abs_det = 0.0;
    return cd;
  };
  BOOST_CHECK_THROW(slice_interval_polished(bad, 0.0, 1.0, 1e-12, 1e-14), std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()
