#include "modalbench/harness/calculix.hpp"

#include "modalbench/harness/files.hpp"
#include "calculix_detail.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

namespace modalbench {

namespace fs = std::filesystem;

namespace calculix_detail {

std::string run_command(const std::string& cmd, int& status) {
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) {
    status = -1;
    return "";
  }
  std::string out;
  std::array<char, 512> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  status = pclose(p);
  return out;
}

namespace {

/// Fortran prints exponents of three digits without the 'E' ("-4.313991-160"): put it back.
double fortran_double(std::string t) {
  for (std::size_t i = t.size(); i-- > 1;)
    if ((t[i] == '-' || t[i] == '+') && std::isdigit(static_cast<unsigned char>(t[i - 1]))) {
      t.insert(i, 1, 'E');
      break;
    }
  std::size_t used = 0;
  const double v = std::stod(t, &used);
  if (used != t.size()) throw std::invalid_argument("not a number: " + t);
  return v;
}

/// Splits a line into whitespace-separated numbers; false if any token is not one.
bool numbers(const std::string& line, std::vector<double>& out) {
  out.clear();
  std::istringstream ls(line);
  std::string tok;
  while (ls >> tok) {
    try {
      out.push_back(fortran_double(tok));
    } catch (const std::exception&) {
      return false;
    }
  }
  return true;
}

}  // namespace

/// Reads the eigenvalue table and one displacement block per mode from a ccx .dat file.
void read_dat(std::istream& dat, int n_nodes, std::vector<double>& omega,
              std::vector<std::vector<std::array<double, 3>>>& shapes) {
  std::string line;
  bool in_table = false;
  while (std::getline(dat, line)) {
    if (line.find("E I G E N V A L U E   O U T P U T") != std::string::npos) {
      in_table = true;
      continue;
    }
    if (line.find("P A R T I C I P A T I O N") != std::string::npos) in_table = false;
    std::vector<double> v;
    if (in_table) {
      if (numbers(line, v) && v.size() == 5) omega.push_back(v[2]);
      continue;
    }
    if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
      shapes.emplace_back(n_nodes, std::array<double, 3>{0, 0, 0});
      continue;
    }
    if (!shapes.empty() && numbers(line, v) && v.size() == 4) {
      const int node = static_cast<int>(v[0]);
      if (node >= 1 && node <= n_nodes) shapes.back()[node - 1] = {v[1], v[2], v[3]};
    }
  }
}

std::vector<ModeFamily> families_from_shares(const Scene& s, const std::vector<std::array<double, 4>>& share,
                                             const std::vector<double>& omega) {
  const std::size_t nm = share.size();
  std::vector<ModeFamily> fam(nm, ModeFamily::Unknown);
  // ccx prints the rigid-body modes of an unsupported solid as zero or rounding noise (S8R shells:
  // 2e-5 of the 22nd elastic frequency of the free plate FV12).
  const double top = omega.empty() ? 0.0 : *std::max_element(omega.begin(), omega.end());
  for (std::size_t m = 0; m < nm; ++m) {
    if (std::abs(omega[m]) <= 1e-4 * top) {
      fam[m] = ModeFamily::Rigid;
      continue;
    }
    if (s.is_plate()) {
      fam[m] = share[m][0] > 0.6 ? ModeFamily::Plate : ModeFamily::Unknown;
      continue;
    }
    const auto& sh = share[m];
    if (sh[0] > 0.6) fam[m] = ModeFamily::Axial;
    else if (sh[1] > 0.6) fam[m] = ModeFamily::BendingXY;
    else if (sh[2] > 0.6) fam[m] = ModeFamily::BendingXZ;
    else if (sh[3] > 0.6) fam[m] = ModeFamily::Torsion;
  }
  if (s.is_beam())
    for (std::size_t m = 0; m + 1 < nm; ++m) {
      if (std::abs(omega[m + 1] / omega[m] - 1) > 1e-5) continue;
      const double yz = share[m][1] + share[m][2] + share[m + 1][1] + share[m + 1][2];
      if ((fam[m] == ModeFamily::Unknown || fam[m + 1] == ModeFamily::Unknown) && yz > 1.6) {
        const bool first_is_z = share[m][2] >= share[m + 1][2];
        fam[m] = first_is_z ? ModeFamily::BendingXZ : ModeFamily::BendingXY;
        fam[m + 1] = first_is_z ? ModeFamily::BendingXY : ModeFamily::BendingXZ;
      }
    }
  return fam;
}

