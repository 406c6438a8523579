// [request.transient] (scene.hpp, TransientRequest): the time function of the loads, the output
// grid, the damping and the static correction. Their ranges are checked by validate().
#include <fmt/format.h>

#include "scene_reader.hpp"

namespace modalbench::scene_detail {

namespace {

std::vector<double> number_array(const Reader& r, const toml::table& t, const std::string& where,
                                 const std::string& key) {
  const toml::node* n = t.get(key);
  if (!n) r.fail(Reader::join(where, key), "missing key");
  const toml::array* a = n->as_array();
  if (!a || a->empty()) r.fail(Reader::join(where, key), "must be a non-empty array of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < a->size(); ++i)
    out.push_back(r.number_node(*a->get(i), fmt::format("{}[{}]", Reader::join(where, key), i)));
  return out;
}

void read_load(const Reader& r, const toml::table& t, TransientRequest& tr) {
  const std::string where = "request.transient";
  const toml::node* n = t.get("load");
  if (!n) r.fail(where + ".load", "missing key (step, impulse, ramp, harmonic, or { time = [...], factor = [...] })");
  if (const toml::table* tab = n->as_table()) {
    r.only_keys(*tab, where + ".load", {"time", "factor"});
    tr.load = TransientRequest::Load::Table;
    tr.time = number_array(r, *tab, where + ".load", "time");
    tr.factor = number_array(r, *tab, where + ".load", "factor");
  } else {
    const std::string name = r.string(t, where, "load");
    if (name == "step")
      tr.load = TransientRequest::Load::Step;
    else if (name == "impulse")
      tr.load = TransientRequest::Load::Impulse;
    else if (name == "ramp")
      tr.load = TransientRequest::Load::Ramp;
    else if (name == "harmonic")
      tr.load = TransientRequest::Load::Harmonic;
    else
      r.fail(where + ".load",
             fmt::format("unknown '{}' (step, impulse, ramp, harmonic, or a table of time and factor)", name));
  }
  const bool ramp = tr.load == TransientRequest::Load::Ramp, harmonic = tr.load == TransientRequest::Load::Harmonic;
  if (ramp)
    tr.rise = r.number(t, where, "rise");
  else if (t.get("rise"))
    r.fail(where + ".rise", "only a ramp has a rise time");
  if (harmonic)
    tr.omega = r.number(t, where, "omega");
  else if (t.get("omega"))
    r.fail(where + ".omega", "only a harmonic load has a circular frequency");
}

void read_damping(const Reader& r, const toml::table& t, TransientRequest& tr) {
  const std::string key = "request.transient.damping";
  const toml::node* n = t.get("damping");
  if (!n) return;
  const toml::table* d = n->as_table();
  if (!d || d->size() != 1) r.fail(key, "must be { modal = zeta } or { rayleigh = [alpha, beta] }");
  r.only_keys(*d, key, {"modal", "rayleigh"});
  if (d->get("modal")) {
    tr.damping = TransientRequest::Damping::Modal;
    tr.zeta = r.number(*d, key, "modal");
  } else {
    const std::vector<double> ab = number_array(r, *d, key, "rayleigh");
    if (ab.size() != 2) r.fail(key + ".rayleigh", "must be [alpha (1/s), beta (s)]");
    tr.damping = TransientRequest::Damping::Rayleigh;
    tr.alpha = ab[0], tr.beta = ab[1];
  }
}

}  // namespace

void read_transient(const Reader& r, const toml::node& n, Scene& s) {
  const std::string where = "request.transient";
  const toml::table* t = n.as_table();
  if (!t) r.fail(where, "must be a table");
  r.only_keys(*t, where, {"duration", "step", "load", "rise", "omega", "damping", "static_correction", "moments"});
  TransientRequest tr;
  tr.duration = r.number(*t, where, "duration");
  tr.step = r.number(*t, where, "step");
  read_load(r, *t, tr);
  read_damping(r, *t, tr);
  if (const toml::node* sc = t->get("static_correction")) {
    const auto b = sc->as_boolean();
    if (!b) r.fail(where + ".static_correction", "must be true or false");
    tr.static_correction = b->get();
  }
  if (const toml::node* mo = t->get("moments")) {
    const auto* b = mo->as_boolean();
    if (!b) r.fail(where + ".moments", "must be true or false");
    tr.moments = b->get() ? TransientRequest::Moments::Asked : TransientRequest::Moments::Off;
  }
  s.request.transient = tr;
}

}  // namespace modalbench::scene_detail
