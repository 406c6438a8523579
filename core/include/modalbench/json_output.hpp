#pragma once
// The JSON form of one solve (`modalbench solve --json`); schema in README.md.

#include <nlohmann/json.hpp>
#include <string>

#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"
#include "modalbench/solver.hpp"

namespace modalbench {

nlohmann::json to_json(const Scene& scene, const std::string& backend, const Discretization& mesh,
                       const Result& result);

}  // namespace modalbench
