#include "modalbench/registry.hpp"

#ifdef MODALBENCH_HAVE_EXACT
#include "modalbench/exact/exact.hpp"
#endif
#ifdef MODALBENCH_HAVE_RFEM
#include "modalbench/rfem/rfem.hpp"
#endif
#ifdef MODALBENCH_HAVE_DIFFERENCE_EQ
#include "modalbench/difference_eq/difference_eq.hpp"
#endif
#ifdef MODALBENCH_HAVE_DTFM
#include "modalbench/dtfm/dtfm.hpp"
#endif

namespace modalbench {

Registry make_default_registry() {
  Registry r;
#ifdef MODALBENCH_HAVE_EXACT
  r.add(std::make_unique<exact::ExactSolver>());
#endif
#ifdef MODALBENCH_HAVE_RFEM
  r.add(std::make_unique<rfem::RfemSolver>());
#endif
#ifdef MODALBENCH_HAVE_DIFFERENCE_EQ
  r.add(std::make_unique<difference_eq::DifferenceEqSolver>());
#endif
#ifdef MODALBENCH_HAVE_DTFM
  r.add(std::make_unique<dtfm::DtfmSolver>());
#endif
  return r;
}

}  // namespace modalbench
