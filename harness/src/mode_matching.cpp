#include "modalbench/harness/mode_matching.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace modalbench {

std::vector<int> match_modes(const std::vector<ModeFamily>& reference, const std::vector<ModeFamily>& run) {
  std::map<ModeFamily, std::vector<int>> by_family;
  std::vector<int> elastic;
  bool labelled = false;
  for (int j = 0; j < static_cast<int>(run.size()); ++j) {
    if (run[j] == ModeFamily::Rigid) continue;
    by_family[run[j]].push_back(j);
    elastic.push_back(j);
    labelled = labelled || run[j] != ModeFamily::Unknown;
  }
  std::map<ModeFamily, std::size_t> used;
  std::size_t used_elastic = 0;
  std::vector<int> out(reference.size(), -1);
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const ModeFamily f = reference[i];
    if (f == ModeFamily::Rigid) continue;
    if (!labelled) {
      if (used_elastic < elastic.size()) out[i] = elastic[used_elastic++];
      continue;
    }
    auto& list = by_family[f];
    std::size_t& u = used[f];
    if (u < list.size()) out[i] = list[u++];
  }
  return out;
}

namespace {

std::vector<double> mac_vector(const ModeShapes& s, std::size_t mode, double twist_length) {
  std::vector<double> v;
  for (std::size_t c = 0; c < s.components.size(); ++c) {
    const int d = s.components[c];
    if (d > 3 || (d == 3 && twist_length == 0.0)) continue;
    const double f = d == 3 ? twist_length : 1.0;
    for (double x : s.values[mode][c]) v.push_back(f * x);
  }
  return v;
}

}  // namespace

double mac(const ModeShapes& a, std::size_t i, const ModeShapes& b, std::size_t j, double twist_length) {
  if (a.points != b.points || a.components != b.components) return std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> x = mac_vector(a, i, twist_length), y = mac_vector(b, j, twist_length);
  double xy = 0, xx = 0, yy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    xy += x[k] * y[k];
    xx += x[k] * x[k];
    yy += y[k] * y[k];
  }
  if (!(xx > 0 && yy > 0)) return std::numeric_limits<double>::quiet_NaN();
  return xy * xy / (xx * yy);
}

std::vector<std::vector<double>> mac_matrix(const ModeShapes& reference, const ModeShapes& run, double twist_length) {
  std::vector<std::vector<double>> m(reference.values.size(), std::vector<double>(run.values.size()));
  for (std::size_t i = 0; i < reference.values.size(); ++i)
    for (std::size_t j = 0; j < run.values.size(); ++j) m[i][j] = mac(reference, i, run, j, twist_length);
  return m;
}

std::vector<int> match_modes_by_mac(const std::vector<ModeFamily>& reference, const std::vector<ModeFamily>& run,
                                    const std::vector<std::vector<double>>& mac_m) {
  struct Candidate {
    double mac;
    std::size_t i, j;
  };
  std::vector<Candidate> cand;
  for (std::size_t i = 0; i < reference.size() && i < mac_m.size(); ++i) {
    if (reference[i] == ModeFamily::Rigid) continue;
    for (std::size_t j = 0; j < run.size() && j < mac_m[i].size(); ++j) {
      if (run[j] == ModeFamily::Rigid || std::isnan(mac_m[i][j])) continue;
      const bool compatible =
          reference[i] == run[j] || reference[i] == ModeFamily::Unknown || run[j] == ModeFamily::Unknown;
      if (compatible) cand.push_back({mac_m[i][j], i, j});
    }
  }
  // Descending MAC; ties keep the order of the modes (stable).
  std::stable_sort(cand.begin(), cand.end(), [](const Candidate& a, const Candidate& b) { return a.mac > b.mac; });
  std::vector<int> out(reference.size(), -1);
  std::vector<char> used(run.size(), 0);
  for (const auto& c : cand)
    if (out[c.i] < 0 && !used[c.j]) {
      out[c.i] = static_cast<int>(c.j);
      used[c.j] = 1;
    }
  return out;
}

}  // namespace modalbench
