#pragma once
// What the solver-level tests share: the registry of every back-end, a relative difference, the
// check that a scene text is refused with the key and reason named, and roots of a scalar function.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "modalbench/registry.hpp"

namespace modalbench::solver_tests {

inline const Registry& registry() {
  static const Registry r = make_default_registry();
  return r;
}

inline double rel(double a, double ref) { return std::abs(a / ref - 1.0); }

/// The tests' plate: steel, 1 x 0.8 x 0.01 m, Kirchhoff, every edge simply supported; `extra` adds
/// its loads, points and masses, `request` the body of its [request] table.
inline std::string steel_plate(const std::string& extra, const std::string& request) {
  return R"(
[scene]
name = "steel-plate"
kind = "plate"
physics = "bending"
theory = "kirchhoff"
[geometry]
length = 1.0
width = 0.8
height = 0.01
[material]
E = 2.1e11
nu = 0.3
rho = 7850.0
[supports]
x0 = "pinned"
xL = "pinned"
y0 = "pinned"
yB = "pinned"
)" + extra + "\n[request]\n" + request + "\n";
}

/// Parsing `text` must fail with an InputError naming `key`, its reason containing `reason`.
inline void expect_input_error(const std::string& text, const std::string& key, const std::string& reason) {
  try {
    parse_scene(text, "bad.toml");
    BOOST_ERROR("accepted: " << key);
  } catch (const InputError& e) {
    BOOST_TEST(e.key() == key, e.what());
    BOOST_TEST(e.reason().find(reason) != std::string::npos, e.what());
  }
}

/// Roots of f in (lo, hi), by sign changes on a fine grid and bisection to rounding (a sign change
/// through a pole, where |f| stays large, is not a root).
inline std::vector<double> roots(const std::function<double(double)>& f, double lo, double hi, int count) {
  std::vector<double> out;
  const int n = 20000;
  double a = lo, fa = f(a);
  for (int i = 1; i <= n && static_cast<int>(out.size()) < count; ++i) {
    const double c = lo + (hi - lo) * i / n, fc = f(c);
    if ((fa < 0) != (fc < 0)) {
      double x0 = a, x1 = c, f0 = fa;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (x0 + x1), fm = f(mid);
        if ((fm < 0) == (f0 < 0)) x0 = mid, f0 = fm;
        else x1 = mid;
      }
      if (std::abs(f(0.5 * (x0 + x1))) < 1e-6) out.push_back(0.5 * (x0 + x1));
    }
    a = c, fa = fc;
  }
  return out;
}

}  // namespace modalbench::solver_tests
