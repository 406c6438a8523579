// The registry: the only place that holds every back-end, by name.
#include "modalbench/solver.hpp"

#include <stdexcept>

namespace modalbench {

void Registry::add(std::unique_ptr<Solver> solver) {
  const std::string n = solver->name();
  for (auto& s : solvers_)
    if (s->name() == n) throw std::invalid_argument("solver '" + n + "' registered twice");
  solvers_.push_back(std::move(solver));
}

const Solver& Registry::get(const std::string& name) const {
  for (auto& s : solvers_)
    if (s->name() == name) return *s;
  std::string known;
  for (auto& s : solvers_) {
    if (!known.empty()) known += ", ";
    known += s->name();
  }
  throw std::invalid_argument("unknown back-end '" + name + "' (known: " + known + ")");
}

std::vector<const Solver*> Registry::all() const {
  std::vector<const Solver*> v;
  for (auto& s : solvers_) v.push_back(s.get());
  return v;
}

void Registry::check_backend_tables(const Scene& scene) const {
  for (const auto& [name, opts] : scene.backend_options) {
    bool known = false;
    for (const auto& sv : solvers_) known = known || sv->name() == name;
    if (!known) {
      std::string list;
      for (const auto& sv : solvers_) list += (list.empty() ? "" : ", ") + sv->name();
      throw InputError(scene.source, "backend." + name, "no such back-end (known: " + list + ")");
    }
  }
}

std::vector<std::string> Registry::names() const {
  std::vector<std::string> v;
  for (auto& s : solvers_) v.push_back(s->name());
  return v;
}

}  // namespace modalbench
