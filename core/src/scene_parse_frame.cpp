// A frame scene ([scene] kind = "frame"): its nodes, members, supports, masses, loads, gravity and
// request, each bad entry named by file, key and reason. The layout is docs/scene-format.md's
// "Frames"; the model, frame.hpp.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <toml++/toml.h>

#include "modalbench/frame.hpp"
#include "modalbench/scene.hpp"
#include "scene_reader.hpp"

namespace modalbench {

using scene_detail::Reader;

namespace {

/// The array of tables at `key` (absent: an empty one), each element checked to be a table.
std::vector<const toml::table*> tables(const Reader& r, const toml::table& root, const std::string& key) {
  std::vector<const toml::table*> out;
  const toml::node* n = root.get(key);
  if (!n) return out;
  const toml::array* arr = n->as_array();
  if (!arr) r.fail(key, "must be an array of tables ([[" + key + "]])");
  for (std::size_t i = 0; i < arr->size(); ++i) {
    if (!arr->get(i)->is_table()) r.fail(fmt::format("{}[{}]", key, i), "must be a table");
    out.push_back(arr->get(i)->as_table());
  }
  return out;
}

/// Node and member ids to indices.
struct Ids {
  std::map<std::string, int> nodes, members;
};

int node_ref(const Reader& r, const Ids& ids, const toml::table& t, const std::string& where, const std::string& key) {
  const std::string id = r.string(t, where, key);
  const auto it = ids.nodes.find(id);
  if (it == ids.nodes.end()) r.fail(where + "." + key, "unknown node '" + id + "' (no [[nodes]] has this id)");
  return it->second;
}

void read_nodes(const Reader& r, const toml::table& root, Frame& f, Ids& ids) {
  const auto list = tables(r, root, "nodes");
  if (list.size() < 2) r.fail("nodes", "a frame needs at least two nodes ([[nodes]] id, x, z)");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = fmt::format("nodes[{}]", i);
    const toml::table& t = *list[i];
    r.only_keys(t, where, {"id", "x", "y", "z"});
    FrameNode n;
    n.id = r.string(t, where, "id");
    if (n.id.empty()) r.fail(where + ".id", "must not be empty");
    if (!ids.nodes.emplace(n.id, static_cast<int>(i)).second) r.fail(where + ".id", "node '" + n.id + "' is given twice");
    if (!f.spatial && t.get("y"))
      r.fail(where + ".y", "a planar frame lies in the x-z plane: its nodes have no y (physics spatial for a space frame)");
    n.x = {r.number(t, where, "x"), r.opt_number(t, where, "y").value_or(0.0), r.number(t, where, "z")};
    f.nodes.push_back(n);
  }
}

std::optional<std::array<double, 3>> read_up(const Reader& r, const toml::table& t, const std::string& where, bool spatial) {
  const toml::node* n = t.get("up");
  if (!n) return std::nullopt;
  if (!spatial)
    r.fail(where + ".up", "a planar frame's members bend in the x-z plane: `up` is for spatial frames");
  const toml::array* a = n->as_array();
  if (!a || a->size() != 3) r.fail(where + ".up", "must be a vector [x, y, z] in the member's local x-z plane");
  std::array<double, 3> v{};
  for (std::size_t k = 0; k < 3; ++k) v[k] = r.number_node(*a->get(k), fmt::format("{}.up[{}]", where, k));
  if (v == std::array<double, 3>{0, 0, 0}) r.fail(where + ".up", "must not be the zero vector");
  return v;
}

/// A member's end ids in `releases`, as the ends they release.
std::array<bool, 2> read_releases(const Reader& r, const toml::table& t, const std::string& where, const Frame& f,
                                  const FrameMember& m) {
  std::array<bool, 2> out{};
  const toml::node* n = t.get("releases");
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a) r.fail(where + ".releases", "must be a list of the member's node ids, e.g. [\"B\"]");
  for (std::size_t k = 0; k < a->size(); ++k) {
    const std::string key = fmt::format("{}.releases[{}]", where, k);
    const auto* s = a->get(k)->as_string();
    if (!s) r.fail(key, "must be a node id (a string)");
    bool found = false;
    for (int e = 0; e < 2; ++e)
      if (f.nodes[static_cast<std::size_t>(m.nodes[static_cast<std::size_t>(e)])].id == s->get()) {
        if (out[static_cast<std::size_t>(e)]) r.fail(key, "'" + s->get() + "' is released twice");
        out[static_cast<std::size_t>(e)] = found = true;
      }
    if (!found) r.fail(key, "'" + s->get() + "' is not one of the member's nodes");
  }
  return out;
}

