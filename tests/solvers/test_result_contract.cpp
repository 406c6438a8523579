// The result contract (result.hpp), checked on every registered back-end and every built-in
// scene: one meaning per Summary field, the worst status wins, options validated with the file,
// key and reason.
#define BOOST_TEST_MODULE result_contract
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>

#include "modalbench/json_output.hpp"
#include "modalbench/registry.hpp"
#include "solve_options.hpp"

using namespace modalbench;

namespace {

std::vector<Scene> builtin_scenes() {
  std::vector<Scene> v;
  for (const auto& e : std::filesystem::directory_iterator(MODALBENCH_SCENES_DIR))
    if (e.path().extension() == ".toml") v.push_back(load_scene(e.path()));
  std::sort(v.begin(), v.end(), [](const Scene& a, const Scene& b) { return a.name < b.name; });
  return v;
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_backend_honours_every_field) {
  const Registry reg = make_default_registry();
  int runs = 0;
  for (const Scene& sc : builtin_scenes())
    for (const Solver* s : reg.all()) {
      const Result r = s->solve(sc, testing::default_mesh(*s, sc), Options{});
      const Summary& m = r.summary;
      BOOST_TEST_CONTEXT(s->name() << " on " << sc.name << " (" << to_string(m.status) << ": " << m.message << ")") {
        ++runs;
        // Status and message: a message whenever the status is not success.
        BOOST_TEST((m.status == Status::Success) == m.message.empty());
        BOOST_TEST(m.method_requested == "defaults");
        if (m.status == Status::Unsupported || m.status == Status::InvalidInput) continue;
        BOOST_TEST(!m.method.empty());
        // unknowns: the size of the system solved; every back-end here solves one, except the
        // closed-form Navier plate of `exact`.
        BOOST_TEST(m.unknowns >= 0);
        if (s->name() != "exact") BOOST_TEST(m.unknowns > 0);
        BOOST_TEST((m.threads >= 1 && m.threads <= 2));
        // max_backward_error: not measured (NaN) or a backward error that passed the back-end's check.
        if (!std::isnan(m.max_backward_error) && r.ok()) {
          BOOST_TEST(m.max_backward_error >= 0.0);
          BOOST_TEST(m.max_backward_error <= 1e-8);
        }
        // Phases: one vocabulary, each charged once (they never sum to more than the total).
        const auto& t = m.timings_s;
        for (double p : {t.build, t.modes, t.statics, t.frf}) BOOST_TEST(p >= 0.0);
        BOOST_TEST(t.build + t.modes + t.statics + t.frf <= m.total_time_s * 1.0001 + 1e-6);
        const Capability cap = s->supports(sc);
        if (sc.request.modes > 0 && cap.modes) BOOST_TEST(t.modes > 0.0);
        if (!sc.request.probes.empty() && cap.statics && r.ok()) BOOST_TEST(t.statics > 0.0);
        if (sc.request.frf && cap.frf) BOOST_TEST(t.frf > 0.0);
        // Numbers: parallel, ascending, finite on success.
        BOOST_TEST(r.mode_families.size() == r.frequencies_rad_s.size());
        for (std::size_t i = 1; i < r.frequencies_rad_s.size(); ++i)
          BOOST_TEST(r.frequencies_rad_s[i] >= r.frequencies_rad_s[i - 1]);
        // JSON carries each field under its one name.
        const auto j = to_json(sc, s->name(), testing::default_mesh(*s, sc), r);
        for (const char* key : {"unknowns", "threads", "max_backward_error", "diagnostics", "timing_s"})
          BOOST_TEST(j.contains(key), key);
        for (const char* key : {"requested", "used", "fallbacks", "converges_to_scene_theory"})
          BOOST_TEST(j["method"].contains(key), key);
        // The exact back-end is the scene's theory: its own limit.
        if (s->name() == "exact") BOOST_TEST(m.converges_to_scene_theory);
        for (const char* key : {"build", "modes", "statics", "frf", "total"}) BOOST_TEST(j["timing_s"].contains(key), key);
      }
    }
  BOOST_TEST(runs == static_cast<int>(builtin_scenes().size() * reg.all().size()));
}

BOOST_AUTO_TEST_CASE(the_worst_status_wins_and_every_message_is_kept) {
  Summary s;
  s.raise(Status::NumericalIssue, "first");
  s.raise(Status::NotConverged, "second");
  BOOST_TEST((s.status == Status::NumericalIssue));
  s.raise(Status::InvalidInput, "third");
  BOOST_TEST((s.status == Status::InvalidInput));
  BOOST_TEST(s.message == "first; second; third");
  for (Status a : {Status::Success, Status::NotConverged, Status::NumericalIssue, Status::ResourceLimit,
                   Status::Unsupported, Status::InvalidInput})
    BOOST_TEST(severity(a) >= severity(Status::Success));
  BOOST_TEST(severity(Status::ResourceLimit) > severity(Status::NumericalIssue));
}

BOOST_AUTO_TEST_CASE(backend_options_are_validated_with_file_key_and_reason) {
  const Registry reg = make_default_registry();
  Scene sc = load_scene(std::string(MODALBENCH_SCENES_DIR) + "/paper_fixed_beam.toml");
  for (const Solver* s : reg.all()) {
    BOOST_TEST_CONTEXT(s->name()) {
      // Every declared default is itself valid: the solve with all defaults given explicitly
      // equals the solve with none.
      Options o;
      for (const auto& spec : s->option_specs()) o.backend.emplace_back(spec.key, spec.default_value);
      const Result a = s->solve(sc, testing::default_mesh(*s, sc), o), b = s->solve(sc, testing::default_mesh(*s, sc), Options{});
      BOOST_TEST((a.summary.status == b.summary.status));
      BOOST_TEST(a.frequencies_rad_s == b.frequencies_rad_s);
      // An unknown key in the scene: file, dotted key, reason.
      Scene bad = sc;
      bad.backend_options[s->name()] = {{"no_such_option", "1"}};
      const Result r = s->solve(bad, testing::default_mesh(*s, bad), Options{});
      BOOST_TEST((r.summary.status == Status::InvalidInput));
      BOOST_TEST(r.summary.message.find(sc.source + ": backend." + s->name() + ".no_such_option: unknown option") !=
                 std::string::npos);
    }
  }
  // A bad value: named with its range.
  Options o;
  o.backend = {{"dense_limit", "-3"}};
  const Result r = reg.get("rfem").solve(sc, Discretization{{16}}, o);
  BOOST_TEST((r.summary.status == Status::InvalidInput));
  BOOST_TEST(r.summary.message.find("command line: --option dense_limit: must lie in [1, 1000000] (got -3)") !=
             std::string::npos);
  // A table for a back-end that does not exist.
  Scene odd = sc;
  odd.backend_options["fem3d"] = {{"x", "1"}};
  BOOST_CHECK_THROW(reg.check_backend_tables(odd), InputError);
}