/// What one ccx run read: NAME.modes.csv beside its deck, so that the work folder keeps the input
/// and the numbers taken from it.
void write_modes_csv(const std::string& work_dir, const std::string& name, const Result& r) {
  std::string csv = "mode,omega_rad_s,frequency_hz,family\n";
  for (std::size_t m = 0; m < r.frequencies_rad_s.size(); ++m)
    csv += fmt::format("{},{:.17g},{:.17g},{}\n", m + 1, r.frequencies_rad_s[m], r.frequencies_rad_s[m] / (2 * M_PI),
                       to_string(r.mode_families[m]));
  write_text_file((fs::path(work_dir) / (name + ".modes.csv")).string(), csv);
}

/// Removes ccx's working files of a run read successfully (everything of NAME but the deck and the
/// modes read; spooles.out, the solver's own log, too).
void remove_work_files(const std::string& work_dir, const std::string& name) {
  std::error_code ec;
  for (const char* ext : {".dat", ".frd", ".sta", ".cvg", ".12d", ".log"})
    fs::remove(fs::path(work_dir) / (name + ext), ec);
  fs::remove(fs::path(work_dir) / "spooles.out", ec);
}

RunRecord run_deck(const Scene& s, RunRecord rec, const std::string& name, const std::string& deck, int n_nodes,
                   const std::string& exe, const std::string& work_dir, const SharesOf& shares, bool keep_work_files) {
  rec.repeats = 1;
  Result& r = rec.result;
  make_output_dir(work_dir);
  write_text_file((fs::path(work_dir) / (name + ".inp")).string(), deck);
  const auto t0 = std::chrono::steady_clock::now();
  int st = 0;
  const std::string log =
      run_command(fmt::format("cd '{}' && OMP_NUM_THREADS=1 '{}' -i '{}' > '{}.log'", work_dir, exe, name, name), st);
  rec.median_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.summary.total_time_s = rec.median_s;
  r.summary.timings_s.modes = rec.median_s;  // one ccx run computes the modes only
  rec.time_s.modes = rec.median_s;
  rec.spent_s = rec.median_s;
  std::ifstream dat(fs::path(work_dir) / (name + ".dat"));
  if (st != 0 || !dat) {
    r.summary.raise(Status::NumericalIssue, fmt::format("ccx failed (status {}); see {}/{}.log", st, work_dir, name));
    return rec;
  }
  std::vector<double> omega;
  std::vector<std::vector<std::array<double, 3>>> shapes;
  read_dat(dat, n_nodes, omega, shapes);
  if (omega.empty() || shapes.size() != omega.size()) {
    r.summary.raise(Status::NumericalIssue, fmt::format("could not read {} frequencies and shapes from {}.dat", omega.size(), name));
    return rec;
  }
  r.mode_families = families_from_shares(s, shares(shapes), omega);
  r.frequencies_rad_s = omega;
  r.summary.set_diagnostic("ccx_modes_read", static_cast<double>(omega.size()));
  dat.close();
  write_modes_csv(work_dir, name, r);
  if (!keep_work_files) remove_work_files(work_dir, name);
  return rec;
}

std::string deck_name(const Scene& s, const std::string& suffix) {
  std::string name;
  for (char c : s.name) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return name + "_" + suffix;
}

bool is_clamped(const Support& s) { return std::isinf(s.translational) && std::isinf(s.rotational); }
bool is_simply_supported(const Support& s) { return std::isinf(s.translational) && s.rotational == 0.0; }

}  // namespace calculix_detail

