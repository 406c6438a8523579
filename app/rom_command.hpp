#pragma once
// `modalbench rom SCENE --backend B --inputs X --outputs X [--modes N]`: the reduced-order model.
#include <string>
#include <vector>

#include "modalbench/registry.hpp"

struct RomArgs {
  std::string backend = "exact", mesh, out;
  std::vector<std::string> inputs, outputs;
  int modes = 12;
  double zeta = 0;
  bool no_static_correction = false;
};

/// Writes the model as JSON (stdout, or --out); the exit code as `solve`'s.
int run_rom(const modalbench::Registry& reg, const modalbench::Scene& scene, const RomArgs& a);