void read_members(const Reader& r, const toml::table& root, const Scene& s, Frame& f, Ids& ids, bool kappa_given) {
  const auto list = tables(r, root, "members");
  if (list.empty()) r.fail("members", "a frame needs at least one member ([[members]] id, nodes, section)");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = fmt::format("members[{}]", i);
    const toml::table& t = *list[i];
    r.only_keys(t, where, {"id", "nodes", "section", "material", "releases", "up"});
    FrameMember m;
    m.id = r.string(t, where, "id");
    if (m.id.empty()) r.fail(where + ".id", "must not be empty");
    if (!ids.members.emplace(m.id, static_cast<int>(i)).second) r.fail(where + ".id", "member '" + m.id + "' is given twice");
    const toml::node* nn = t.get("nodes");
    const toml::array* na = nn ? nn->as_array() : nullptr;
    if (!na || na->size() != 2 || !na->get(0)->is_string() || !na->get(1)->is_string())
      r.fail(where + ".nodes", "must be the two node ids it joins, e.g. [\"A\", \"B\"]");
    for (std::size_t e = 0; e < 2; ++e) {
      const std::string id = na->get(e)->as_string()->get();
      const auto it = ids.nodes.find(id);
      if (it == ids.nodes.end()) r.fail(fmt::format("{}.nodes[{}]", where, e), "unknown node '" + id + "'");
      m.nodes[e] = it->second;
    }
    if (m.nodes[0] == m.nodes[1]) r.fail(where + ".nodes", "a member joins two different nodes (it has zero length)");
    for (std::size_t j = 0; j < i; ++j) {
      const auto& o = f.members[j].nodes;
      if ((o[0] == m.nodes[0] && o[1] == m.nodes[1]) || (o[0] == m.nodes[1] && o[1] == m.nodes[0]))
        r.fail(where + ".nodes", fmt::format("member '{}' already joins these nodes", f.members[j].id));
    }
    const auto& a = f.nodes[static_cast<std::size_t>(m.nodes[0])].x;
    const auto& b = f.nodes[static_cast<std::size_t>(m.nodes[1])].x;
    m.length = std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
    if (!(m.length > 0))
      r.fail(where + ".nodes", fmt::format("nodes '{}' and '{}' are at the same point: the member would have zero length",
                                           f.nodes[static_cast<std::size_t>(m.nodes[0])].id,
                                           f.nodes[static_cast<std::size_t>(m.nodes[1])].id));
    try {
      m.axes = member_axes(a, b, read_up(r, t, where, f.spatial));
    } catch (const std::invalid_argument& e) {
      r.fail(where + ".up", e.what());
    }
    Geometry extent;
    scene_detail::read_section(r, r.table(t, where, "section"), where + ".section", m.section, extent);
    m.width = extent.width;
    m.height = extent.height;
    m.material = s.material;
    bool own_kappa = false;
    if (t.get("material"))
      own_kappa = scene_detail::read_material_overrides(r, r.table(t, where, "material"), where + ".material", m.material);
    if (!own_kappa && !kappa_given) {
      std::string note;
      m.material.kappa = scene_detail::default_kappa(r, m.section, m.material.nu, s.theory, where + ".material.kappa", note);
    }
    m.released = read_releases(r, t, where, f, m);
    f.members.push_back(m);
  }
  for (std::size_t k = 0; k < f.nodes.size(); ++k)
    if (std::none_of(f.members.begin(), f.members.end(), [k](const FrameMember& m) {
          return m.nodes[0] == static_cast<int>(k) || m.nodes[1] == static_cast<int>(k);
        }))
      r.fail(fmt::format("nodes[{}]", k), "node '" + f.nodes[k].id + "' joins no member");
}

