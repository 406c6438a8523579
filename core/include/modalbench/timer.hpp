#pragma once
// Wall-clock lap timer for the per-phase timings a Result reports.

#include <chrono>

namespace modalbench {

struct Timer {
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  /// Seconds since construction or the previous lap; starts the next lap.
  double lap() {
    const auto t = std::chrono::steady_clock::now();
    const double d = std::chrono::duration<double>(t - t0).count();
    t0 = t;
    return d;
  }
};

}  // namespace modalbench
