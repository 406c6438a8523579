// What the process may use and has used: the memory limit, the peak resident size, the stack.
#include "solve_internal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

namespace modalbench {

double default_memory_limit() {
  double avail = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (!(avail > 0)) avail = 8.0 * (1ull << 30);
  // An address-space limit counts what the process has mapped already (libraries, thread stacks).
  double mapped = 0;
  {
    std::ifstream statm("/proc/self/statm");
    double pages = 0;
    if (statm >> pages) mapped = pages * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  }
  // Under an address-space limit, OpenBLAS's per-thread work buffers (128 MiB each, two threads)
  // are mapped on first use and count too.
  const double blas_buffers = 2.0 * 134225920.0;
  for (int which : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit rl{};
    if (getrlimit(which, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
      avail = std::min(avail, std::max(0.0, static_cast<double>(rl.rlim_cur) - mapped - blas_buffers));
  }
  return 0.8 * avail;
}

void reuse_freed_memory() {
  // glibc serves a block over its mmap threshold (128 KiB, raised as such blocks are freed, up to
  // 32 MiB) with a fresh mapping whose pages fault in on first touch, and returns a freed heap top
  // over twice that to the system: dtfm's segment matrices (2.4 MB each on 180 strips) were mapped
  // and faulted in afresh on every count, 9 % of a free plate's run (perf). Blocks under 64 MiB
  // now come from the heap, which keeps up to 256 MiB of freed memory for the next ones.
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

/// Maps the first pages of this thread's stack now. The main thread's stack grows on demand, and
/// under an address-space limit (ulimit -v) that growth fails once the heap has taken the rest:
/// the next deep call (Eigen keeps temporaries of up to 128 KB on the stack) is then a SIGSEGV
/// instead of a std::bad_alloc the solver can report. Linux never unmaps grown stack pages.
[[gnu::noinline]] void detail::map_stack_pages() {
  static thread_local bool done = false;
  if (done) return;
  done = true;
  rlimit rl{};
  std::size_t bytes = std::size_t(2) << 20;
  if (getrlimit(RLIMIT_STACK, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
    bytes = std::min<std::size_t>(bytes, static_cast<std::size_t>(rl.rlim_cur) / 4);
  volatile char* p = static_cast<volatile char*>(__builtin_alloca(bytes));
  for (std::size_t i = 0; i < bytes; i += 4096) p[i] = 0;
}

/// Peak resident memory of this process so far (VmHWM), bytes; NaN where unknown.
double detail::peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      double kb = 0;
      status >> kb;
      return kb * 1024.0;
    }
    status.ignore(1 << 12, '\n');
  }
  return kNotMeasured;
}

std::string detail::gigabytes(double bytes) { return fmt::format("{:.3g} GB", bytes / 1e9); }

}  // namespace modalbench
