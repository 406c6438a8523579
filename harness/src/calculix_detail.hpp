#pragma once
// Private to the CalculiX references (bricks: calculix.cpp; shells and beams: calculix_peers.cpp):
// running ccx on an input deck and reading its frequencies, shapes and mode families.

#include <array>
#include <functional>
#include <istream>
#include <string>
#include <vector>

#include "modalbench/harness/comparison.hpp"

namespace modalbench::calculix_detail {

/// Standard output and error of a shell command; `status` its exit status.
std::string run_command(const std::string& cmd, int& status);
/// The eigenvalue table and one displacement block per mode of a ccx .dat file.
void read_dat(std::istream& dat, int n_nodes, std::vector<double>& omega,
              std::vector<std::vector<std::array<double, 3>>>& shapes);
/// Families from the shares of motion per mode (beam: [axial, y, z, twist]; plate: [w, in-plane]):
/// a share above 0.6 names the mode; zero frequencies are rigid; nearly coincident pairs of a beam
/// dominated jointly by y and z are labelled xz and xy.
std::vector<ModeFamily> families_from_shares(const Scene& s, const std::vector<std::array<double, 4>>& share,
                                             const std::vector<double>& omega);
using SharesOf =
    std::function<std::vector<std::array<double, 4>>(const std::vector<std::vector<std::array<double, 3>>>&)>;
/// Writes `deck` as NAME.inp into `work_dir`, runs ccx on it (one thread, timed) and reads the
/// result into `rec` (backend, mesh and method set by the caller); failures come back marked. Once
/// read, the frequencies go to NAME.modes.csv and ccx's working files are removed, unless
/// `keep_work_files` (a failed run keeps them: its log says why).
RunRecord run_deck(const Scene& s, RunRecord rec, const std::string& name, const std::string& deck, int n_nodes,
                   const std::string& exe, const std::string& work_dir, const SharesOf& shares, bool keep_work_files);
/// A file-name-safe deck name: the scene's name and `suffix`.
std::string deck_name(const Scene& s, const std::string& suffix);

bool is_clamped(const Support& s);
bool is_simply_supported(const Support& s);

}  // namespace modalbench::calculix_detail
