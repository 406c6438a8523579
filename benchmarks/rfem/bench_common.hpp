#pragma once
// Timing helpers for the rfem benchmarks: median wall time of repeats after a warm-up, CPU time,
// and the peak resident memory of a child process that runs one configuration alone.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <functional>
#include <vector>

namespace rfem_bench {

struct Timing {
  double median_s = 0, min_s = 0, cpu_median_s = 0;
  int repeats = 0;
};

/// One warm-up call, then `repeats` timed calls; wall and process CPU medians.
inline Timing time_it(const std::function<void()>& f, int repeats) {
  f();
  std::vector<double> wall, cpu;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    f();
    cpu.push_back(static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  return {wall[wall.size() / 2], wall.front(), cpu[cpu.size() / 2], repeats};
}

/// Peak resident set of this process so far, MB.
inline double peak_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

/// Runs `f` in a child process (so its peak memory is its own) and waits for it.
inline void in_child(const std::function<void()>& f) {
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0) {
    f();
    std::fflush(stdout);
    _exit(0);
  }
  int status = 0;
  waitpid(pid, &status, 0);
}

}  // namespace rfem_bench
