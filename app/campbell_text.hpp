#pragma once
// The text output of a rotor scene's Campbell diagram (`modalbench solve`).
#include "modalbench/result.hpp"

/// Prints the critical speeds and, per spin, the whirl frequencies with their senses (growth rates
/// where a root is not neutral).
void print_campbell(const modalbench::Campbell& c, bool verbose);
