#pragma once
// The scene the core tests' fake back-ends solve (their answers do not depend on it): a steel
// cantilever 1 m long, 20 x 20 mm, Euler-Bernoulli bending, `modes` modes asked.

#include <string>

#include "modalbench/scene.hpp"

namespace modalbench::testing {

inline Scene cantilever_scene(const std::string& name, int modes) {
  const std::string text = R"([scene]
name = ")" + name + R"("
kind = "beam"
physics = "bending"
theory = "euler-bernoulli"
[geometry]
length = 1.0
width = 0.02
height = 0.02
[material]
E = 2.1e11
nu = 0.3
rho = 7850.0
[supports]
x0 = "clamped"
xL = "free"
[request]
modes = )" + std::to_string(modes) + "\n";
  return parse_scene(text, name + ".toml");
}

}  // namespace modalbench::testing
