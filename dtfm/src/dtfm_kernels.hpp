#pragma once
// Internal to dtfm: the kernels of one prism model (dtfm_kernels.cpp), what DtfmSolver::build returns.
#include <memory>

#include "modalbench/dtfm/prism_model.hpp"
#include "modalbench/kernels.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::dtfm {

/// The prism model of `scene` on `mesh` (the back-end options over `base`), its line analysis and
/// kernels, and what the model is, into r.summary (model, method, fields).
std::unique_ptr<Kernels> make_kernels(const Scene& scene, const Discretization& mesh, const Options& options,
                                      const ModelOptions& base, Result& r);

}  // namespace modalbench::dtfm
