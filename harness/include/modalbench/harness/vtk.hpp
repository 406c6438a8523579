#pragma once
// ParaView export: a result's mode shapes (and static deflections at the probes) as VTK XML
// unstructured grids (.vtu, ASCII), which ParaView opens directly ("Warp By Vector" shows a mode).

#include <string>
#include <vector>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench {

/// Writes `dir`/<scene>_<backend>_modes.vtu (the sample points, joined as a polyline for a beam or
/// quads for a plate; per mode one 3-component point array "mode K (omega rad/s, f Hz)" with
/// (u, v, w), and one per rotation component) and, with deflections, <scene>_<backend>_statics.vtu
/// (the probes as vertices; arrays displacement and rotation). Returns the paths written. Throws
/// std::runtime_error naming the path on a write failure; std::invalid_argument without shapes
/// or deflections.
std::vector<std::string> write_vtk(const Scene& scene, const std::string& backend, const Result& result,
                                   const std::string& dir);

}  // namespace modalbench
