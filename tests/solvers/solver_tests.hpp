#pragma once
// What the solver-level tests share: the registry of every back-end, a relative difference, and
// the check that a scene text is refused with the key and reason named.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "modalbench/registry.hpp"

namespace modalbench::solver_tests {

inline const Registry& registry() {
  static const Registry r = make_default_registry();
  return r;
}

inline double rel(double a, double ref) { return std::abs(a / ref - 1.0); }

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

}  // namespace modalbench::solver_tests
