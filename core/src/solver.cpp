#include "modalbench/solver.hpp"

// The interface's small types: statuses, the summary, mass models, mode families, mesh specs and
// families.
// The pipeline of Solver::solve is in solve_pipeline.cpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace modalbench {

std::string to_string(Status s) {
  switch (s) {
    case Status::Success: return "success";
    case Status::NotConverged: return "not-converged";
    case Status::NumericalIssue: return "numerical-issue";
    case Status::ResourceLimit: return "resource-limit";
    case Status::Unsupported: return "unsupported";
    case Status::InvalidInput: return "invalid-input";
  }
  return "?";
}

int severity(Status s) { return static_cast<int>(s); }

void Summary::raise(Status s, const std::string& text) {
  if (severity(s) > severity(status)) status = s;
  if (!text.empty()) message += (message.empty() ? "" : "; ") + text;
}

void Summary::set_diagnostic(const std::string& name, double value) {
  for (auto& [n, v] : diagnostics)
    if (n == name) {
      v = value;
      return;
    }
  diagnostics.emplace_back(name, value);
}

double Summary::diagnostic(const std::string& name) const {
  for (const auto& [n, v] : diagnostics)
    if (n == name) return v;
  return kNotMeasured;
}

void Summary::note_backward_error(double e) {
  if (std::isnan(e)) return;
  max_backward_error = std::isnan(max_backward_error) ? e : std::max(max_backward_error, e);
}

void note_frf_omissions(Summary& sum, int skipped, int points, const std::string& reason) {
  if (skipped <= 0) return;
  // One or two samples on a natural frequency are the request's bad luck; all of them is no FRF.
  if (skipped <= 2 && skipped < points) {
    sum.warnings.push_back(fmt::format("FRF: {} of {} sample(s) omitted (singular dynamic stiffness: on or within "
                                       "rounding of a natural frequency; {})", skipped, points, reason));
    return;
  }
  sum.raise(Status::NumericalIssue, fmt::format("FRF: {} of {} samples could not be computed ({})", skipped, points, reason));
}

std::string to_string(MassModel m) { return m == MassModel::Consistent ? "consistent" : "lumped"; }

MassModel parse_mass_model(const std::string& text, const std::string& source, const std::string& key) {
  if (text == "consistent") return MassModel::Consistent;
  if (text == "lumped") return MassModel::Lumped;
  throw InputError(source, key, "must be consistent or lumped (got '" + text + "')");
}

std::string to_string(Whirl w) {
  switch (w) {
    case Whirl::Forward: return "forward";
    case Whirl::Backward: return "backward";
    case Whirl::Mixed: return "mixed";
    case Whirl::Planar: return "planar";
    case Whirl::None: return "none";
  }
  return "?";
}

std::string to_string(ModeFamily f) {
  switch (f) {
    case ModeFamily::BendingXZ: return "bending-xz";
    case ModeFamily::BendingXY: return "bending-xy";
    case ModeFamily::Axial: return "axial";
    case ModeFamily::Torsion: return "torsion";
    case ModeFamily::Plate: return "plate";
    case ModeFamily::Rigid: return "rigid";
    case ModeFamily::Unknown: return "unknown";
  }
  return "unknown";
}

std::string Discretization::spec() const {
  if (counts.empty()) return "-";
  std::string s;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    if (i) s += 'x';
    s += std::to_string(counts[i]);
  }
  return s;
}

std::optional<CoarserMesh> MeshFamily::coarser_than(const Discretization& mesh) const {
  return coarser ? coarser(mesh) : std::nullopt;
}

std::optional<Discretization> MeshFamily::finer_than(const Discretization& mesh, double factor) const {
  return finer ? finer(mesh, factor) : std::nullopt;
}

MeshFamily MeshFamily::single(const Discretization& mesh) {
  MeshFamily f;
  f.default_mesh = mesh;
  f.ladder = {mesh};
  f.theory = mesh;
  f.stress = {mesh};
  return f;
}

Discretization Discretization::parse(const std::string& spec) {
  Discretization d;
  if (spec.empty() || spec == "-") return d;
  std::size_t pos = 0;
  while (pos <= spec.size()) {
    std::size_t end = spec.find('x', pos);
    if (end == std::string::npos) end = spec.size();
    const std::string part = spec.substr(pos, end - pos);
    if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos || part.size() > 9)
      throw InputError("command line", "--mesh",
                       "'" + spec + "' is not a mesh: expected positive integers joined by 'x' (e.g. 64, 100x60)");
    const int n = std::stoi(part);
    if (n <= 0) throw InputError("command line", "--mesh", "mesh counts must be >= 1 (got '" + spec + "')");
    d.counts.push_back(n);
    pos = end + 1;
  }
  return d;
}

}  // namespace modalbench
