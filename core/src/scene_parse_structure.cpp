// What a scene's structure carries besides its ends: supports between them, point masses,
// distributed loads (line loads on beams, pressures on plates) and gravity. Each bad entry is
// named by file, key and reason.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <toml++/toml.h>

#include "modalbench/scene.hpp"
#include "scene_reader.hpp"

namespace modalbench {

using scene_detail::check_range;
using scene_detail::Reader;

namespace {

/// The array of tables at `key` of `t` (absent: nullptr), each element checked to be a table.
const toml::array* table_array(const Reader& r, const toml::table& t, const std::string& key, const std::string& full) {
  const toml::node* n = t.get(key);
  if (!n) return nullptr;
  const toml::array* arr = n->as_array();
  if (!arr) r.fail(full, "must be an array of tables ([[" + full + "]])");
  for (std::size_t i = 0; i < arr->size(); ++i)
    if (!arr->get(i)->is_table()) r.fail(fmt::format("{}[{}]", full, i), "must be a table");
  return arr;
}

/// A position x on the beam's axis, strictly between its ends (`where`.x).
double interior_x(const Reader& r, const toml::table& t, const std::string& where, const Scene& s) {
  const double x = r.number(t, where, "x");
  if (!(x > 0.0 && x < s.geometry.length))
    r.fail(where + ".x", fmt::format("must lie strictly between the ends, in (0, {}) m (got {}); the ends' supports "
                                     "are supports.x0 and supports.xL",
                                     s.geometry.length, x));
  return x;
}

/// A component of a distributed load: a number (uniform) or [start, end] (linear), `full` its key.
std::array<double, 2> linear_value(const Reader& r, const toml::node& n, const std::string& full) {
  if (const toml::array* a = n.as_array()) {
    if (a->size() != 2) r.fail(full, "must be a number or [start, end]");
    return {r.number_node(*a->get(0), full + "[0]"), r.number_node(*a->get(1), full + "[1]")};
  }
  const double v = r.number_node(n, full);
  return {v, v};
}

/// An interval [from, to] of [0, hi] from `key` = [from, to] (default: the whole of it).
std::array<double, 2> interval(const Reader& r, const toml::table& t, const std::string& where, const std::string& key,
                               double hi) {
  const toml::node* n = t.get(key);
  if (!n) return {0.0, hi};
  const toml::array* a = n->as_array();
  if (!a || a->size() != 2) r.fail(where + "." + key, "must be [from, to]");
  const double lo = r.number_node(*a->get(0), where + "." + key + "[0]"), up = r.number_node(*a->get(1), where + "." + key + "[1]");
  check_range(r, where + "." + key + "[0]", lo, 0.0, hi);
  check_range(r, where + "." + key + "[1]", up, 0.0, hi);
  if (!(lo < up)) r.fail(where + "." + key, fmt::format("must have from < to (got [{}, {}])", lo, up));
  return {lo, up};
}

void read_line_loads(const Reader& r, const toml::array& arr, Scene& s) {
  std::set<std::string> comps = {"qz"};
  if (carries_axial(s.physics)) comps.insert("qx");
  if (carries_xy(s.physics)) comps.insert("qy");
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::string where = fmt::format("line_loads[{}]", i);
    const toml::table& t = *arr.get(i)->as_table();
    std::set<std::string> allowed = comps;
    allowed.insert("x_from");
    allowed.insert("x_to");
    r.only_keys(t, where, allowed);
    DistributedLoad q;
    q.from[0] = r.opt_number(t, where, "x_from").value_or(0.0);
    q.to[0] = r.opt_number(t, where, "x_to").value_or(s.geometry.length);
    check_range(r, where + ".x_from", q.from[0], 0.0, s.geometry.length);
    check_range(r, where + ".x_to", q.to[0], 0.0, s.geometry.length);
    if (!(q.from[0] < q.to[0]))
      r.fail(where + ".x_to", fmt::format("must exceed x_from ({} m; got {} m)", q.from[0], q.to[0]));
    bool any = false;
    for (const std::string& c : comps)
      if (const toml::node* n = t.get(c)) {
        any = true;
        (c == "qx" ? q.qx : c == "qy" ? q.qy : q.qz) = linear_value(r, *n, where + "." + c);
      }
    if (!any) r.fail(where, "a line load needs at least one component (" + std::string(comps.count("qx") ? "qx, " : "") +
                                (comps.count("qy") ? "qy, " : "") + "qz), N/m");
    s.line_loads.push_back(q);
  }
}

void read_pressures(const Reader& r, const toml::array& arr, Scene& s) {
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::string where = fmt::format("pressures[{}]", i);
    const toml::table& t = *arr.get(i)->as_table();
    r.only_keys(t, where, {"p", "x", "y"});
    DistributedLoad q;
    const auto x = interval(r, t, where, "x", s.geometry.length), y = interval(r, t, where, "y", s.geometry.width);
    q.from = {x[0], y[0]};
    q.to = {x[1], y[1]};
    const double p = r.number(t, where, "p");
    q.qz = {p, p};
    s.pressures.push_back(q);
  }
}

}  // namespace

