#pragma once
// The exact back-end's plate responses: statics (deflections, moments, edge reactions) and FRF of
// the simply supported Kirchhoff plate by its Navier and Levy series (plate_responses.cpp).
#include "modalbench/result.hpp"
#include "modalbench/scene.hpp"

namespace modalbench::exact::detail {

/// Deflections and moments at the probes (Navier, m, n <= terms; the tails checked against the
/// scene's tolerance) and the edge reactions (navier_reactions).
void navier_statics(const Scene& s, int terms, Result& r);
/// The receptance at the scene's FRF samples (Navier, m, n <= terms; the tail checked against the
/// static flexibility of the same pair).
void navier_frf(const Scene& s, int terms, Result& r);

}  // namespace modalbench::exact::detail
