// Cross-sections and the pieces of a stepped beam ([[segments]]): each section table read the same
// way wherever it is written, each piece's material the scene's with its own overrides.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <toml++/toml.h>

#include "modalbench/scene.hpp"
#include "scene_reader.hpp"

namespace modalbench {

using scene_detail::Reader;

namespace {

/// One dimension of a section: a positive number, or where `end` is given (a piece of [[segments]])
/// `[start, end]`, both positive (a piece cannot taper to a point: its stiffness would vanish there).
/// Returns the start value; the end value into *end (the start's for a number).
double dimension(const Reader& r, const toml::table& t, const std::string& where, const std::string& key,
                 double* end, bool& varies) {
  const toml::node* n = t.get(key);
  const toml::array* a = n ? n->as_array() : nullptr;
  if (!a) {
    const double v = r.positive(t, where, key);
    if (end) *end = v;
    return v;
  }
  const std::string full = where + "." + key;
  if (!end)
    r.fail(full, "a section that varies along the beam is written per piece, in [[segments]] (here it is uniform)");
  if (a->size() != 2 || !a->get(0)->is_number() || !a->get(1)->is_number())
    r.fail(full, "must be a number or [start, end], two numbers (m, or m^2 and m^4 for a general section)");
  const double v0 = a->get(0)->value<double>().value(), v1 = a->get(1)->value<double>().value();
  for (int i = 0; i < 2; ++i) {
    const double v = i == 0 ? v0 : v1;
    if (!std::isfinite(v)) r.fail(fmt::format("{}[{}]", full, i), "must be finite");
    if (!(v > 0))
      r.fail(fmt::format("{}[{}]", full, i),
             fmt::format("must be > 0 (got {}): the dimension would reach zero or below inside the piece, where its "
                         "section vanishes (a taper to a point has no stiffness at its tip: end it at a small tip)",
                         v));
  }
  *end = v1;
  varies = varies || v0 != v1;
  return v0;
}

}  // namespace

void scene_detail::read_section(const Reader& r, const toml::table& t, const std::string& where, SectionSpec& sp,
                                Geometry& extent, SectionEnd* end, bool* varies_out) {
  const toml::node* shape_node = t.get("shape");
  if (!shape_node || !shape_node->is_string())
    r.fail(where + ".shape", "missing or not a string (rectangle, circle, tube or general)");
  const std::string shape = shape_node->as_string()->get();
  sp = SectionSpec{};
  SectionEnd tail;
  SectionSpec& e = tail.section;
  double* const no = nullptr;
  auto dim = [&](const std::string& key, double& at_end, bool& varies) {
    return dimension(r, t, where, key, end ? &at_end : no, varies);
  };
  bool varies = false;
  if (shape == "rectangle") {
    r.only_keys(t, where, {"shape", "width", "height"});
    sp.shape = SectionShape::Rectangle;
    extent.width = dim("width", tail.width, varies);
    extent.height = dim("height", tail.height, varies);
  } else if (shape == "circle") {
    r.only_keys(t, where, {"shape", "diameter"});
    sp.shape = SectionShape::Circle;
    sp.diameter = dim("diameter", e.diameter, varies);
    extent.width = extent.height = sp.diameter;
    tail.width = tail.height = e.diameter;
  } else if (shape == "tube") {
    r.only_keys(t, where, {"shape", "outer_diameter", "inner_diameter"});
    sp.shape = SectionShape::Tube;
    sp.diameter = dim("outer_diameter", e.diameter, varies);
    sp.inner_diameter = dim("inner_diameter", e.inner_diameter, varies);
    // Both ends suffice: under one profile the bore ratio d/D is monotone along the piece.
    if (!(sp.inner_diameter < sp.diameter))
      r.fail(where + ".inner_diameter", fmt::format("must be below outer_diameter ({} m; got {} m): a tube has a wall",
                                                    sp.diameter, sp.inner_diameter));
    if (end && !(e.inner_diameter < e.diameter))
      r.fail(where + ".inner_diameter",
             fmt::format("at the piece's end must be below outer_diameter there ({} m; got {} m): the bore would "
                         "reach the outside inside the piece",
                         e.diameter, e.inner_diameter));
    extent.width = extent.height = sp.diameter;
    tail.width = tail.height = e.diameter;
  } else if (shape == "general") {
    r.only_keys(t, where, {"shape", "area", "Iy", "Iz", "J"});
    sp.shape = SectionShape::General;
    sp.A = dim("area", e.A, varies);
    sp.Iy = dim("Iy", e.Iy, varies);
    sp.Iz = dim("Iz", e.Iz, varies);
    sp.J = dim("J", e.J, varies);
    extent.height = std::sqrt(12.0 * sp.Iy / sp.A);
    extent.width = sp.A / extent.height;
    tail.height = std::sqrt(12.0 * e.Iy / e.A);
    tail.width = e.A / tail.height;
  } else {
    r.fail(where + ".shape", "unknown shape '" + shape + "' (expected rectangle, circle, tube or general)");
  }
  e.shape = sp.shape;
  if (end) *end = tail;
  if (varies_out) *varies_out = varies;
}

double scene_detail::default_kappa(const Reader& r, const SectionSpec& sp, double nu, Theory theory,
                                   const std::string& key, std::string& note) {
  switch (sp.shape) {
    case SectionShape::Circle: {
      const double k = cowper_kappa_tube(nu, 0.0);
      note = fmt::format("Cowper's shear coefficient of a circle, 6 (1 + nu) / (7 + 6 nu) = {:.6g}", k);
      return k;
    }
    case SectionShape::Tube: {
      const double m = sp.inner_diameter / sp.diameter, k = cowper_kappa_tube(nu, m);
      note = fmt::format("Cowper's shear coefficient of a tube (d/D = {:.4g}) = {:.6g}", m, k);
      return k;
    }
    case SectionShape::General:
      if (theory == Theory::Timoshenko)
        r.fail(key, "required for a general section under Timoshenko theory (no shape to derive Cowper's shear "
                    "coefficient from)");
      note.clear();
      return 1.0;  // not used by the Euler-Bernoulli theory
    case SectionShape::Rectangle: break;
  }
  // 5/6 for rectangles, as every scene so far was solved (Cowper's would be 10 (1 + nu) / (12 + 11 nu)).
  note = "shear coefficient 5/6";
  return 5.0 / 6.0;
}

namespace {

const toml::array& segment_array(const Reader& r, const toml::table& root) {
  const toml::array* arr = root.get("segments")->as_array();
  if (!arr || arr->empty()) r.fail("segments", "must be a non-empty array of tables ([[segments]])");
  for (std::size_t i = 0; i < arr->size(); ++i)
    if (!arr->get(i)->is_table()) r.fail(fmt::format("segments[{}]", i), "must be a table");
  return *arr;
}

}  // namespace

void scene_detail::read_segment_sections(const Reader& r, const toml::table& root, Scene& s) {
  const toml::array& arr = segment_array(r, root);
  double x = 0;
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::string where = fmt::format("segments[{}]", i);
    const toml::table& t = *arr.get(i)->as_table();
    r.only_keys(t, where, {"length", "section", "material", "profile"});
    Segment seg;
    seg.x_from = x;
    x += r.positive(t, where, "length");
    seg.x_to = x;
    if (!t.get("section")) r.fail(where + ".section", "missing: every piece of a stepped beam gives its section");
    Geometry extent;
    SectionEnd end;
    bool varies = false;
    read_section(r, r.table(t, where, "section"), where + ".section", seg.section, extent, &end, &varies);
    seg.width = extent.width;
    seg.height = extent.height;
    if (t.get("profile")) {
      const std::string p = r.string(t, where, "profile");
      if (p != "linear" && p != "exponential")
        r.fail(where + ".profile", "unknown profile '" + p + "' (expected linear or exponential)");
      if (!varies)
        r.fail(where + ".profile",
               "given, but no dimension of the section varies (write one as [start, end] with two different values)");
      end.profile = p == "linear" ? Profile::Linear : Profile::Exponential;
    }
    if (varies) seg.end = end;
    s.segments.push_back(seg);
  }
  // The lengths must add up to the beam's, to rounding of the sum (n pieces: n ulps of L).
  const double L = s.geometry.length, slack = 4.0 * static_cast<double>(arr.size()) * 2.2e-16 * L;
  if (!(std::abs(x - L) <= slack))
    r.fail("segments", fmt::format("the pieces' lengths add up to {} m, not geometry.length = {} m", x, L));
  s.segments.back().x_to = L;
  // The scene's section is the first piece's (its default kappa); its extent the largest.
  s.cross_section = s.segments.front().section;
  for (const Segment& seg : s.segments) {
    s.geometry.width = std::max({s.geometry.width, seg.width, seg.end ? seg.end->width : 0.0});
    s.geometry.height = std::max({s.geometry.height, seg.height, seg.end ? seg.end->height : 0.0});
  }
}

