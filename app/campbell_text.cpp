#include "campbell_text.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <string>

namespace mb = modalbench;

namespace {

std::string list(const std::vector<double>& v) {
  if (v.empty()) return "none";
  std::string out;
  for (double x : v) out += (out.empty() ? "" : ", ") + fmt::format("{:.8g}", x);
  return out + " rad/s";
}

char sense(mb::Whirl w) {
  switch (w) {
    case mb::Whirl::Forward: return 'F';
    case mb::Whirl::Backward: return 'B';
    case mb::Whirl::Mixed: return 'M';
    case mb::Whirl::Planar: return 'P';
    case mb::Whirl::None: return '0';
  }
  return '?';
}

}  // namespace

void print_campbell(const mb::Campbell& c, bool verbose) {
  std::cout << fmt::format("  Campbell diagram ({} frame), {} spin speeds; whirl F forward, B backward, M mixed, P planar, 0 none\n", c.frame,
                           c.points.size());
  std::cout << fmt::format("  critical speeds: forward {}; backward {}\n", list(c.forward_criticals),
                           list(c.backward_criticals));
  if (!c.criticals_note.empty() && verbose) std::cout << "  critical speeds: " << c.criticals_note << "\n";
  for (const mb::CampbellPoint& p : c.points) {
    std::string line = fmt::format("  spin {:>12.6g} rad/s:", p.spin_rad_s);
    for (std::size_t i = 0; i < p.frequencies_rad_s.size(); ++i) {
      line += fmt::format(" {:.8g} {}", p.frequencies_rad_s[i], sense(p.whirl[i]));
      if (p.growth_rates_1_s[i] != 0) line += fmt::format(" (growth {:+.3g} 1/s)", p.growth_rates_1_s[i]);
      line += i + 1 < p.frequencies_rad_s.size() ? "," : "";
    }
    std::cout << line << "\n";
  }
  if (!c.unstable_spins.empty()) std::cout << "  unstable at spins: " << list(c.unstable_spins) << "\n";
  if (verbose && !c.note.empty()) std::cout << "  campbell: " << c.note << "\n";
  if (!c.orbit_points_m.empty())
    std::cout << fmt::format("  orbits: every root's v, w at {} points (--json){}\n", c.orbit_points_m.size(),
                             verbose ? "; " + c.orbit_note : "");
  else if (!c.orbit_note.empty())
    std::cout << "  orbits: " << c.orbit_note << "\n";
}
