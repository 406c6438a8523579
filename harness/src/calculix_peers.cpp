// The element a practitioner would use for the scene's dimension, as a peer of the bricks:
// S8R shells (8-node, reduced integration) for plates and B32R beams (3-node, reduced
// integration) for beams, each over its own mesh ladder. ccx expands both into C3D20R bricks
// internally; B32R takes no shear coefficient of the user's (ccx's own section treatment).

#include <fmt/format.h>

#include <cmath>
#include <sstream>

#include "calculix_detail.hpp"
#include "modalbench/harness/calculix.hpp"

namespace modalbench {

using namespace calculix_detail;

namespace {

/// Node ids on the doubled grid of an n x m quadratic mesh (beam: m = 0); 0 = no node there.
struct PeerGrid {
  int n = 0, m = 0;
  std::vector<int> id;
  std::vector<std::array<double, 2>> xy;  // by id - 1
  std::vector<std::array<int, 2>> ij;     // by id - 1
  int at(int i, int j) const { return id[static_cast<std::size_t>(j) * (2 * n + 1) + i]; }
};

PeerGrid make_peer_grid(const Scene& s, int n, int m) {
  PeerGrid g{n, m, std::vector<int>(static_cast<std::size_t>(2 * n + 1) * (2 * m + 1), 0), {}, {}};
  int next = 1;
  for (int j = 0; j <= 2 * m; ++j)
    for (int i = 0; i <= 2 * n; ++i) {
      if (i % 2 && j % 2) continue;  // an S8R has no centre node
      g.id[static_cast<std::size_t>(j) * (2 * n + 1) + i] = next++;
      g.xy.push_back({s.geometry.length * i / (2.0 * n), m > 0 ? s.geometry.width * j / (2.0 * m) : 0.0});
      g.ij.push_back({i, j});
    }
  return g;
}

std::string material(const Scene& s) {
  return fmt::format("*MATERIAL, NAME=M\n*ELASTIC\n{:.12g}, {:.12g}\n*DENSITY\n{:.12g}\n", s.material.E, s.material.nu,
                     s.material.rho);
}

/// S8R shells on the plate's mid-surface. Every node's in-plane translations are held: in a flat
/// plate membrane and bending motion are uncoupled, so this removes the membrane modes (and the
/// in-plane rigid motion, which point supports would hold only through a soft, mesh-dependent
/// spring: spurious low modes) without touching the bending. Edges: clamped (w and the rotations
/// held), simply supported (w held), free.
std::string shell_deck(const Scene& s, const PeerGrid& g, long& held) {
  std::ostringstream d;
  d << "** modalbench: " << s.name << " (" << s.source << "), S8R shells\n*NODE, NSET=NALL\n";
  for (std::size_t k = 0; k < g.xy.size(); ++k) d << fmt::format("{}, {:.12g}, {:.12g}, 0\n", k + 1, g.xy[k][0], g.xy[k][1]);
  d << "*ELEMENT, TYPE=S8R, ELSET=EALL\n";
  int eid = 1;
  for (int ej = 0; ej < g.m; ++ej)
    for (int ei = 0; ei < g.n; ++ei) {
      const int i = 2 * ei, j = 2 * ej;
      d << fmt::format("{}, {}, {}, {}, {}, {}, {}, {}, {}\n", eid++, g.at(i, j), g.at(i + 2, j), g.at(i + 2, j + 2),
                       g.at(i, j + 2), g.at(i + 1, j), g.at(i + 2, j + 1), g.at(i + 1, j + 2), g.at(i, j + 1));
    }
  d << material(s) << fmt::format("*SHELL SECTION, ELSET=EALL, MATERIAL=M\n{:.12g}\n*BOUNDARY\n", s.geometry.height);
  held = 0;
  auto hold = [&](int node, int first, int last) {
    d << fmt::format("{}, {}, {}\n", node, first, last);
    held += last - first + 1;
  };
  const Support* edges[4] = {&s.x0, &s.xL, &s.y0, &s.yB};
  for (std::size_t k = 0; k < g.ij.size(); ++k) {
    const auto& q = g.ij[k];
    const bool on[4] = {q[0] == 0, q[0] == 2 * g.n, q[1] == 0, q[1] == 2 * g.m};
    bool clamp = false, ss = false;
    for (int e = 0; e < 4; ++e) {
      if (!on[e]) continue;
      if (is_clamped(*edges[e])) clamp = true;
      else if (is_simply_supported(*edges[e])) ss = true;
    }
    hold(static_cast<int>(k) + 1, 1, clamp ? 6 : ss ? 3 : 2);
  }
  return d.str();
}

/// B32R beams along the axis, section RECT width (y) x height (z). Each end DOF is held where
/// the scene's support is rigid: translations (2, 3), bending rotations (5, 6), axial (1), twist (4).
std::string beam_deck(const Scene& s, const PeerGrid& g, long& held) {
  std::ostringstream d;
  d << "** modalbench: " << s.name << " (" << s.source << "), B32R beams\n*NODE, NSET=NALL\n";
  for (std::size_t k = 0; k < g.xy.size(); ++k) d << fmt::format("{}, {:.12g}, 0, 0\n", k + 1, g.xy[k][0]);
  d << "*ELEMENT, TYPE=B32R, ELSET=EALL\n";
  for (int e = 0; e < g.n; ++e) d << fmt::format("{}, {}, {}, {}\n", e + 1, 2 * e + 1, 2 * e + 2, 2 * e + 3);
  // Direction 1 of the section is y: its first thickness is the width, the second the height.
  d << material(s)
    << fmt::format("*BEAM SECTION, ELSET=EALL, MATERIAL=M, SECTION=RECT\n{:.12g}, {:.12g}\n0, 1, 0\n*BOUNDARY\n",
                   s.geometry.width, s.geometry.height);
  held = 0;
  const int ends[2] = {1, 2 * g.n + 1};
  const Support* sup[2] = {&s.x0, &s.xL};
  for (int e = 0; e < 2; ++e) {
    const Support& q = *sup[e];
    auto hold = [&](int first, int last) {
      d << fmt::format("{}, {}, {}\n", ends[e], first, last);
      held += last - first + 1;
    };
    if (std::isinf(q.axial)) hold(1, 1);
    if (std::isinf(q.translational)) hold(2, 3);
    if (std::isinf(q.torsional)) hold(4, 4);
    if (std::isinf(q.rotational)) hold(5, 6);
  }
  return d.str();
}

/// Shares of motion per mode. Plate: [w, in-plane]. Beam: [axial, y, z, twist] from the axis
/// translations; a mode that moves the axis by less than 1e-6 of a unit-modal-mass translation is
/// a twist of the section (the axis of a doubly symmetric section does not move in torsion).
std::vector<std::array<double, 4>> peer_shares(const Scene& s, const std::vector<std::vector<std::array<double, 3>>>& shapes) {
  std::vector<std::array<double, 4>> share;
  const double unit = 1.0 / std::sqrt(s.material.rho * s.geometry.length * s.geometry.width * s.geometry.height);
  for (const auto& u : shapes) {
    std::array<double, 4> e{0, 0, 0, 0};
    double peak = 0;
    for (const auto& p : u) {
      if (s.is_plate()) {
        e[0] += p[2] * p[2];
        e[1] += p[0] * p[0] + p[1] * p[1];
      } else {
        for (int c = 0; c < 3; ++c) e[static_cast<std::size_t>(c)] += p[static_cast<std::size_t>(c)] * p[static_cast<std::size_t>(c)];
      }
      peak = std::max({peak, std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
    }
    if (s.is_beam() && peak < 1e-6 * unit) e = {0, 0, 0, 1};
    const double tot = e[0] + e[1] + e[2] + e[3];
    for (auto& x : e) x = tot > 0 ? x / tot : 0.0;
    share.push_back(e);
  }
  return share;
}

}  // namespace

std::string calculix_peer_element(const Scene& s) { return s.is_beam() ? "B32R" : "S8R"; }

std::string calculix_peer_unsupported_reason(const Scene& s) {
  if (s.is_frame()) return "the CalculiX peers are written for one beam or plate, not for frames yet";
  if (s.is_beam()) {
    if (s.cross_section.shape != SectionShape::Rectangle)
      return "the B32R beam reference is written with a rectangular section only (got a " +
             to_string(s.cross_section.shape) + ")";
    if (s.is_stepped() || s.has_tapered_pieces())
      return "the B32R beam reference is written for uniform beams only (no [[segments]])";
    if (!s.point_supports.empty() || !s.masses.empty())
      return "the B32R beam reference is written without supports between the ends or point masses";
    for (const Support* e : {&s.x0, &s.xL})
      for (double k : {e->translational, e->rotational, e->axial, e->torsional})
        if (k != 0.0 && !std::isinf(k)) return "the B32R beam reference holds or frees each end DOF: no springs";
    return "";
  }
  if (!s.point_supports.empty() || !s.masses.empty())
    return "the S8R shell reference is written without supports or masses at points of a plate";
  for (const Support* e : {&s.x0, &s.xL, &s.y0, &s.yB})
    if (!(is_clamped(*e) || is_simply_supported(*e) || e->is_free()))
      return "the S8R shell reference models plate edges simply supported, clamped or free only";
  return "";
}

std::vector<Discretization> calculix_peer_ladder(const Scene& s) {
  std::vector<Discretization> l;
  if (s.is_beam()) {
    for (int n : {4, 8, 16, 32, 64, 128}) l.push_back({{n}});
    return l;
  }
  const double ar = s.geometry.length / s.geometry.width;
  for (int n : {4, 8, 16, 32, 48}) l.push_back({{std::max(2, static_cast<int>(std::lround(n * ar))), n}});
  return l;
}

RunRecord calculix_peer_run(const Scene& s, const Discretization& mesh, const std::string& exe, const std::string& work_dir,
                            bool keep_work_files) {
  RunRecord rec;
  rec.backend = "calculix-" + calculix_peer_element(s);
  rec.mesh = mesh;
  auto& sum = rec.result.summary;
  sum.method = s.is_beam() ? fmt::format("CalculiX B32R, {} elements (3-node beams, reduced integration; ccx's own "
                                         "shear treatment: the scene's kappa is not used)",
                                         mesh.spec())
                           : fmt::format("CalculiX S8R, {} elements (8-node shells, reduced integration)", mesh.spec());
  const std::string why = calculix_peer_unsupported_reason(s);
  if (!why.empty()) {
    sum.raise(Status::Unsupported, why);
    return rec;
  }
  const PeerGrid g = make_peer_grid(s, mesh.counts.at(0), s.is_beam() ? 0 : mesh.counts.at(1));
  long held = 0;
  const std::string deck = (s.is_beam() ? beam_deck(s, g, held) : shell_deck(s, g, held)) +
                           fmt::format("*STEP\n*FREQUENCY\n{}\n*NODE PRINT, NSET=NALL\nU\n*END STEP\n",
                                       std::max(1, s.request.modes) * (s.is_beam() ? 3 : 2) + 4);
  const int n_nodes = static_cast<int>(g.xy.size());
  sum.unknowns = 6L * n_nodes - held;  // nodal DOFs of the shell or beam model, before ccx expands it
  return run_deck(s, std::move(rec), deck_name(s, calculix_peer_element(s) + "_" + mesh.spec()), deck, n_nodes, exe,
                  work_dir, [&](const auto& shapes) { return peer_shares(s, shapes); }, keep_work_files);
}

}  // namespace modalbench