namespace {

using namespace calculix_detail;

/// Structured 20-node brick mesh of a box; node ids on the doubled grid (0 = no node there).
struct Grid {
  int nx, ny, nz;
  std::vector<int> id;
  std::vector<std::array<double, 3>> xyz;  // by id - 1
  std::vector<std::array<int, 3>> ijk;     // by id - 1
  int at(int i, int j, int k) const { return id[(static_cast<std::size_t>(k) * (2 * ny + 1) + j) * (2 * nx + 1) + i]; }
};

Grid make_grid(const Scene& s, const SolidMesh& m) {
  Grid g{m.nx, m.ny, m.nz, {}, {}, {}};
  g.id.assign(static_cast<std::size_t>(2 * m.nx + 1) * (2 * m.ny + 1) * (2 * m.nz + 1), 0);
  const double L = s.geometry.length, B = s.geometry.width, H = s.geometry.height;
  const double y0 = s.is_beam() ? -0.5 * B : 0.0;
  int next = 1;
  for (int k = 0; k <= 2 * m.nz; ++k)
    for (int j = 0; j <= 2 * m.ny; ++j)
      for (int i = 0; i <= 2 * m.nx; ++i) {
        if ((i % 2) + (j % 2) + (k % 2) > 1) continue;  // face or body centre: not a node of C3D20
        g.id[(static_cast<std::size_t>(k) * (2 * m.ny + 1) + j) * (2 * m.nx + 1) + i] = next++;
        g.xyz.push_back({L * i / (2.0 * m.nx), y0 + B * j / (2.0 * m.ny), -0.5 * H + H * k / (2.0 * m.nz)});
        g.ijk.push_back({i, j, k});
      }
  return g;
}

/// Per mode the shares of the motion that name its family (bricks): beam [axial, y, z, twist]
/// from each x-slice's section-mean translations and twist; plate [w, in-plane] on the mid-plane.
std::vector<std::array<double, 4>> brick_shares(const Scene& s, const Grid& g,
                                                const std::vector<std::vector<std::array<double, 3>>>& shapes) {
  const std::size_t nm = shapes.size();
  std::vector<std::array<double, 4>> share(nm, {0, 0, 0, 0});
  for (std::size_t m = 0; m < nm; ++m) {
    const auto& u = shapes[m];
    std::array<double, 4> e{0, 0, 0, 0};
    if (s.is_beam()) {
      std::map<int, std::array<double, 7>> slice;  // n, sum ux, uy, uz, sum(y uz - z uy), sum(y^2+z^2), dummy
      for (std::size_t n = 0; n < u.size(); ++n) {
        auto& sl = slice[g.ijk[n][0]];
        const double y = g.xyz[n][1], z = g.xyz[n][2];
        sl[0] += 1;
        sl[1] += u[n][0];
        sl[2] += u[n][1];
        sl[3] += u[n][2];
        sl[4] += y * u[n][2] - z * u[n][1];
        sl[5] += y * y + z * z;
      }
      for (auto& [i, sl] : slice) {
        const double cnt = sl[0];
        e[0] += std::pow(sl[1] / cnt, 2);
        e[1] += std::pow(sl[2] / cnt, 2);
        e[2] += std::pow(sl[3] / cnt, 2);
        if (sl[5] > 0) e[3] += std::pow(sl[4] / sl[5], 2) * (sl[5] / cnt);
      }
    } else {
      for (std::size_t n = 0; n < u.size(); ++n) {
        if (g.ijk[n][2] != g.nz) continue;  // mid-plane nodes
        e[0] += u[n][2] * u[n][2];
        e[1] += u[n][0] * u[n][0] + u[n][1] * u[n][1];
      }
    }
    const double tot = e[0] + e[1] + e[2] + e[3];
    for (int q = 0; q < 4; ++q) share[m][q] = tot > 0 ? e[q] / tot : 0.0;
  }
  return share;
}

}  // namespace

std::string calculix_version(const std::string& exe) {
  int st = 0;
  const std::string out = run_command(exe + " -v", st);
  const auto pos = out.find("Version");
  if (pos == std::string::npos) return "";
  auto end = out.find('\n', pos);
  return "CalculiX " + out.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
}

std::string calculix_unsupported_reason(const Scene& s) {
  if (s.is_frame()) return "the 3D reference is written for one beam or plate, not for frames";
  if (s.is_beam()) {
    if (s.cross_section.shape != SectionShape::Rectangle)
      return "the 3D reference meshes rectangular sections only (got a " + to_string(s.cross_section.shape) + ")";
    if (s.is_stepped() || s.has_tapered_pieces())
      return "the 3D reference meshes uniform beams only (no [[segments]])";
    if (!s.point_supports.empty() || !s.masses.empty())
      return "the 3D reference has no supports between the ends or point masses";
    for (const Support* e : {&s.x0, &s.xL})
      if (!(e->kind == "clamped" || e->kind == "free"))
        return "the 3D reference models beam ends clamped or free only (got '" + e->kind + "')";
    return "";
  }
  if (!s.point_supports.empty() || !s.masses.empty())
    return "the 3D reference has no supports or masses at points of a plate";
  for (const Support* e : {&s.x0, &s.xL, &s.y0, &s.yB})
    if (!(is_clamped(*e) || is_simply_supported(*e) || e->is_free()))
      return "the 3D reference models plate edges simply supported, clamped or free only";
  return "";
}

