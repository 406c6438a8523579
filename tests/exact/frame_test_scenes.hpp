#pragma once
// What the exact frame tests share: a frame scene from TOML solved by exact, the built-in scenes,
// the steel, and the portal of scenes/frame_portal.toml.
#include <fmt/format.h>

#include <string>

#include "modalbench/exact/exact.hpp"

namespace modalbench::frame_tests {

inline Scene builtin(const char* file) { return load_scene(std::string(MODALBENCH_SCENES_DIR) + "/" + file); }

inline Result solve(const std::string& toml) {
  exact::ExactSolver s;
  return s.solve(parse_scene(toml, "test.toml"), {}, {});
}

inline const char* kSteel = "[material]\nE = 2.1e11\nnu = 0.3\nrho = 7850.0\n";

/// The portal of scenes/frame_portal.toml as TOML, with optional hinge and supports.
inline std::string portal_toml(const std::string& physics, const std::string& extra_member_bc = "",
                        const std::string& support_d = "clamped") {
  return fmt::format(R"([scene]
name = "portal"
kind = "frame"
physics = "{}"
theory = "euler-bernoulli"
{}
[[nodes]]
id = "A"
x = 0.0
z = 0.0
[[nodes]]
id = "B"
x = 0.0
z = 4.0
[[nodes]]
id = "C"
x = 6.0
z = 4.0
[[nodes]]
id = "D"
x = 6.0
z = 0.0
[[members]]
id = "AB"
nodes = ["A", "B"]
section = {{ shape = "rectangle", width = 0.1, height = 0.2 }}
[[members]]
id = "BC"
nodes = ["B", "C"]
section = {{ shape = "rectangle", width = 0.1, height = 0.3 }}
{}
[[members]]
id = "CD"
nodes = ["C", "D"]
section = {{ shape = "rectangle", width = 0.1, height = 0.2 }}
[supports]
A = "clamped"
D = "{}"
[request]
modes = 8
)",
                     physics, kSteel, extra_member_bc, support_d);
}

}  // namespace modalbench::frame_tests
