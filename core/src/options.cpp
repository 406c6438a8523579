// Back-end options: the scene's [backend.NAME] table and the command line, checked against the
// back-end's OptionSpecs and resolved (given or default) for one solve.
#include "solve_internal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace modalbench {

namespace {

bool parse_bool(const std::string& t, bool& out) {
  if (t == "true") out = true;
  else if (t == "false") out = false;
  else return false;
  return true;
}

/// Checks `text` against `spec`; returns the reason it is not valid, or "".
std::string check_option(const OptionSpec& spec, const std::string& text) {
  switch (spec.type) {
    case OptionSpec::Type::Bool: {
      bool b;
      return parse_bool(text, b) ? "" : "must be true or false (got '" + text + "')";
    }
    case OptionSpec::Type::Choice: {
      if (std::find(spec.choices.begin(), spec.choices.end(), text) != spec.choices.end()) return "";
      std::string list;
      for (const auto& c : spec.choices) list += (list.empty() ? "" : ", ") + c;
      return "must be one of " + list + " (got '" + text + "')";
    }
    case OptionSpec::Type::Integer:
    case OptionSpec::Type::Number: {
      const bool integer = spec.type == OptionSpec::Type::Integer;
      char* end = nullptr;
      errno = 0;
      const double v = integer ? static_cast<double>(std::strtoll(text.c_str(), &end, 10)) : std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
        return fmt::format("must be {} (got '{}')", integer ? "an integer" : "a finite number", text);
      if (!(v >= spec.min && v <= spec.max)) return fmt::format("must lie in [{}, {}] (got {})", spec.min, spec.max, text);
      return "";
    }
  }
  return "";
}

}  // namespace

ResolvedOptions detail::resolve_options(const Solver& solver, const Scene& scene, const Options& options) {
  const std::vector<OptionSpec> specs = solver.option_specs();
  ResolvedOptions out;
  for (const auto& spec : specs) out.entries.push_back({spec, spec.default_value, "default"});
  std::string allowed;
  for (const auto& spec : specs) allowed += (allowed.empty() ? "" : ", ") + spec.key;
  if (allowed.empty()) allowed = "none";
  auto apply = [&](const std::string& key, const std::string& text, const std::string& source,
                   const std::string& full_key) {
    for (auto& e : out.entries)
      if (e.spec.key == key) {
        const std::string why = check_option(e.spec, text);
        if (!why.empty()) throw InputError(source, full_key, why);
        e.text = text;
        e.source = source;
        return;
      }
    throw InputError(source, full_key, "unknown option of back-end " + solver.name() + " (allowed: " + allowed + ")");
  };
  if (auto it = scene.backend_options.find(solver.name()); it != scene.backend_options.end())
    for (const auto& o : it->second)
      apply(o.key, o.text, scene.source.empty() ? "<scene>" : scene.source, "backend." + solver.name() + "." + o.key);
  // Named as the caller wrote them: `--option KEY` on the command line, `options.KEY` elsewhere.
  for (const auto& [key, text] : options.backend)
    apply(key, text, options.origin, options.origin == "command line" ? "--option " + key : "options." + key);
  return out;
}

const ResolvedOptions::Entry& ResolvedOptions::find(const std::string& key, OptionSpec::Type type) const {
  for (const auto& e : entries)
    if (e.spec.key == key) {
      if (e.spec.type != type) throw std::logic_error("option '" + key + "' read with the wrong type");
      return e;
    }
  throw std::logic_error("option '" + key + "' is not declared by the back-end");
}

bool ResolvedOptions::get_bool(const std::string& key) const {
  bool b = false;
  parse_bool(find(key, OptionSpec::Type::Bool).text, b);
  return b;
}
long ResolvedOptions::get_integer(const std::string& key) const {
  return std::strtol(find(key, OptionSpec::Type::Integer).text.c_str(), nullptr, 10);
}
double ResolvedOptions::get_number(const std::string& key) const {
  return std::strtod(find(key, OptionSpec::Type::Number).text.c_str(), nullptr);
}
const std::string& ResolvedOptions::get_choice(const std::string& key) const {
  return find(key, OptionSpec::Type::Choice).text;
}
std::string ResolvedOptions::given() const {
  std::string out;
  for (const auto& e : entries)
    if (e.source != "default") out += fmt::format("{}{}={} ({})", out.empty() ? "" : ", ", e.spec.key, e.text, e.source);
  return out.empty() ? "defaults" : out;
}

}  // namespace modalbench