namespace {

/// A plate point's y, strictly inside the plate's width (`where`.y).
double interior_y(const Reader& r, const toml::table& t, const std::string& where, const Scene& s) {
  const double y = r.number(t, where, "y");
  if (!(y > 0.0 && y < s.geometry.width))
    r.fail(where + ".y", fmt::format("must lie strictly inside the plate, in (0, {}) m (got {}); the edges' supports "
                                     "are supports.y0 and supports.yB",
                                     s.geometry.width, y));
  return y;
}

}  // namespace

/// [[supports.points]]: supports between a beam's ends (at x; sorted by x) or inside a plate (at
/// x, y; as written), each a name (kind) or springs.
void scene_detail::read_point_supports(const Reader& r, const toml::table& sup, Scene& s) {
  const toml::array* arr = table_array(r, sup, "points", "supports.points");
  if (!arr) return;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string where = fmt::format("supports.points[{}]", i);
    const toml::table& t = *arr->get(i)->as_table();
    PointSupport ps;
    ps.x = interior_x(r, t, where, s);
    if (s.is_plate()) ps.y = interior_y(r, t, where, s);
    if (const toml::node* kind = t.get("kind")) {
      r.only_keys(t, where, s.is_plate() ? std::set<std::string>{"x", "y", "kind"} : std::set<std::string>{"x", "kind"});
      if (!kind->is_string()) r.fail(where + ".kind", "must be a support name (free, pinned, clamped, guided)");
      ps.support = read_support_node(r, kind, where + ".kind", s);
    } else {
      toml::table springs = t;
      springs.erase("x");
      springs.erase("y");
      ps.support = read_support_node(r, &springs, where, s);
    }
    for (const PointSupport& other : s.point_supports)
      if (other.x == ps.x && other.y == ps.y)
        r.fail(where + ".x", s.is_plate() ? fmt::format("a second support at ({}, {}) m (one per point)", ps.x, ps.y)
                                          : fmt::format("a second support at x = {} m (one per point)", ps.x));
    s.point_supports.push_back(ps);
  }
  if (s.is_beam())
    std::sort(s.point_supports.begin(), s.point_supports.end(),
              [](const PointSupport& a, const PointSupport& b) { return a.x < b.x; });
}

