#pragma once
// Internal to rfem: the kernels of one model (rfem_kernels.cpp), what RfemSolver::build returns.
#include <memory>

#include "modalbench/kernels.hpp"
#include "modalbench/rfem/model.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::rfem::detail {

/// The kernels of `model` (built for `s` on `mesh`; assembled here) and what the model is, into
/// r.summary (model, method, unknowns, coordinates). Throws InputError where the supports hold
/// every coordinate of the mesh.
std::unique_ptr<Kernels> make_kernels(const Scene& s, const Discretization& mesh, const Options& options, Model model,
                                      Result& r);

}  // namespace modalbench::rfem::detail