std::vector<SolidMesh> calculix_ladder(const Scene& s) {
  if (s.is_beam()) {
    // Elements across the section nyz, along the beam proportional to the aspect ratio.
    const double ar = s.geometry.length / std::max(s.geometry.width, s.geometry.height);
    std::vector<SolidMesh> l;
    for (int n : {2, 4, 6, 8, 12}) {
      const int nl = std::max(2, static_cast<int>(std::lround(n * ar * 1.25)));
      l.push_back({nl, n, n});
    }
    return l;
  }
  const double ar = s.geometry.length / s.geometry.width;
  std::vector<SolidMesh> l;
  for (int n : {3, 6, 12, 18, 30}) l.push_back({std::max(2, static_cast<int>(std::lround(n * ar))), n, n < 12 ? 1 : 2});
  return l;
}

namespace {

/// The 20-node brick model of the scene as a CalculiX input deck; `held` counts the restrained DOFs.
std::string brick_input(const Scene& s, const SolidMesh& m, const Grid& g, long& held) {
  const int n_nodes = static_cast<int>(g.xyz.size());
  std::ostringstream inp;
  inp << "** modalbench: " << s.name << " (" << s.source << ")\n*NODE, NSET=NALL\n";
  for (int n = 0; n < n_nodes; ++n) inp << fmt::format("{}, {:.12g}, {:.12g}, {:.12g}\n", n + 1, g.xyz[n][0], g.xyz[n][1], g.xyz[n][2]);
  inp << "*ELEMENT, TYPE=C3D20R, ELSET=EALL\n";
  int eid = 1;
  for (int ez = 0; ez < m.nz; ++ez)
    for (int ey = 0; ey < m.ny; ++ey)
      for (int ex = 0; ex < m.nx; ++ex) {
        const int i = 2 * ex, j = 2 * ey, k = 2 * ez;
        const int c[20] = {g.at(i, j, k),         g.at(i + 2, j, k),         g.at(i + 2, j + 2, k),     g.at(i, j + 2, k),
                           g.at(i, j, k + 2),     g.at(i + 2, j, k + 2),     g.at(i + 2, j + 2, k + 2), g.at(i, j + 2, k + 2),
                           g.at(i + 1, j, k),     g.at(i + 2, j + 1, k),     g.at(i + 1, j + 2, k),     g.at(i, j + 1, k),
                           g.at(i + 1, j, k + 2), g.at(i + 2, j + 1, k + 2), g.at(i + 1, j + 2, k + 2), g.at(i, j + 1, k + 2),
                           g.at(i, j, k + 1),     g.at(i + 2, j, k + 1),     g.at(i + 2, j + 2, k + 1), g.at(i, j + 2, k + 1)};
        inp << eid++;
        for (int q = 0; q < 15; ++q) inp << ", " << c[q];
        inp << ",\n" << c[15];
        for (int q = 16; q < 20; ++q) inp << ", " << c[q];
        inp << "\n";
      }
  inp << fmt::format("*MATERIAL, NAME=M\n*ELASTIC\n{:.12g}, {:.12g}\n*DENSITY\n{:.12g}\n", s.material.E, s.material.nu,
                     s.material.rho);
  inp << "*SOLID SECTION, ELSET=EALL, MATERIAL=M\n*BOUNDARY\n";
  held = 0;
  auto hold = [&](int node, int first, int last) {
    inp << fmt::format("{}, {}, {}\n", node, first, last);
    held += last - first + 1;
  };
  if (s.is_beam()) {
    for (int n = 0; n < n_nodes; ++n) {
      if (g.ijk[n][0] == 0 && s.x0.kind == "clamped") hold(n + 1, 1, 3);
      if (g.ijk[n][0] == 2 * m.nx && s.xL.kind == "clamped") hold(n + 1, 1, 3);
    }
  } else {
    const Support* edges[4] = {&s.x0, &s.xL, &s.y0, &s.yB};
    bool any_clamped = false;
    for (int n = 0; n < n_nodes; ++n) {
      const auto& q = g.ijk[n];
      const bool on[4] = {q[0] == 0, q[0] == 2 * m.nx, q[1] == 0, q[1] == 2 * m.ny};
      bool clamp = false, ss = false;
      for (int e = 0; e < 4; ++e) {
        if (!on[e]) continue;
        if (is_clamped(*edges[e])) clamp = true;
        else if (is_simply_supported(*edges[e]) && q[2] == m.nz) ss = true;
      }
      if (clamp) {
        hold(n + 1, 1, 3);
        any_clamped = true;
      } else if (ss) {
        hold(n + 1, 3, 3);
      }
    }
    if (!any_clamped) {  // remove the in-plane rigid motions without restraining anything else
      const int a = g.at(0, 0, m.nz), b = g.at(2 * m.nx, 0, m.nz);
      if (a && b) {
        hold(a, 1, 2);
        hold(b, 2, 2);
      }
    }
  }
  const int k = std::max(1, s.request.modes) * (s.is_beam() ? 3 : 2) + 4;
  inp << fmt::format("*STEP\n*FREQUENCY\n{}\n*NODE PRINT, NSET=NALL\nU\n*END STEP\n", k);
  return inp.str();
}

}  // namespace