FrameSupport read_frame_support(const Reader& r, const toml::node& n, const std::string& where, int node, bool spatial) {
  FrameSupport sp;
  sp.node = node;
  constexpr double inf = kRigid;
  if (const auto* str = n.as_string()) {
    sp.kind = str->get();
    if (sp.kind == "free") sp.springs = {0, 0, 0, 0, 0, 0};
    else if (sp.kind == "pinned") sp.springs = {inf, inf, inf, 0, 0, 0};
    else if (sp.kind == "clamped") sp.springs = {inf, inf, inf, inf, inf, inf};
    else r.fail(where, "unknown support '" + sp.kind + "' (expected free, pinned, clamped, or a table of springs)");
    return sp;
  }
  const auto* t = n.as_table();
  if (!t) r.fail(where, "must be free, pinned, clamped or a table of springs { ux = N/m, uz = N/m, ry = N m/rad }");
  sp.kind = "springs";
  static const std::array<const char*, 6> names = {"ux", "uy", "uz", "rx", "ry", "rz"};
  std::set<std::string> allowed = spatial ? std::set<std::string>{"ux", "uy", "uz", "rx", "ry", "rz"}
                                          : std::set<std::string>{"ux", "uz", "ry"};
  r.only_keys(*t, where, allowed);
  for (std::size_t k = 0; k < 6; ++k)
    if (auto v = r.opt_number(*t, where, names[k], /*allow_inf=*/true)) {
      if (*v < 0) r.fail(where + "." + names[k], fmt::format("spring stiffness must be >= 0 (got {})", *v));
      sp.springs[k] = *v;
    }
  return sp;
}

void read_frame_supports(const Reader& r, const toml::table& root, Frame& f, const Ids& ids) {
  const toml::table& sup = r.table(root, "", "supports");
  for (auto&& [key, node] : sup) {
    const std::string id(key.str()), where = "supports." + id;
    const auto it = ids.nodes.find(id);
    if (it == ids.nodes.end()) r.fail(where, "unknown node '" + id + "' (supports are keyed by node id)");
    f.supports.push_back(read_frame_support(r, node, where, it->second, f.spatial));
  }
}

void read_frame_masses(const Reader& r, const toml::table& root, Frame& f, const Ids& ids) {
  const auto list = tables(r, root, "masses");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = fmt::format("masses[{}]", i);
    const toml::table& t = *list[i];
    r.only_keys(t, where, f.spatial ? std::set<std::string>{"node", "mass", "Jx", "Jy", "Jz"}
                                    : std::set<std::string>{"node", "mass", "Jy"});
    FrameMass m;
    m.node = node_ref(r, ids, t, where, "node");
    auto nonneg = [&](const char* k) {
      const double v = r.opt_number(t, where, k).value_or(0.0);
      if (v < 0) r.fail(where + "." + k, fmt::format("must be >= 0 (got {})", v));
      return v;
    };
    m.mass = nonneg("mass");
    m.Jx = nonneg("Jx");
    m.Jy = nonneg("Jy");
    m.Jz = nonneg("Jz");
    f.masses.push_back(m);
  }
}

void read_frame_loads(const Reader& r, const toml::table& root, Frame& f, const Ids& ids) {
  static const std::array<const char*, 6> names = {"Fx", "Fy", "Fz", "Mx", "My", "Mz"};
  const auto list = tables(r, root, "loads");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = fmt::format("loads[{}]", i);
    const toml::table& t = *list[i];
    r.only_keys(t, where, f.spatial ? std::set<std::string>{"node", "Fx", "Fy", "Fz", "Mx", "My", "Mz"}
                                    : std::set<std::string>{"node", "Fx", "Fz", "My"});
    FrameLoad p;
    p.node = node_ref(r, ids, t, where, "node");
    bool any = false;
    for (std::size_t k = 0; k < 6; ++k)
      if (auto v = r.opt_number(t, where, names[k])) {
        p.F[k] = *v;
        any = true;
      }
    if (!any) r.fail(where, "a load needs at least one component");
    f.loads.push_back(p);
  }
}

/// A component of a line load: a number (uniform) or [start, end].
std::array<double, 2> intensity(const Reader& r, const toml::table& t, const std::string& where, const char* key) {
  const toml::node* n = t.get(key);
  if (!n) return {0, 0};
  if (const auto* a = n->as_array()) {
    if (a->size() != 2) r.fail(where + "." + key, "must be a number (N/m) or [start, end]");
    return {r.number_node(*a->get(0), where + "." + key + "[0]"), r.number_node(*a->get(1), where + "." + key + "[1]")};
  }
  const double v = r.number_node(*n, where + "." + key);
  return {v, v};
}

