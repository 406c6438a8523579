#include <fmt/format.h>

#include <fstream>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "modalbench/scene.hpp"
#include "scene_reader.hpp"

namespace modalbench {

namespace {

using scene_detail::check_range;
using scene_detail::Reader;

}  // namespace

Support scene_detail::read_support_node(const Reader& r, const toml::node* n, const std::string& full, const Scene& s) {
  if (auto str = n->as_string()) {
    try {
      return Support::named(str->get());
    } catch (const std::invalid_argument& e) {
      r.fail(full, e.what());
    }
  }
  if (!n->is_table()) r.fail(full, "must be a support name or a table of springs");
  const auto& t = *n->as_table();
  Support sp;
  sp.kind = "springs";
  std::set<std::string> allowed = {"translational", "rotational"};
  if (s.is_beam() && carries_axial(s.physics)) allowed.insert("axial");
  if (s.is_beam() && carries_torsion(s.physics)) allowed.insert("torsional");
  r.only_keys(t, full, allowed);
  auto spring = [&](const std::string& k) {
    double v = r.number(t, full, k, /*allow_inf=*/true);
    if (v < 0) r.fail(full + "." + k, fmt::format("spring stiffness must be >= 0 (got {})", v));
    return v;
  };
  sp.translational = spring("translational");
  sp.rotational = spring("rotational");
  if (allowed.count("axial")) sp.axial = spring("axial");
  if (allowed.count("torsional")) sp.torsional = spring("torsional");
  return sp;
}

namespace {

using scene_detail::read_distributed_loads;
using scene_detail::read_gravity;
using scene_detail::read_masses;
using scene_detail::read_point_supports;
using scene_detail::read_section;
using scene_detail::read_segment_materials;
using scene_detail::read_segment_sections;
using scene_detail::read_support_node;

Support read_support(const Reader& r, const toml::table& supports, const std::string& key, const Scene& s) {
  const std::string full = "supports." + key;
  const toml::node* n = supports.get(key);
  if (!n) r.fail(full, "missing key (each beam end x0, xL / plate edge x0, xL, y0, yB needs a support)");
  return read_support_node(r, n, full, s);
}

std::array<double, 2> read_point(const Reader& r, const toml::node& n, const std::string& key, const Scene& s) {
  const double L = s.geometry.length, B = s.geometry.width;
  if (s.is_beam()) {
    double x = r.number_node(n, key);
    check_range(r, key, x, 0.0, L);
    return {x, 0.0};
  }
  auto arr = n.as_array();
  if (!arr || arr->size() != 2) r.fail(key, "a plate point must be an array [x, y]");
  double x = r.number_node(*arr->get(0), key + "[0]");
  double y = r.number_node(*arr->get(1), key + "[1]");
  check_range(r, key + "[0]", x, 0.0, L);
  check_range(r, key + "[1]", y, 0.0, B);
  return {x, y};
}

/// [scene]: name, kind, physics, theory.
void read_scene_table(const Reader& r, const toml::table& root, Scene& s) {
  const auto& sc = r.table(root, "", "scene");
  r.only_keys(sc, "scene", {"name", "kind", "physics", "theory", "description"});
  s.name = r.string(sc, "scene", "name");
  if (s.name.empty()) r.fail("scene.name", "must not be empty");
  const std::string kind = r.string(sc, "scene", "kind");
  if (kind == "beam") s.kind = SceneKind::Beam;
  else if (kind == "plate") s.kind = SceneKind::Plate;
  else if (kind == "frame") s.kind = SceneKind::Frame;
  else r.fail("scene.kind", "unknown kind '" + kind + "' (expected beam, plate or frame)");

  const std::string physics = r.string(sc, "scene", "physics");
  if (s.is_frame()) {
    if (physics == "planar") s.physics = Physics::Planar;
    else if (physics == "spatial") s.physics = Physics::Spatial;
    else r.fail("scene.physics", "unknown frame physics '" + physics + "' (expected planar or spatial)");
  } else if (s.is_beam()) {
    if (physics == "bending") s.physics = Physics::Bending;
    else if (physics == "planar") s.physics = Physics::Planar;
    else if (physics == "spatial") s.physics = Physics::Spatial;
    else if (physics == "lateral") s.physics = Physics::Lateral;
    else r.fail("scene.physics", "unknown beam physics '" + physics + "' (expected bending, planar, spatial or lateral)");
  } else {
    if (physics != "bending") r.fail("scene.physics", "a plate has physics 'bending' (got '" + physics + "')");
    s.physics = Physics::Bending;
  }
  const std::string theory = r.string(sc, "scene", "theory");
  if (!s.is_plate()) {
    if (theory == "euler-bernoulli") s.theory = Theory::EulerBernoulli;
    else if (theory == "timoshenko") s.theory = Theory::Timoshenko;
    else r.fail("scene.theory", "unknown " + to_string(s.kind) + " theory '" + theory +
                                    "' (expected euler-bernoulli or timoshenko)");
  } else {
    if (theory == "kirchhoff") s.theory = Theory::Kirchhoff;
    else if (theory == "mindlin") s.theory = Theory::Mindlin;
    else r.fail("scene.theory", "unknown plate theory '" + theory + "' (expected kirchhoff or mindlin)");
  }
}

/// [geometry]: length; a beam's section (width and height: a rectangle; or section = {...}); a
/// plate's width and thickness (height).
void read_geometry(const Reader& r, const toml::table& root, Scene& s) {
  const auto& g = r.table(root, "", "geometry");
  r.only_keys(g, "geometry", {"length", "width", "height", "section"});
  s.geometry.length = r.positive(g, "geometry", "length");
  if (root.get("segments")) {
    if (s.is_plate()) r.fail("segments", "a plate has no segments (a stepped beam's pieces)");
    for (const char* k : {"width", "height", "section"})
      if (g.get(k))
        r.fail(std::string("geometry.") + k, "a stepped beam gives its sections per piece ([[segments]] section = "
                                              "{...}), not here");
    read_segment_sections(r, root, s);
    return;
  }
  if (g.get("section")) {
    if (s.is_plate()) r.fail("geometry.section", "a plate has no cross-section: give its width and thickness (height)");
    if (g.get("width") || g.get("height"))
      r.fail("geometry.width", "give the section either as geometry.width and height (a rectangle) or as "
                               "geometry.section, not both");
    read_section(r, r.table(g, "geometry", "section"), "geometry.section", s.cross_section, s.geometry);
    return;
  }
  s.geometry.width = r.positive(g, "geometry", "width");
  s.geometry.height = r.positive(g, "geometry", "height");
}

/// The shear coefficient where material.kappa is not given (default_kappa in scene_reader.hpp);
/// said only where the theory has shear deformation.
void default_kappa(const Reader& r, Scene& s) {
  std::string note;
  const SectionSpec rect;
  s.material.kappa = scene_detail::default_kappa(r, s.is_beam() ? s.cross_section : rect, s.material.nu, s.theory,
                                                 "material.kappa", note);
  if (!note.empty() && (s.theory == Theory::Timoshenko || s.theory == Theory::Mindlin))
    s.notes.push_back("material.kappa not given: " + note);
}

/// [material]: E, G and/or nu, rho, kappa, loss_factor.
void read_material(const Reader& r, const toml::table& root, Scene& s) {
  const auto& m = r.table(root, "", "material");
  r.only_keys(m, "material", {"E", "G", "nu", "rho", "kappa", "loss_factor"});
  s.material.E = r.positive(m, "material", "E");
  s.material.rho = r.positive(m, "material", "rho");
  auto G = r.opt_number(m, "material", "G");
  auto nu = r.opt_number(m, "material", "nu");
  if (!G && !nu) r.fail("material", "give G or nu (or both, consistent)");
  if (nu && !(*nu > -1.0 && *nu < 0.5)) r.fail("material.nu", fmt::format("must lie in (-1, 0.5) (got {})", *nu));
  if (G && !(*G > 0)) r.fail("material.G", fmt::format("must be > 0 (got {})", *G));
  if (G && nu) {
    const double implied = s.material.E / (2.0 * (1.0 + *nu));
    if (std::abs(implied - *G) > 1e-6 * *G)
      r.fail("material.G", fmt::format("inconsistent with E and nu: E/(2(1+nu)) = {} Pa but G = {} Pa", implied, *G));
  }
  s.material.G = G ? *G : s.material.E / (2.0 * (1.0 + *nu));
  s.material.nu = nu ? *nu : s.material.E / (2.0 * *G) - 1.0;
  if (!(s.material.nu > -1.0 && s.material.nu < 0.5))
    r.fail("material.G", fmt::format("implies nu = E/(2G) - 1 = {} outside (-1, 0.5)", s.material.nu));
  if (auto k = r.opt_number(m, "material", "kappa")) {
    if (!(*k > 0)) r.fail("material.kappa", fmt::format("must be > 0 (got {})", *k));
    s.material.kappa = *k;
  } else {
    default_kappa(r, s);
  }
  if (auto eta = r.opt_number(m, "material", "loss_factor")) {
    if (*eta < 0) r.fail("material.loss_factor", fmt::format("must be >= 0 (got {})", *eta));
    s.material.loss_factor = *eta;
  }
}

/// [supports]: beam ends x0, xL; plate edges x0, xL, y0, yB.
void read_supports(const Reader& r, const toml::table& root, Scene& s) {
  const auto& sup = r.table(root, "", "supports");
  if (s.is_beam()) {
    r.only_keys(sup, "supports", {"x0", "xL", "points"});
    s.x0 = read_support(r, sup, "x0", s);
    s.xL = read_support(r, sup, "xL", s);
  } else {
    r.only_keys(sup, "supports", {"x0", "xL", "y0", "yB", "points"});
    s.x0 = read_support(r, sup, "x0", s);
    s.xL = read_support(r, sup, "xL", s);
    s.y0 = read_support(r, sup, "y0", s);
    s.yB = read_support(r, sup, "yB", s);
  }
  read_point_supports(r, sup, s);
}

/// [[loads]]: point loads with the components the physics carries.
void read_loads(const Reader& r, const toml::table& root, Scene& s) {
  if (const toml::node* ln = root.get("loads")) {
    auto arr = ln->as_array();
    if (!arr) r.fail("loads", "must be an array of tables ([[loads]])");
    std::set<std::string> comps;
    if (s.is_plate()) comps = {"Fz"};
    else if (s.physics == Physics::Bending) comps = {"Fz", "My"};
    else if (s.physics == Physics::Planar) comps = {"Fx", "Fz", "My"};
    else if (s.physics == Physics::Lateral) comps = {"Fy", "Fz", "My", "Mz"};
    else comps = {"Fx", "Fy", "Fz", "Mx", "My", "Mz"};
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const std::string where = fmt::format("loads[{}]", i);
      auto t = arr->get(i)->as_table();
      if (!t) r.fail(where, "must be a table");
      std::set<std::string> allowed = comps;
      allowed.insert("x");
      if (s.is_plate()) allowed.insert("y");
      r.only_keys(*t, where, allowed);
      PointLoad p;
      const toml::node* xn = t->get("x");
      if (!xn) r.fail(where + ".x", "missing key");
      if (s.is_beam()) {
        p.x = read_point(r, *xn, where + ".x", s)[0];
      } else {
        p.x = r.number(*t, where, "x");
        p.y = r.number(*t, where, "y");
        check_range(r, where + ".x", p.x, 0.0, s.geometry.length);
        check_range(r, where + ".y", p.y, 0.0, s.geometry.width);
      }
      auto comp = [&](const char* k) { return r.opt_number(*t, where, k).value_or(0.0); };
      p.Fx = comp("Fx"); p.Fy = comp("Fy"); p.Fz = comp("Fz");
      p.Mx = comp("Mx"); p.My = comp("My"); p.Mz = comp("Mz");
      bool any = false;
      for (auto& c : comps) any = any || t->contains(c);
      if (!any) r.fail(where, "a load needs at least one component");
      s.loads.push_back(p);
    }
  }
}

/// request.shapes: true (default sampling), false, or { nx = N } (beam) / { nx = N, ny = M } (plate).
void read_shapes(const Reader& r, const toml::node& n, Scene& s) {
  const std::string key = "request.shapes";
  if (auto b = n.as_boolean()) {
    if (!b->get()) return;
    ShapeRequest sr;
    sr.nx = s.is_beam() ? ShapeRequest::kBeamDefaultNx : ShapeRequest::kPlateDefaultNx;
    sr.ny = s.is_beam() ? 1 : ShapeRequest::kPlateDefaultNy;
    s.request.shapes = sr;
    return;
  }
  const auto* t = n.as_table();
  if (!t) r.fail(key, "must be true, false or a table { nx = N" + std::string(s.is_plate() ? ", ny = M }" : " }"));
  r.only_keys(*t, key, s.is_beam() ? std::set<std::string>{"nx"} : std::set<std::string>{"nx", "ny"});
  ShapeRequest sr;
  auto count = [&](const char* k, long def, long hi) {
    const auto v = r.opt_integer(*t, key, k);
    const long c = v ? *v : def;
    if (c < 2 || c > hi) r.fail(key + "." + k, fmt::format("must lie in [2, {}] (got {})", hi, c));
    return static_cast<int>(c);
  };
  sr.nx = count("nx", s.is_beam() ? ShapeRequest::kBeamDefaultNx : ShapeRequest::kPlateDefaultNx, 100001);
  sr.ny = s.is_beam() ? 1 : count("ny", ShapeRequest::kPlateDefaultNy, 10001);
  if (static_cast<long>(sr.nx) * sr.ny > 1000000)
    r.fail(key, fmt::format("{} x {} points exceed the limit of 1e6 sample points", sr.nx, sr.ny));
  s.request.shapes = sr;
}

/// [request]: modes, probes, frf, shapes, tolerance, transient.
void read_request(const Reader& r, const toml::table& root, Scene& s) {
  if (const toml::node* rn = root.get("request")) {
    auto t = rn->as_table();
    if (!t) r.fail("request", "must be a table");
    r.only_keys(*t, "request", {"modes", "probes", "frf", "shapes", "tolerance", "transient"});
    if (const toml::node* tn = t->get("transient")) read_transient(r, *tn, s);
    scene_detail::read_modes_and_tolerance(r, *t, s);
    if (const toml::node* pn = t->get("probes")) {
      auto arr = pn->as_array();
      if (!arr) r.fail("request.probes", "must be an array");
      for (std::size_t i = 0; i < arr->size(); ++i)
        s.request.probes.push_back(read_point(r, *arr->get(i), fmt::format("request.probes[{}]", i), s));
    }
    if (const toml::node* sn = t->get("shapes")) read_shapes(r, *sn, s);
    if (const toml::node* fn = t->get("frf")) {
      auto ft = fn->as_table();
      if (!ft) r.fail("request.frf", "must be a table");
      r.only_keys(*ft, "request.frf", {"excite", "observe", "omega_min", "omega_max", "points"});
      FrfRequest f;
      for (const char* k : {"excite", "observe"}) {
        const toml::node* n = ft->get(k);
        if (!n) r.fail(std::string("request.frf.") + k, "missing key");
        (std::string(k) == "excite" ? f.excite : f.observe) = read_point(r, *n, std::string("request.frf.") + k, s);
      }
      f.omega_min = r.number(*ft, "request.frf", "omega_min");
      f.omega_max = r.number(*ft, "request.frf", "omega_max");
      if (f.omega_min < 0) r.fail("request.frf.omega_min", "must be >= 0 rad/s");
      if (!(f.omega_max > f.omega_min)) r.fail("request.frf.omega_max", "must be > omega_min");
      auto pts = r.opt_integer(*ft, "request.frf", "points");
      if (!pts) r.fail("request.frf.points", "missing key");
      if (*pts < 2 || *pts > 1000000) r.fail("request.frf.points", fmt::format("must lie in [2, 1000000] (got {})", *pts));
      f.points = static_cast<int>(*pts);
      s.request.frf = f;
    }
  }
}

/// [backend.NAME]: scalar options per back-end, kept as text for the back-end to validate.
void read_backend_options(const Reader& r, const toml::table& root, Scene& s) {
  const toml::node* bn = root.get("backend");
  if (!bn) return;
  const auto* bt = bn->as_table();
  if (!bt) r.fail("backend", "must be a table of back-end tables ([backend.NAME])");
  for (auto&& [name, node] : *bt) {
    const std::string where = "backend." + std::string(name.str());
    const auto* t = node.as_table();
    if (!t) r.fail(where, "must be a table of options (key = value)");
    auto& list = s.backend_options[std::string(name.str())];
    for (auto&& [key, v] : *t) {
      const std::string full = where + "." + std::string(key.str());
      std::string text;
      if (auto b = v.as_boolean()) text = b->get() ? "true" : "false";
      else if (auto i = v.as_integer()) text = std::to_string(i->get());
      else if (auto f = v.as_floating_point()) text = fmt::format("{}", f->get());
      else if (auto str = v.as_string()) text = str->get();
      else r.fail(full, "an option value must be a boolean, a number or a string");
      list.push_back({std::string(key.str()), text});
    }
  }
}

}  // namespace

