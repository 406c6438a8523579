// `modalbench rom`: the reduced-order state-space model of a scene (modalbench/rom.hpp) as JSON.
#include "rom_command.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "modalbench/rom.hpp"

namespace mb = modalbench;

namespace {

/// "x" (beam) or "x,y" (plate), inside the body; InputError naming the option otherwise.
std::array<double, 2> parse_point(const mb::Scene& s, const std::string& text, const std::string& option) {
  if (s.is_frame())
    throw mb::InputError(s.source, "scene.kind",
                         "a reduced model of a frame is not available yet (its modes carry no shapes); beams and plates only");
  std::array<double, 2> p{0.0, 0.0};
  const char* c = text.c_str();
  char* end = nullptr;
  p[0] = std::strtod(c, &end);
  bool ok = end != c;
  if (ok && s.is_plate()) {
    ok = *end == ',';
    if (ok) {
      const char* y = end + 1;
      p[1] = std::strtod(y, &end);
      ok = end != y;
    }
  }
  ok = ok && *end == '\0' && std::isfinite(p[0]) && std::isfinite(p[1]);
  if (!ok)
    throw mb::InputError(
        "command line", option,
        fmt::format("'{}': expected {}", text, s.is_plate() ? "x,y (m) on the plate" : "x (m) on the beam"));
  if (p[0] < 0 || p[0] > s.geometry.length || (s.is_plate() && (p[1] < 0 || p[1] > s.geometry.width)))
    throw mb::InputError("command line", option,
                         fmt::format("'{}' lies outside the {}", text, s.is_plate() ? "plate" : "beam"));
  return p;
}

}  // namespace

int run_rom(const mb::Registry& reg, const mb::Scene& scene, const RomArgs& a) {
  const mb::Solver& solver = reg.get(a.backend);
  mb::RomRequest rq;
  for (const auto& t : a.inputs) rq.inputs.push_back(parse_point(scene, t, "--inputs"));
  for (const auto& t : a.outputs) rq.outputs.push_back(parse_point(scene, t, "--outputs"));
  rq.modes = a.modes;
  rq.zeta = a.zeta;
  rq.static_correction = !a.no_static_correction;
  const std::optional<mb::Discretization> mesh =
      a.mesh.empty() ? std::nullopt : std::optional<mb::Discretization>(mb::Discretization::parse(a.mesh));
  const mb::StateSpaceModel m = mb::export_rom(solver, scene, mesh, rq);
  const std::string doc = mb::to_json(m).dump(2);
  if (a.out.empty()) {
    std::cout << doc << "\n";
  } else {
    std::ofstream f(a.out);
    if (!f) throw mb::InputError("command line", "--out", "cannot write " + a.out);
    f << doc << "\n";
    std::cerr << fmt::format("wrote {}: {} states, {} inputs, {} outputs; {}\n", a.out, m.A.rows(), m.B.cols(),
                             m.C.rows(), m.note);
  }
  if (m.status != mb::Status::Success)
    std::cerr << "modalbench: rom: " << mb::to_string(m.status) << ": " << m.message << "\n";
  if (m.status == mb::Status::Success) return 0;
  return severity(m.status) >= severity(mb::Status::ResourceLimit) ? 2 : 3;
}