bool scene_detail::read_material_overrides(const Reader& r, const toml::table& o, const std::string& where, Material& m) {
  r.only_keys(o, where, {"E", "G", "nu", "rho", "kappa"});
  if (o.get("E")) m.E = r.positive(o, where, "E");
  if (o.get("rho")) m.rho = r.positive(o, where, "rho");
  const auto G = r.opt_number(o, where, "G"), nu = r.opt_number(o, where, "nu");
  if (nu && !(*nu > -1.0 && *nu < 0.5)) r.fail(where + ".nu", fmt::format("must lie in (-1, 0.5) (got {})", *nu));
  if (G && !(*G > 0)) r.fail(where + ".G", fmt::format("must be > 0 (got {})", *G));
  // E, G and nu stay consistent: a piece that changes one of them says which other it keeps.
  if (G && nu && std::abs(m.E / (2.0 * (1.0 + *nu)) - *G) > 1e-6 * *G)
    r.fail(where + ".G", fmt::format("inconsistent with E and nu: E/(2(1+nu)) = {} Pa but G = {} Pa",
                                     m.E / (2.0 * (1.0 + *nu)), *G));
  if (G) m.G = *G;
  if (nu) m.nu = *nu;
  if (G && !nu) m.nu = m.E / (2.0 * m.G) - 1.0;
  else m.G = m.E / (2.0 * (1.0 + m.nu));  // nu given, or neither (E changed or not: nu kept)
  if (!(m.nu > -1.0 && m.nu < 0.5))
    r.fail(where + ".G", fmt::format("implies nu = E/(2G) - 1 = {} outside (-1, 0.5)", m.nu));
  if (auto k = r.opt_number(o, where, "kappa")) {
    if (!(*k > 0)) r.fail(where + ".kappa", fmt::format("must be > 0 (got {})", *k));
    m.kappa = *k;
    return true;
  }
  return false;
}

void scene_detail::read_segment_materials(const Reader& r, const toml::table& root, Scene& s) {
  if (s.segments.empty()) return;
  const toml::array& arr = segment_array(r, root);
  const toml::table& mat = r.table(root, "", "material");
  const bool kappa_given = mat.get("kappa") != nullptr;
  for (std::size_t i = 0; i < arr.size(); ++i) {
    const std::string where = fmt::format("segments[{}].material", i);
    const toml::table& t = *arr.get(i)->as_table();
    Segment& seg = s.segments[i];
    seg.material = s.material;
    Material& m = seg.material;
    if (t.get("material") &&
        scene_detail::read_material_overrides(r, r.table(t, fmt::format("segments[{}]", i), "material"), where, m))
      continue;
    if (kappa_given) continue;
    std::string note;
    m.kappa = default_kappa(r, seg.section, m.nu, s.theory, where + ".kappa", note);
    // A tapered tube's bore ratio may vary: Cowper's coefficient then follows it (Segment::kappa_at).
    seg.kappa_follows_shape = seg.end && seg.section.shape == SectionShape::Tube;
  }
  s.material = s.segments.front().material;
}

}  // namespace modalbench
