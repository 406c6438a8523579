#include "modalbench/registry.hpp"

#include "modalbench/exact.hpp"

namespace modalbench {

Registry make_default_registry() {
  Registry r;
  r.add(std::make_unique<exact::ExactSolver>());
  return r;
}

}  // namespace modalbench