void read_frame_line_loads(const Reader& r, const toml::table& root, Frame& f, const Ids& ids) {
  const auto list = tables(r, root, "line_loads");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = fmt::format("line_loads[{}]", i);
    const toml::table& t = *list[i];
    r.only_keys(t, where, f.spatial ? std::set<std::string>{"member", "qx", "qy", "qz"}
                                    : std::set<std::string>{"member", "qx", "qz"});
    const std::string id = r.string(t, where, "member");
    const auto it = ids.members.find(id);
    if (it == ids.members.end()) r.fail(where + ".member", "unknown member '" + id + "'");
    if (!t.get("qx") && !t.get("qy") && !t.get("qz")) r.fail(where, "a line load needs at least one of qx, qz" +
                                                                        std::string(f.spatial ? ", qy" : ""));
    f.line_loads.push_back({it->second, intensity(r, t, where, "qx"), intensity(r, t, where, "qy"),
                            intensity(r, t, where, "qz")});
  }
}

FrameProbe read_probe(const Reader& r, const toml::node& n, const std::string& where, const Frame& f, const Ids& ids) {
  FrameProbe p;
  if (const auto* s = n.as_string()) {
    const auto it = ids.nodes.find(s->get());
    if (it == ids.nodes.end()) r.fail(where, "unknown node '" + s->get() + "'");
    p.node = it->second;
    p.label = s->get();
    return p;
  }
  const auto* t = n.as_table();
  if (!t) r.fail(where, "must be a node id or { member = \"ID\", s = 0..1 }");
  r.only_keys(*t, where, {"member", "s"});
  const std::string id = r.string(*t, where, "member");
  const auto it = ids.members.find(id);
  if (it == ids.members.end()) r.fail(where + ".member", "unknown member '" + id + "'");
  p.member = it->second;
  p.s = r.number(*t, where, "s");
  scene_detail::check_range(r, where + ".s", p.s, 0.0, 1.0);
  p.label = fmt::format("{}@{:g}", f.members[static_cast<std::size_t>(p.member)].id, p.s);
  return p;
}

void read_frame_request(const Reader& r, const toml::table& root, Scene& s, Frame& f, const Ids& ids) {
  const toml::node* rn = root.get("request");
  if (!rn) return;
  const auto* t = rn->as_table();
  if (!t) r.fail("request", "must be a table");
  for (const char* k : {"frf", "shapes", "transient"})
    if (t->get(k))
      r.fail(std::string("request.") + k, "not available for frames yet (modes and statics are): remove the key");
  r.only_keys(*t, "request", {"modes", "probes", "tolerance"});
  scene_detail::read_modes_and_tolerance(r, *t, s);
  if (const toml::node* pn = t->get("probes")) {
    const auto* arr = pn->as_array();
    if (!arr) r.fail("request.probes", "must be an array of node ids or { member = \"ID\", s = 0..1 }");
    for (std::size_t i = 0; i < arr->size(); ++i) {
      f.probes.push_back(read_probe(r, *arr->get(i), fmt::format("request.probes[{}]", i), f, ids));
      // The pipeline asks statics of a scene with probes: one entry per frame probe (its x and z).
      const auto at = f.probe_point(f.probes.back());
      s.request.probes.push_back({at[0], at[2]});
    }
  }
}

}  // namespace

void scene_detail::read_frame(const Reader& r, const toml::table& root, Scene& s) {
  for (const char* k : {"geometry", "segments", "pressures", "rotor"})
    if (root.get(k))
      r.fail(k, "a frame has no [" + std::string(k) + "]: its geometry is its [[nodes]] and [[members]]");
  auto f = std::make_shared<Frame>();
  f->spatial = s.physics == Physics::Spatial;
  const toml::table& mat = r.table(root, "", "material");
  const bool kappa_given = mat.get("kappa") != nullptr;
  // read_material's default shear coefficient is a beam's (its one section); a frame's members
  // each take their own section's.
  if (!kappa_given)
    s.notes.erase(std::remove_if(s.notes.begin(), s.notes.end(),
                                 [](const std::string& n) { return n.rfind("material.kappa not given", 0) == 0; }),
                  s.notes.end());
  Ids ids;
  read_nodes(r, root, *f, ids);
  read_members(r, root, s, *f, ids, kappa_given);
  if (!kappa_given && s.theory == Theory::Timoshenko)
    s.notes.push_back("material.kappa not given: each member's section gives its own (5/6 for rectangles, Cowper's "
                      "for circles and tubes)");
  read_frame_supports(r, root, *f, ids);
  read_frame_masses(r, root, *f, ids);
  read_frame_loads(r, root, *f, ids);
  read_frame_line_loads(r, root, *f, ids);
  read_gravity(r, root, s);
  if (s.gravity && !f->spatial && (*s.gravity)[1] != 0.0)
    r.fail("gravity.g[1]", "a planar frame lies in the x-z plane: give gy = 0");
  read_frame_request(r, root, s, *f, ids);
  s.frame = std::move(f);
}

