#pragma once
// Internal to difference_eq: the kernels of one regular chain (difference_eq_kernels.cpp), what
// DifferenceEqSolver::build returns.
#include <memory>

#include "modalbench/kernels.hpp"
#include "modalbench/solver.hpp"

namespace modalbench::difference_eq {

/// The regular beam of `s` on R elements, its loads on nodes (InputError for one off them) and
/// attachments, with its kernels; what the model is into res.summary (model, method, unknowns,
/// what it does not model).
std::unique_ptr<Kernels> make_kernels(const Scene& s, long R, const Options& options, Result& res);

}  // namespace modalbench::difference_eq
