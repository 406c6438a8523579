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

void scene_detail::read_section(const Reader& r, const toml::table& t, const std::string& where, SectionSpec& sp,
                                Geometry& extent) {
  const toml::node* shape_node = t.get("shape");
  if (!shape_node || !shape_node->is_string())
    r.fail(where + ".shape", "missing or not a string (rectangle, circle, tube or general)");
  const std::string shape = shape_node->as_string()->get();
  sp = SectionSpec{};
  if (shape == "rectangle") {
    r.only_keys(t, where, {"shape", "width", "height"});
    sp.shape = SectionShape::Rectangle;
    extent.width = r.positive(t, where, "width");
    extent.height = r.positive(t, where, "height");
  } else if (shape == "circle") {
    r.only_keys(t, where, {"shape", "diameter"});
    sp.shape = SectionShape::Circle;
    sp.diameter = r.positive(t, where, "diameter");
    extent.width = extent.height = sp.diameter;
  } else if (shape == "tube") {
    r.only_keys(t, where, {"shape", "outer_diameter", "inner_diameter"});
    sp.shape = SectionShape::Tube;
    sp.diameter = r.positive(t, where, "outer_diameter");
    sp.inner_diameter = r.positive(t, where, "inner_diameter");
    if (!(sp.inner_diameter < sp.diameter))
      r.fail(where + ".inner_diameter", fmt::format("must be below outer_diameter ({} m; got {} m): a tube has a wall",
                                                    sp.diameter, sp.inner_diameter));
    extent.width = extent.height = sp.diameter;
  } else if (shape == "general") {
    r.only_keys(t, where, {"shape", "area", "Iy", "Iz", "J"});
    sp.shape = SectionShape::General;
    sp.A = r.positive(t, where, "area");
    sp.Iy = r.positive(t, where, "Iy");
    sp.Iz = r.positive(t, where, "Iz");
    sp.J = r.positive(t, where, "J");
    extent.height = std::sqrt(12.0 * sp.Iy / sp.A);
    extent.width = sp.A / extent.height;
  } else {
    r.fail(where + ".shape", "unknown shape '" + shape + "' (expected rectangle, circle, tube or general)");
  }
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
    r.only_keys(t, where, {"length", "section", "material"});
    Segment seg;
    seg.x_from = x;
    x += r.positive(t, where, "length");
    seg.x_to = x;
    if (!t.get("section")) r.fail(where + ".section", "missing: every piece of a stepped beam gives its section");
    Geometry extent;
    read_section(r, r.table(t, where, "section"), where + ".section", seg.section, extent);
    seg.width = extent.width;
    seg.height = extent.height;
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
    s.geometry.width = std::max(s.geometry.width, seg.width);
    s.geometry.height = std::max(s.geometry.height, seg.height);
  }
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
    if (t.get("material")) {
      const toml::table& o = r.table(t, fmt::format("segments[{}]", i), "material");
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
        continue;
      }
    }
    if (kappa_given) continue;
    std::string note;
    m.kappa = default_kappa(r, seg.section, m.nu, s.theory, where + ".kappa", note);
  }
  s.material = s.segments.front().material;
}

}  // namespace modalbench
