#pragma once
// Private to the scene parser and validator: reads typed values out of toml++ nodes, naming
// the file and the key in every complaint.

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <toml++/toml.h>

#include "modalbench/scene.hpp"

namespace modalbench::scene_detail {

/// Reads typed values out of toml++ nodes, naming file and key in every complaint.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const {
    throw InputError(source_, key, reason);
  }

  void only_keys(const toml::table& t, const std::string& where, std::set<std::string> allowed) const {
    for (auto&& [k, v] : t) {
      if (!allowed.count(std::string(k.str()))) {
        std::string list;
        for (auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(join(where, std::string(k.str())), "unknown key (allowed here: " + list + ")");
      }
    }
  }

  static std::string join(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
  }

  const toml::table& table(const toml::table& t, const std::string& where, const std::string& key) const {
    const toml::node* n = t.get(key);
    if (!n) fail(join(where, key), "missing table");
    if (!n->is_table()) fail(join(where, key), "must be a table");
    return *n->as_table();
  }

  std::optional<double> opt_number(const toml::table& t, const std::string& where, const std::string& key,
                                   bool allow_inf = false) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    return number_node(*n, join(where, key), allow_inf);
  }

  double number_node(const toml::node& n, const std::string& full, bool allow_inf = false) const {
    double v;
    if (auto i = n.as_integer()) v = static_cast<double>(i->get());
    else if (auto f = n.as_floating_point()) v = f->get();
    else fail(full, "must be a number");
    if (std::isnan(v)) fail(full, "is NaN");
    if (std::isinf(v) && !allow_inf) fail(full, "must be finite");
    return v;
  }

  double number(const toml::table& t, const std::string& where, const std::string& key,
                bool allow_inf = false) const {
    auto v = opt_number(t, where, key, allow_inf);
    if (!v) fail(join(where, key), "missing key");
    return *v;
  }

  double positive(const toml::table& t, const std::string& where, const std::string& key) const {
    double v = number(t, where, key);
    if (!(v > 0)) fail(join(where, key), fmt::format("must be > 0 (got {})", v));
    return v;
  }

  std::string string(const toml::table& t, const std::string& where, const std::string& key) const {
    const toml::node* n = t.get(key);
    if (!n) fail(join(where, key), "missing key");
    auto s = n->as_string();
    if (!s) fail(join(where, key), "must be a string");
    return s->get();
  }

  std::optional<long> opt_integer(const toml::table& t, const std::string& where, const std::string& key) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    auto i = n->as_integer();
    if (!i) fail(join(where, key), "must be an integer");
    return i->get();
  }

 private:
  std::string source_;
};

inline void check_range(const Reader& r, const std::string& key, double v, double lo, double hi) {
  if (!(v >= lo && v <= hi)) r.fail(key, fmt::format("must lie in [{}, {}] (got {})", lo, hi, v));
}

/// A support given as a name or a table of springs (scene_parse.cpp), `full` its key.
Support read_support_node(const Reader& r, const toml::node* n, const std::string& full, const Scene& s);

// Sections and the pieces of a stepped beam (scene_parse_segments.cpp).
/// A section table (`where` names it): its SectionSpec, and the extent (width, height) of
/// the section into `extent` (a rectangle's sides; a circle's or tube's outer diameter; a general
/// section's equivalent rectangle) at its start. With `end` (a piece of [[segments]]), a dimension
/// may be `[start, end]`: the section at the end into *end, and whether any dimension varies into
/// *varies; without it, such a dimension fails (a uniform section).
void read_section(const Reader& r, const toml::table& t, const std::string& where, SectionSpec& sp, Geometry& extent,
                  SectionEnd* end = nullptr, bool* varies = nullptr);
/// The default shear coefficient of a section (Cowper's for circles and tubes, from nu; 5/6 for
/// rectangles); a general section has none: under Timoshenko theory that fails naming `key`, else
/// 1 (unused). `note` says which was taken.
double default_kappa(const Reader& r, const SectionSpec& sp, double nu, Theory theory, const std::string& key,
                     std::string& note);
/// [[segments]]: each piece's length and section (before [material]: the first piece's section
/// is the scene's cross_section, its default kappa's shape).
void read_segment_sections(const Reader& r, const toml::table& root, Scene& s);
/// A piece's or member's `material = {...}` (`where` names it): E, G, nu, rho, kappa over the
/// scene's `m`, E, G and nu kept consistent. Returns whether kappa was given.
bool read_material_overrides(const Reader& r, const toml::table& o, const std::string& where, Material& m);
/// [[segments]] material = {...}: each piece's material, the scene's with the piece's overrides.
void read_segment_materials(const Reader& r, const toml::table& root, Scene& s);

// What a structure carries besides its ends (scene_parse_structure.cpp).
/// [[supports.points]] of the [supports] table `sup`.
void read_point_supports(const Reader& r, const toml::table& sup, Scene& s);
/// [[masses]].
void read_masses(const Reader& r, const toml::table& root, Scene& s);
/// [[line_loads]] (beams) and [[pressures]] (plates).
void read_distributed_loads(const Reader& r, const toml::table& root, Scene& s);
/// [request] modes and tolerance (the table `t`), as every kind of scene takes them.
void read_modes_and_tolerance(const Reader& r, const toml::table& t, Scene& s);
/// [gravity].
void read_gravity(const Reader& r, const toml::table& root, Scene& s);

/// [rotor] (scene_parse_rotor.cpp).
void read_rotor(const Reader& r, const toml::table& root, Scene& s);
/// The rules of a rotor scene (scene_parse_rotor.cpp; validate() calls it).
void validate_rotor(const Reader& r, const Scene& s);

/// A frame's nodes, members, supports, masses, loads, gravity and request (scene_parse_frame.cpp),
/// after [scene] and [material].
void read_frame(const Reader& r, const toml::table& root, Scene& s);
/// The rules of a frame scene (scene_parse_frame.cpp; validate() calls it for frames).
void validate_frame(const Reader& r, const Scene& s);

/// [request.transient] (scene_parse_transient.cpp).
void read_transient(const Reader& r, const toml::node& n, Scene& s);

}  // namespace modalbench::scene_detail
