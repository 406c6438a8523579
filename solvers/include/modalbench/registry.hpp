#pragma once
// The one place that names every back-end.

#include "modalbench/solver.hpp"

namespace modalbench {

/// A registry holding `exact` and every back-end built into this modalbench.
Registry make_default_registry();

}  // namespace modalbench