/// [[masses]]: point masses on a beam's axis, at x in [0, L] (sorted by x), or on a plate at x, y
/// (as written), with optional rotary inertias.
void scene_detail::read_masses(const Reader& r, const toml::table& root, Scene& s) {
  const toml::array* arr = table_array(r, root, "masses", "masses");
  if (!arr) return;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const std::string where = fmt::format("masses[{}]", i);
    const toml::table& t = *arr->get(i)->as_table();
    r.only_keys(t, where, s.is_plate() ? std::set<std::string>{"x", "y", "mass", "Jx", "Jy", "Jz"}
                                       : std::set<std::string>{"x", "mass", "Jx", "Jy", "Jz"});
    PointMass pm;
    pm.x = r.number(t, where, "x");
    check_range(r, where + ".x", pm.x, 0.0, s.geometry.length);
    if (s.is_plate()) {
      pm.y = r.number(t, where, "y");
      check_range(r, where + ".y", pm.y, 0.0, s.geometry.width);
    }
    auto non_negative = [&](const std::string& key, bool required) {
      const std::optional<double> v = required ? std::optional<double>(r.number(t, where, key)) : r.opt_number(t, where, key);
      if (v && !(*v >= 0)) r.fail(where + "." + key, fmt::format("must be >= 0 (got {})", *v));
      return v.value_or(0.0);
    };
    pm.mass = non_negative("mass", true);
    pm.Jx = non_negative("Jx", false);
    pm.Jy = non_negative("Jy", false);
    pm.Jz = non_negative("Jz", false);
    if (pm.mass == 0 && pm.Jx == 0 && pm.Jy == 0 && pm.Jz == 0)
      r.fail(where, "a point mass with no mass and no rotary inertia (remove it, or give mass > 0)");
    s.masses.push_back(pm);
  }
  if (s.is_beam())
    std::sort(s.masses.begin(), s.masses.end(), [](const PointMass& a, const PointMass& b) { return a.x < b.x; });
}

void scene_detail::read_distributed_loads(const Reader& r, const toml::table& root, Scene& s) {
  if (const toml::array* a = table_array(r, root, "line_loads", "line_loads")) {
    if (s.is_plate()) r.fail("line_loads", "a plate takes [[pressures]] (Pa over a patch), not line loads");
    read_line_loads(r, *a, s);
  }
  if (const toml::array* a = table_array(r, root, "pressures", "pressures")) {
    if (s.is_beam()) r.fail("pressures", "a beam takes [[line_loads]] (N/m), not pressures");
    read_pressures(r, *a, s);
  }
}

void scene_detail::read_modes_and_tolerance(const Reader& r, const toml::table& t, Scene& s) {
  if (auto tol = r.opt_number(t, "request", "tolerance")) {
    if (!(*tol >= 1e-14 && *tol <= 1.0))
      r.fail("request.tolerance", fmt::format("must lie in [1e-14, 1] (relative error; got {})", *tol));
    s.request.tolerance = *tol;
  }
  if (auto k = r.opt_integer(t, "request", "modes")) {
    if (*k < 0 || *k > 100000) r.fail("request.modes", fmt::format("must lie in [0, 100000] (got {})", *k));
    s.request.modes = static_cast<int>(*k);
  }
}

void scene_detail::read_gravity(const Reader& r, const toml::table& root, Scene& s) {
  const toml::node* n = root.get("gravity");
  if (!n) return;
  if (!n->is_table()) r.fail("gravity", "must be a table: [gravity] g = [gx, gy, gz] (m/s^2)");
  const toml::table& t = *n->as_table();
  r.only_keys(t, "gravity", {"g"});
  const toml::node* g = t.get("g");
  const toml::array* a = g ? g->as_array() : nullptr;
  if (!a || a->size() != 3) r.fail("gravity.g", "must be [gx, gy, gz] in m/s^2, e.g. [0.0, 0.0, -9.81]");
  std::array<double, 3> v{};
  for (int k = 0; k < 3; ++k) v[static_cast<std::size_t>(k)] = r.number_node(*a->get(static_cast<std::size_t>(k)), fmt::format("gravity.g[{}]", k));
  // Components the model has no field for would be dropped silently: refused instead.
  // A frame's members run in every direction: its nodes carry x and z (and y in space).
  const bool axial = (s.is_beam() && carries_axial(s.physics)) || s.is_frame();
  const bool lateral = ((s.is_beam() || s.is_frame()) && carries_xy(s.physics));
  if (v[0] != 0.0 && !axial)
    r.fail("gravity.g[0]", fmt::format("a {} carries no load along x (physics '{}'): give gx = 0 or a planar or spatial beam",
                                       to_string(s.kind), to_string(s.physics)));
  if (v[1] != 0.0 && !lateral)
    r.fail("gravity.g[1]", fmt::format("a {} carries no load along y: give gy = 0{}", to_string(s.kind),
                                       s.is_beam() ? " or a spatial or lateral beam" : ""));
  s.gravity = v;
}

}  // namespace modalbench
