// Which values a result reports as its answer: the mesh's own, or, on the default path, the
// Richardson extrapolation's where its own estimate meets the tolerance and the mesh's does not
// (solve_internal.hpp).
#include <algorithm>
#include <string_view>
#include <vector>

#include "solve_internal.hpp"

namespace modalbench::detail {

namespace {
bool meets(double estimate, double tolerance) { return estimate <= tolerance; }  // NaN: not estimated, no

/// The extrapolated modes in ascending order of their values (stable). Two modes of nearly one
/// frequency (a square plate's pair) can come out of the extrapolation in either order, each within
/// its estimate of the other; the result lists frequencies ascending.
std::vector<std::size_t> ascending(const std::vector<double>& f) {
  std::vector<std::size_t> order(f.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return f[a] < f[b]; });
  return order;
}

/// Whether putting the extrapolated values in ascending order keeps every mode's family (the
/// result's labels, shapes and participations stay the mesh's, by index).
bool order_keeps_families(const Result& fine, const Extrapolation& x) {
  const std::vector<std::size_t> order = ascending(x.frequencies_rad_s);
  for (std::size_t i = 0; i < order.size(); ++i)
    if (i < fine.mode_families.size() && order[i] < fine.mode_families.size() &&
        fine.mode_families[i] != fine.mode_families[order[i]])
      return false;
  return true;
}
}  // namespace

bool gives_forces(const Result& r) {
  return std::any_of(r.deflections.begin(), r.deflections.end(), [](const Deflection& d) { return d.has_forces; });
}

ReportedValues extrapolated_answers(const Scene& scene, const Result& fine, const Extrapolation& x,
                                    const ErrorEstimate& e) {
  ReportedValues v;
  const double tol = scene.request.tolerance;
  if (scene.request.modes > 0 && !fine.frequencies_rad_s.empty() && !meets(e.frequencies, tol))
    v.frequencies = x.frequencies_rad_s.size() == fine.frequencies_rad_s.size() && meets(x.frequency_error, tol) &&
                    order_keeps_families(fine, x);
  // Stress resultants are judged with the deflections (ErrorEstimate::deflections) but not
  // extrapolated: where the result gives them, the deflections stay the mesh's.
  if (!scene.request.probes.empty() && !fine.deflections.empty() && !meets(e.deflections, tol) && !gives_forces(fine))
    v.deflections = x.deflections.size() == fine.deflections.size() && meets(x.deflection_error, tol);
  return v;
}

std::vector<std::string> problems_left(const std::vector<std::string>& problems, const ReportedValues& v) {
  std::vector<std::string> out;
  for (const std::string& p : problems) {
    const std::string_view s(p);
    if (v.frequencies && s.starts_with("frequencies:")) continue;
    if (v.deflections && s.starts_with("deflections:")) continue;
    out.push_back(p);
  }
  return out;
}

void report_extrapolated(Result& r, const ReportedValues& v) {
  Extrapolation& x = r.extrapolated;
  if (v.frequencies) {
    x.mesh_frequencies_rad_s = r.frequencies_rad_s;
    const std::vector<std::size_t> order = ascending(x.frequencies_rad_s);
    std::vector<double> f, e;
    for (std::size_t i : order) {
      f.push_back(x.frequencies_rad_s[i]);
      if (i < x.frequency_errors.size()) e.push_back(x.frequency_errors[i]);
    }
    x.frequencies_rad_s = f;
    if (e.size() == f.size()) x.frequency_errors = e;
    r.frequencies_rad_s = std::move(f);
    x.frequencies_reported = true;
  }
  if (v.deflections) {
    x.mesh_deflections = r.deflections;
    r.deflections = x.deflections;
    x.deflections_reported = true;
  }
}

}  // namespace modalbench::detail