RunRecord calculix_run(const Scene& s, const SolidMesh& m, const std::string& exe, const std::string& work_dir,
                       bool keep_work_files) {
  RunRecord rec;
  rec.backend = "calculix";
  rec.mesh.counts = {m.nx, m.ny, m.nz};
  rec.result.summary.method = fmt::format("CalculiX C3D20R {}x{}x{} (20-node bricks, reduced integration)", m.nx, m.ny, m.nz);
  const std::string why = calculix_unsupported_reason(s);
  if (!why.empty()) {
    rec.result.summary.raise(Status::Unsupported, why);
    return rec;
  }
  const Grid g = make_grid(s, m);
  const int n_nodes = static_cast<int>(g.xyz.size());
  long held = 0;
  const std::string deck = brick_input(s, m, g, held);
  rec.result.summary.unknowns = 3L * n_nodes - held;
  return run_deck(s, std::move(rec), deck_name(s, fmt::format("{}x{}x{}", m.nx, m.ny, m.nz)), deck, n_nodes, exe, work_dir,
                  [&](const auto& shapes) { return brick_shares(s, g, shapes); }, keep_work_files);
}

std::vector<RunRecord> calculix_runs(const Scene& s, const std::string& exe, const std::string& work_dir, double budget_s,
                                     std::ostream* progress, bool keep_work_files) {
  std::vector<RunRecord> runs;
  if (s.request.modes <= 0) return runs;
  // One ladder under the budget: cost grows roughly with DOFs^1.5-2 for the sparse direct solve,
  // so guess x8 per rung.
  auto ladder = [&](const std::string& label, const std::vector<std::string>& specs,
                    const std::function<RunRecord(std::size_t)>& run) {
    double spent = 0, last = 0;
    for (std::size_t k = 0; k < specs.size(); ++k) {
      if (last > 0 && spent + 8 * last > budget_s) {
        if (progress)
          *progress << fmt::format("[{}] {}: ladder stopped before {} (time budget {:.0f} s)\n", s.name, label, specs[k], budget_s);
        break;
      }
      if (progress) *progress << fmt::format("[{}] {} {} ...", s.name, label, specs[k]) << std::flush;
      RunRecord r = run(k);
      if (progress) *progress << fmt::format(" {} in {:.3g} s\n", to_string(r.result.summary.status), r.median_s);
      spent += r.median_s;
      last = r.median_s;
      const bool failed = r.failed();
      runs.push_back(std::move(r));
      if (failed) break;
    }
  };
  if (calculix_unsupported_reason(s).empty()) {
    const auto meshes = calculix_ladder(s);
    std::vector<std::string> specs;
    for (const auto& m : meshes) specs.push_back(fmt::format("{}x{}x{}", m.nx, m.ny, m.nz));
    ladder("calculix", specs, [&](std::size_t k) { return calculix_run(s, meshes[k], exe, work_dir, keep_work_files); });
  }
  if (calculix_peer_unsupported_reason(s).empty()) {
    const auto meshes = calculix_peer_ladder(s);
    std::vector<std::string> specs;
    for (const auto& m : meshes) specs.push_back(m.spec());
    ladder("calculix-" + calculix_peer_element(s), specs,
           [&](std::size_t k) { return calculix_peer_run(s, meshes[k], exe, work_dir, keep_work_files); });
  }
  return runs;
}

}  // namespace modalbench
