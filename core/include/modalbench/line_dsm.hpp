#pragma once
// Transitional umbrella (removed once every includer names the kernel it uses).
#include "modalbench/numerics/balancing.hpp"
#include "modalbench/numerics/block_tridiagonal.hpp"
#include "modalbench/numerics/complex_block_tridiagonal.hpp"
#include "modalbench/numerics/line_system.hpp"
#include "modalbench/numerics/segment_dynamic_stiffness.hpp"
#include "modalbench/numerics/spectrum_slicing.hpp"
#include "modalbench/numerics/symmetric_factor.hpp"
