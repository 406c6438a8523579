#include "modalbench/harness/mode_matching.hpp"

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

}  // namespace modalbench
