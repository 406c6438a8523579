// [rotor]: a spinning shaft's spin speeds and the frame its whirl is seen from, and the rules a
// rotor scene obeys.
#include "scene_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace modalbench {

namespace {

using scene_detail::Reader;

constexpr long kMaxSpins = 10000;

/// spin = [a, b, ...] or { from = a, to = b, num = n } (n evenly spaced speeds, both ends included).
std::vector<double> read_spin(const Reader& r, const toml::node& n) {
  const std::string key = "rotor.spin";
  std::vector<double> out;
  if (const auto* arr = n.as_array()) {
    if (arr->empty()) r.fail(key, "give at least one spin speed, rad/s");
    if (static_cast<long>(arr->size()) > kMaxSpins) r.fail(key, fmt::format("at most {} spin speeds", kMaxSpins));
    for (std::size_t i = 0; i < arr->size(); ++i) out.push_back(r.number_node(*arr->get(i), fmt::format("{}[{}]", key, i)));
    return out;
  }
  const auto* t = n.as_table();
  if (!t) r.fail(key, "must be an array of speeds, rad/s, or a table { from = A, to = B, num = N }");
  r.only_keys(*t, key, {"from", "to", "num"});
  const double from = r.number(*t, key, "from"), to = r.number(*t, key, "to");
  const auto num = r.opt_integer(*t, key, "num");
  if (!num) r.fail(key + ".num", "missing key (how many evenly spaced speeds, ends included)");
  if (*num < 2 || *num > kMaxSpins) r.fail(key + ".num", fmt::format("must lie in [2, {}] (got {})", kMaxSpins, *num));
  if (!(to > from)) r.fail(key + ".to", fmt::format("must be > from (got from = {}, to = {})", from, to));
  const double steps = static_cast<double>(*num - 1);
  for (long i = 0; i < *num; ++i) out.push_back(i + 1 == *num ? to : from + (to - from) * static_cast<double>(i) / steps);
  return out;
}

}  // namespace

void scene_detail::read_rotor(const Reader& r, const toml::table& root, Scene& s) {
  const toml::node* n = root.get("rotor");
  if (!n) return;
  const auto* t = n->as_table();
  if (!t) r.fail("rotor", "must be a table ([rotor] spin = [...], frame = \"stationary\" | \"rotating\")");
  r.only_keys(*t, "rotor", {"spin", "frame"});
  Rotor rotor;
  const toml::node* sp = t->get("spin");
  if (!sp) r.fail("rotor.spin", "missing key (spin speeds about +x, rad/s)");
  rotor.spin = read_spin(r, *sp);
  if (t->get("frame")) {
    const std::string f = r.string(*t, "rotor", "frame");
    if (f == "stationary") rotor.frame = Rotor::Frame::Stationary;
    else if (f == "rotating") rotor.frame = Rotor::Frame::Rotating;
    else r.fail("rotor.frame", "unknown frame '" + f + "' (expected stationary or rotating)");
  }
  s.rotor = rotor;
}

void scene_detail::validate_rotor(const Reader& r, const Scene& s) {
  if (!s.rotor) return;
  if (!s.is_beam() || s.physics != Physics::Lateral)
    r.fail("rotor", fmt::format("a rotor is a beam of physics 'lateral' (this scene is a {} of physics '{}')",
                                to_string(s.kind), to_string(s.physics)));
  const std::vector<double>& spin = s.rotor->spin;
  if (spin.empty()) r.fail("rotor.spin", "give at least one spin speed, rad/s");
  if (static_cast<long>(spin.size()) > kMaxSpins) r.fail("rotor.spin", fmt::format("at most {} spin speeds", kMaxSpins));
  for (std::size_t i = 0; i < spin.size(); ++i) {
    const std::string key = fmt::format("rotor.spin[{}]", i);
    if (!(std::isfinite(spin[i]) && spin[i] >= 0))
      r.fail(key, fmt::format("must be finite and >= 0 rad/s (the spin is about +x; got {})", spin[i]));
    if (i > 0 && !(spin[i] > spin[i - 1])) r.fail(key, "spin speeds must be distinct and ascending");
  }
  if (s.request.modes < 1)
    r.fail("request.modes", "a rotor needs request.modes >= 1: how many whirl frequencies at each spin");
  if (s.rotor->frame == Rotor::Frame::Stationary)
    for (std::size_t i = 0; i < s.beam_pieces().size(); ++i) {
      const Segment piece = s.beam_pieces()[i];
      for (double x : {piece.x_from, piece.x_to}) {  // a tapered piece at both ends
        const Section sec = piece.properties_at(x);
        if (std::abs(sec.Iy - sec.Iz) > 1e-12 * std::max(sec.Iy, sec.Iz))
          r.fail("rotor.frame", fmt::format("a shaft whose section has Iy != Iz ({:.6g} and {:.6g} m^4{}) has equations "
                                            "periodic in time in the stationary frame: use frame = \"rotating\"",
                                            sec.Iy, sec.Iz, s.is_stepped() ? fmt::format(", segments[{}]", i) : ""));
      }
    }
  for (std::size_t i = 0; i < s.masses.size(); ++i)
    if (std::abs(s.masses[i].Jy - s.masses[i].Jz) > 1e-12 * std::max(s.masses[i].Jy, s.masses[i].Jz))
      r.fail(fmt::format("masses[{}].Jz", i), fmt::format("a disc on a rotor has one diametral inertia: Jy = Jz (got {} "
                                                          "and {} kg m^2)", s.masses[i].Jy, s.masses[i].Jz));
}

}  // namespace modalbench