Scene parse_scene(std::string_view text, const std::string& source) {
  Reader r(source);
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& e) {
    throw InputError(source, fmt::format("line {}", e.source().begin.line),
                     std::string("TOML syntax: ") + std::string(e.description()));
  }
  r.only_keys(root, "", {"scene", "geometry", "segments", "material", "supports", "masses", "loads", "line_loads", "pressures",
                         "gravity", "request", "rotor", "backend", "nodes", "members"});
  Scene s;
  s.source = source;
  read_scene_table(r, root, s);
  if (s.is_frame()) {
    read_material(r, root, s);
    scene_detail::read_frame(r, root, s);
    read_backend_options(r, root, s);
    validate(s);
    return s;
  }
  for (const char* k : {"nodes", "members"})
    if (root.get(k)) r.fail(k, "a " + to_string(s.kind) + " has no [[" + k + "]] (a frame's: [scene] kind = \"frame\")");
  read_geometry(r, root, s);
  read_material(r, root, s);
  read_segment_materials(r, root, s);
  read_supports(r, root, s);
  read_masses(r, root, s);
  read_loads(r, root, s);
  read_distributed_loads(r, root, s);
  read_gravity(r, root, s);
  read_request(r, root, s);
  scene_detail::read_rotor(r, root, s);
  read_backend_options(r, root, s);
  validate(s);
  return s;
}

Scene load_scene(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const std::string name = path.string();
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw InputError(name, "", "no such file");
  if (fs::is_directory(st)) throw InputError(name, "", "is a directory, not a scene file (TOML)");
  if (!fs::is_regular_file(st)) throw InputError(name, "", "is not a regular file (a device or a pipe), not a scene file");
  const auto size = fs::file_size(path, ec);
  if (ec) throw InputError(name, "", "cannot read its size: " + ec.message());
  if (size > kMaxSceneBytes)
    throw InputError(name, "", fmt::format("{} bytes: larger than a scene file can be ({} bytes at most)", size, kMaxSceneBytes));
  if (size == 0) throw InputError(name, "", "is empty: a scene needs [scene], [geometry], [material] and [supports]");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(name, "", "cannot open file");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size)) throw InputError(name, "", "could not read the whole file");
  return parse_scene(text, name);
}

}  // namespace modalbench