void scene_detail::validate_frame(const Reader& r, const Scene& s) {
  if (!s.frame) r.fail("nodes", "a frame scene has no frame (nodes and members)");
  const Frame& f = *s.frame;
  if (s.physics != Physics::Planar && s.physics != Physics::Spatial)
    r.fail("scene.physics", "a frame's physics is planar or spatial");
  if (f.spatial != (s.physics == Physics::Spatial)) r.fail("scene.physics", "does not match the frame's");
  if (s.theory != Theory::EulerBernoulli && s.theory != Theory::Timoshenko)
    r.fail("scene.theory", "a frame's theory is euler-bernoulli or timoshenko");
  const int n = static_cast<int>(f.nodes.size());
  for (std::size_t i = 0; i < f.nodes.size(); ++i)
    for (double c : f.nodes[i].x)
      if (!std::isfinite(c)) r.fail(fmt::format("nodes[{}]", i), "coordinates must be finite");
  for (std::size_t i = 0; i < f.members.size(); ++i) {
    const FrameMember& m = f.members[i];
    const std::string key = fmt::format("members[{}]", i);
    if (m.nodes[0] < 0 || m.nodes[0] >= n || m.nodes[1] < 0 || m.nodes[1] >= n || m.nodes[0] == m.nodes[1])
      r.fail(key + ".nodes", "must be two different nodes of the frame");
    if (!(std::isfinite(m.length) && m.length > 0)) r.fail(key, "its length must be finite and > 0");
    const Section p = m.properties();
    for (double v : {p.A, p.Iy, p.Iz, p.J})
      if (!(std::isfinite(v) && v > 0)) r.fail(key + ".section", "its properties must be finite and > 0");
    const Material& mt = m.material;
    for (double v : {mt.E, mt.G, mt.rho, mt.kappa})
      if (!(std::isfinite(v) && v > 0)) r.fail(key + ".material", "E, G, rho and kappa must be finite and > 0");
    if (!f.spatial && !(std::abs(m.axes[1][1]) > 1.0 - 1e-12))
      r.fail(key, "a planar frame's members lie in the x-z plane");
  }
  for (std::size_t i = 0; i < f.supports.size(); ++i)
    for (double k : f.supports[i].springs)
      if (std::isnan(k) || k < 0) r.fail(fmt::format("supports[{}]", i), "spring stiffness must be >= 0");
  for (std::size_t i = 0; i < f.masses.size(); ++i)
    for (double v : {f.masses[i].mass, f.masses[i].Jx, f.masses[i].Jy, f.masses[i].Jz})
      if (!(std::isfinite(v) && v >= 0)) r.fail(fmt::format("masses[{}]", i), "mass and inertias must be finite and >= 0");
  for (std::size_t i = 0; i < f.loads.size(); ++i)
    for (double v : f.loads[i].F)
      if (!std::isfinite(v)) r.fail(fmt::format("loads[{}]", i), "values must be finite");
  for (std::size_t i = 0; i < f.line_loads.size(); ++i) {
    const FrameLineLoad& q = f.line_loads[i];
    for (double v : {q.qx[0], q.qx[1], q.qy[0], q.qy[1], q.qz[0], q.qz[1]})
      if (!std::isfinite(v)) r.fail(fmt::format("line_loads[{}]", i), "values must be finite");
  }
  if (s.gravity)
    for (double g : *s.gravity)
      if (!std::isfinite(g)) r.fail("gravity.g", "values must be finite");
  if (s.request.modes < 0) r.fail("request.modes", "must be >= 0");
}

}  // namespace modalbench
