// modalbench: solve a beam or plate scene with one of several methods and compare them.
//
// Sample runs:
//   modalbench list
//   modalbench solve scenes/paper_fixed_beam.toml --backend exact --json
//   modalbench compare --out report
//   modalbench study spec.toml --out study   (the Python study driver of this build)

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "campbell_text.hpp"
#include "rom_command.hpp"
#include "modalbench/harness/calculix.hpp"
#include "modalbench/harness/comparison.hpp"
#include "modalbench/json_output.hpp"
#include "modalbench/registry.hpp"
#include "modalbench/harness/report.hpp"
#include "modalbench/harness/stability.hpp"
#include "modalbench/harness/vtk.hpp"

namespace mb = modalbench;

namespace {

std::string scenes_dir() {
  if (const char* env = std::getenv("MODALBENCH_SCENES")) return env;
  return MODALBENCH_SCENES_DIR;
}

/// A scene argument: a path as given where it names a file; otherwise a built-in scene's name
/// (`paper_fixed_beam` or `paper_fixed_beam.toml`, as `modalbench list` shows them).
std::string resolve_scene(const std::string& arg) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(arg, ec) || arg.find('/') != std::string::npos) return arg;
  for (const std::string& name : {arg, arg + ".toml"}) {
    const fs::path builtin = fs::path(scenes_dir()) / name;
    if (fs::is_regular_file(builtin, ec)) return builtin.string();
  }
  return arg;  // load_scene names what is missing
}

/// Solves on a worker thread and waits at most twice --max-time: the estimates that refuse a
/// request up front are fitted, not bounds, and an iteration can stall (Lanczos restarts). A solve
/// still running then is abandoned: the process prints a resource-limit result and exits with 2.
mb::Result solve_within(const mb::Solver& solver, const mb::Scene& scene, const mb::Discretization& mesh,
                        const mb::Options& opt, bool json) {
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  mb::Result result;
  std::thread worker([&] {
    mb::Result r = solver.solve(scene, mesh, opt);
    std::lock_guard<std::mutex> lock(m);
    result = std::move(r);
    done = true;
    cv.notify_one();
  });
  std::unique_lock<std::mutex> lock(m);
  const double hard_s = 2.0 * opt.max_time_s;
  if (!cv.wait_for(lock, std::chrono::duration<double>(hard_s), [&] { return done; })) {
    mb::Result stopped;
    stopped.summary.mesh = mesh.spec();
    stopped.summary.raise(mb::Status::ResourceLimit,
                          fmt::format("{}: stopped after {:g} s, twice the time limit (--max-time {:g} s): the solve "
                                      "ran far beyond its estimate; nothing of it is reported",
                                      solver.name(), hard_s, opt.max_time_s));
    if (json) std::cout << mb::to_json(scene, solver.name(), mesh, stopped).dump(2) << std::endl;
    std::cerr << "modalbench: " << stopped.summary.message << std::endl;
    std::_Exit(2);  // the worker cannot be interrupted; leave without unwinding it
  }
  lock.unlock();
  worker.join();
  return result;
}

int run_list(const mb::Registry& reg) {
  std::cout << "back-ends:\n";
  for (const auto* s : reg.all()) std::cout << fmt::format("  {:<14} {}\n", s->name(), s->description());
  std::cout << "built-in scenes (solve one by name: modalbench solve NAME --backend B):\n";
  for (const auto& f : mb::scene_files(scenes_dir())) {
    const std::string name = std::filesystem::path(f).stem().string();
    try {
      const mb::Scene sc = mb::load_scene(f);
      std::cout << fmt::format("  {:<32} {} {} ({})\n", name, mb::to_string(sc.kind), mb::to_string(sc.physics),
                               mb::to_string(sc.theory));
    } catch (const mb::InputError& e) {
      std::cout << fmt::format("  {:<32} INVALID: {}\n", name, e.what());
    }
  }
  return 0;
}

int run_options(const mb::Registry& reg, const std::string& only) {
  if (!only.empty()) {
    const auto names = reg.names();
    if (std::find(names.begin(), names.end(), only) == names.end()) {
      std::cerr << "modalbench: options: unknown back-end '" << only << "'\n";
      return 2;
    }
  }
  for (const auto* s : reg.all()) {
    if (!only.empty() && s->name() != only) continue;
    const auto specs = s->option_specs();
    std::cout << fmt::format("{} ([backend.{}] in a scene, --option KEY=VALUE on the command line):\n", s->name(),
                             s->name());
    if (specs.empty()) std::cout << "  (none)\n";
    for (const auto& o : specs) {
      std::string range;
      switch (o.type) {
        case mb::OptionSpec::Type::Bool: range = "true | false"; break;
        case mb::OptionSpec::Type::Choice:
          for (const auto& c : o.choices) range += (range.empty() ? "" : " | ") + c;
          break;
        case mb::OptionSpec::Type::Integer: range = fmt::format("integer in [{}, {}]", o.min, o.max); break;
        case mb::OptionSpec::Type::Number: range = fmt::format("number in [{}, {}]", o.min, o.max); break;
      }
      std::cout << fmt::format("  {} = {}   ({})\n      {}\n", o.key, o.default_value, range, o.help);
    }
  }
  return 0;
}

/// The mesh kept, and where it came from: "64 (given)", "256 (default)", "512 (default 256, refined)".
std::string mesh_line(const mb::Discretization& asked, bool given, const mb::Result& r) {
  const std::string kept = r.summary.mesh.empty() ? asked.spec() : r.summary.mesh;
  if (kept == "-") return "-";
  if (given) return kept + " (given)";
  return kept == asked.spec() ? kept + " (default)" : fmt::format("{} (default {}, refined)", kept, asked.spec());
}

/// A probe's stress resultants (sign conventions: result.hpp, InternalForces), "" where not given.
std::string forces_line(const mb::Scene& scene, const mb::Deflection& d) {
  if (!d.has_forces) return "";
  const auto& f = d.forces;
  if (scene.is_plate())
    return fmt::format("\n      moments mx = {:.6e}, my = {:.6e}, mxy = {:.6e} N*m/m", f.mx, f.my, f.mxy);
  std::string out = fmt::format("\n      {}My = {:.6e} N*m (sagging +), Qz = dMy/dx = {:.6e} N",
                                scene.is_frame() ? "member axes: " : "", f.My, f.Qz);
  if (mb::carries_axial(scene.physics)) out += fmt::format(", N = {:.6e} N", f.N);
  if (mb::carries_xy(scene.physics)) out += fmt::format(", Mz = {:.6e} N*m, Qy = {:.6e} N", f.Mz, f.Qy);
  if (mb::carries_torsion(scene.physics)) out += fmt::format(", T = {:.6e} N*m", f.T);
  return out;
}

/// A probe's deflection in the components the scene carries.
std::string probe_line(const mb::Scene& scene, const mb::Deflection& d) {
  if (scene.is_plate())
    return fmt::format("({:g}, {:g}) m: w = {:.8e} m, theta_x = {:.8e} rad, theta_y = {:.8e} rad", d.position[0],
                       d.position[1], d.w, d.theta_x, d.theta_y);
  if (scene.is_frame()) {
    std::string out = fmt::format("{} ({:g}, {:g}, {:g}) m: u = {:.8e} m, w = {:.8e} m, theta_y = {:.8e} rad", d.probe,
                                  d.point[0], d.point[1], d.point[2], d.u, d.w, d.theta_y);
    if (mb::carries_xy(scene.physics))
      out += fmt::format(", v = {:.8e} m, theta_x = {:.8e} rad, theta_z = {:.8e} rad", d.v, d.theta_x, d.theta_z);
    return out;
  }
  std::string out = fmt::format("x = {:g} m: w = {:.8e} m, theta_y = {:.8e} rad", d.position[0], d.w, d.theta_y);
  if (mb::carries_axial(scene.physics)) out += fmt::format(", u = {:.8e} m", d.u);
  if (mb::carries_xy(scene.physics)) out += fmt::format(", v = {:.8e} m, theta_z = {:.8e} rad", d.v, d.theta_z);
  if (mb::carries_torsion(scene.physics)) out += fmt::format(", theta_x = {:.8e} rad", d.theta_x);
  return out;
}

/// The transient's peaks per probe (the histories are in the JSON).
void print_transient(const mb::Scene& scene, const mb::Transient& tr, bool verbose) {
  std::cout << fmt::format("  transient ({}): {} modes{}, {} output times to {:g} s; truncation estimate {:.2g} of the "
                           "largest peak\n",
                           tr.load, tr.modes_used, tr.static_correction ? " + static correction" : "", tr.time_s.size(),
                           tr.time_s.back(), tr.error_estimate);
  for (std::size_t p = 0; p < tr.peaks.size(); ++p) {
    const auto& at = scene.request.probes[p];
    std::cout << fmt::format("  peak {}: w = {:.8e} m at t = {:.8g} s\n",
                             scene.is_beam() ? fmt::format("x = {:g} m", at[0]) : fmt::format("({:g}, {:g}) m", at[0], at[1]),
                             tr.peaks[p].w, tr.peaks[p].time_s);
    if (p < tr.moment_peaks.size())
      std::cout << fmt::format("       My = {:.8e} N m at t = {:.8g} s\n", tr.moment_peaks[p].w, tr.moment_peaks[p].time_s);
  }
  if (!tr.moments.empty())
    std::cout << fmt::format("  moment histories: truncation estimate {:.2g} of the largest |My| peak\n",
                             tr.moment_error_estimate);
  if (verbose) std::cout << "  transient: " << tr.note << " (histories: --json)\n";
}

/// The result as text: status, the model solved and whether it is the scene's theory, the mesh
/// kept, the numbers, the estimate; the method and options in words with --verbose.
void print_text(const mb::Scene& scene, const std::string& backend, const mb::Discretization& mesh, bool mesh_given,
                const mb::Result& r, bool verbose) {
  const auto& sum = r.summary;
  std::cout << fmt::format("scene {} | backend {} | mesh {} | {}\n", scene.name, backend, mesh_line(mesh, mesh_given, r),
                           mb::to_string(sum.status));
  if (!sum.model.empty())
    std::cout << fmt::format("  model: {} ({})\n", sum.model,
                             sum.converges_to_scene_theory
                                 ? fmt::format("the scene's theory, {} {}", mb::to_string(scene.theory), mb::to_string(scene.kind))
                                 : fmt::format("NOT the scene's theory, {} {}: its distance to exact is model error",
                                               mb::to_string(scene.theory), mb::to_string(scene.kind)));
  if (!sum.message.empty()) std::cout << "  " << sum.message << "\n";
  if (verbose) {
    std::cout << "  options: " << sum.method_requested << "\n";
    if (!sum.method.empty()) std::cout << "  method: " << sum.method << "\n";
  }
  for (const auto& f : sum.fallbacks) std::cout << "  fall-back: " << f << "\n";
  for (std::size_t i = 0; i < r.frequencies_rad_s.size(); ++i)
    std::cout << fmt::format("  mode {:>3}  {:>16.8g} rad/s  {:>14.8g} Hz  {}\n", i + 1, r.frequencies_rad_s[i],
                             r.frequencies_rad_s[i] / (2 * 3.141592653589793), mb::to_string(r.mode_families[i]));
  for (const auto& d : r.deflections) std::cout << "  probe " << probe_line(scene, d) << forces_line(scene, d) << "\n";
  for (const auto& rc : r.reactions)
    std::cout << fmt::format("  reaction {} ({}): F = [{:.6e}, {:.6e}, {:.6e}] N, M = [{:.6e}, {:.6e}, {:.6e}] N*m\n",
                             rc.support,
                             scene.is_frame()  ? fmt::format("at ({:g}, {:g}, {:g}) m", rc.point[0], rc.point[1], rc.point[2])
                             : scene.is_beam() ? fmt::format("x = {:g} m", rc.position[0])
                                               : fmt::format("at ({:g}, {:g}) m", rc.position[0], rc.position[1]),
                             rc.force[0], rc.force[1], rc.force[2], rc.moment[0], rc.moment[1], rc.moment[2]);
  if (!r.frf.empty()) std::cout << fmt::format("  FRF: {} samples\n", r.frf.size());
  const auto& ee = sum.error_estimate;
  std::vector<std::string> est;
  const auto& xp = r.extrapolated;
  if (xp.frequencies_reported)
    est.push_back(
        fmt::format("frequencies {:.2g} (extrapolated; the mesh's {:.2g})", xp.frequency_error, ee.frequencies));
  else if (std::isfinite(ee.frequencies))
    est.push_back(fmt::format("frequencies {:.2g}", ee.frequencies));
  if (xp.deflections_reported)
    est.push_back(fmt::format("deflections {:.2g} of the largest (extrapolated; the mesh's {:.2g})", xp.deflection_error,
                              ee.deflections));
  else if (std::isfinite(ee.deflections))
    est.push_back(fmt::format("deflections {:.2g} of the largest", ee.deflections));
  if (!est.empty())
    std::cout << fmt::format("  estimated discretization error: {} (relative)\n", fmt::join(est, ", "));
  if (xp.frequencies_reported || xp.deflections_reported) {
    std::vector<std::string> what;
    if (xp.frequencies_reported) what.push_back(fmt::format("frequencies (estimate {:.2g})", xp.frequency_error));
    if (xp.deflections_reported) what.push_back(fmt::format("deflections (estimate {:.2g})", xp.deflection_error));
    std::cout << fmt::format("  values reported: extrapolated {} from meshes {}: their estimate meets the tolerance "
                             "{:.2g}, the mesh's own does not (the mesh's values below)\n",
                             fmt::join(what, " and "), xp.meshes, sum.error_estimate.tolerance);
    for (std::size_t i = 0; i < xp.mesh_frequencies_rad_s.size(); ++i)
      std::cout << fmt::format("  mesh mode {:>3}  {:>16.8g} rad/s\n", i + 1, xp.mesh_frequencies_rad_s[i]);
    for (const auto& d : xp.mesh_deflections) std::cout << "  mesh probe " << probe_line(scene, d) << "\n";
  } else if (!xp.empty()) {
    std::cout << fmt::format("  Richardson extrapolation of meshes {} (order {:g} removed):\n", xp.meshes, xp.order);
    for (std::size_t i = 0; i < xp.frequencies_rad_s.size(); ++i)
      std::cout << fmt::format("  mode {:>3}  {:>16.8g} rad/s  estimated error {:.2g}\n", i + 1, xp.frequencies_rad_s[i],
                               xp.frequency_errors[i]);
    for (const auto& d : xp.deflections) std::cout << "  probe " << probe_line(scene, d) << "\n";
    if (!xp.deflections.empty())
      std::cout << fmt::format("  deflections: estimated error {:.2g} of the largest\n", xp.deflection_error);
  }
  if (verbose && !xp.note.empty()) std::cout << "  extrapolation: " << xp.note << "\n";
  if (!r.transient.empty()) print_transient(scene, r.transient, verbose);
  if (!r.campbell.empty()) print_campbell(r.campbell, verbose);
  for (const auto& n : scene.notes) std::cout << "  note: " << n << "\n";
  for (const auto& w : sum.warnings) std::cout << "  warning: " << w << "\n";
  std::cout << fmt::format("  time {:.4g} s{}\n", sum.total_time_s, verbose ? "" : " (--verbose: method and options)");
}

/// Replaces this process by the Python study driver (python3 -m modalbench study ...).
int run_study(const std::string& spec, const std::string& out, const std::string& scheduler, int workers) {
#ifdef MODALBENCH_PYTHON_EXECUTABLE
  std::string path = MODALBENCH_PYTHON_DIR;
  if (const char* old = std::getenv("PYTHONPATH"); old && *old) path += std::string(":") + old;
  setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> args = {MODALBENCH_PYTHON_EXECUTABLE, "-m", "modalbench", "study", spec, "--out", out};
  if (!scheduler.empty()) args.insert(args.end(), {"--scheduler", scheduler});
  if (workers > 0) args.insert(args.end(), {"--workers", std::to_string(workers)});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(argv[0], argv.data());
  std::cerr << "modalbench: study: cannot run " << MODALBENCH_PYTHON_EXECUTABLE << ": " << std::strerror(errno) << "\n";
  return 1;
#else
  (void)spec, (void)out, (void)scheduler, (void)workers;
  std::cerr << "modalbench: study: this modalbench was built without its Python module (pybind11-dev, python3-dev)\n";
  return 2;
#endif
}

/// A positive number of `unit` up to `hi`, as an option's check.
CLI::Validator positive(double hi, const char* unit) {
  return CLI::Validator(
      [hi, unit](const std::string& text) -> std::string {
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || !(v > 0) || v > hi)
          return fmt::format("must be a number of {} in (0, {:g}] (got '{}')", unit, hi, text);
        return "";
      },
      unit, unit);
}

struct SolveArgs {
  std::string scene_path, backend = "exact", mesh_spec, mass = "consistent", vtk_dir;
  bool json = false, verbose = false;
  std::vector<std::string> backend_options;
  double max_memory_gb = 0, max_time_s = 600;
  CLI::Option* backend_given = nullptr;
};

CLI::App* add_solve(CLI::App& app, SolveArgs& a) {
  auto* solve = app.add_subcommand("solve", "solve one scene with one back-end");
  solve->add_option("scene", a.scene_path, "scene file (TOML), or a built-in scene's name (modalbench list)")->required();
  a.backend_given = solve->add_option("--backend,-b", a.backend, "back-end name (see `modalbench list`; default: exact)");
  solve->add_option("--mesh,-m", a.mesh_spec, "discretization, e.g. 64 or 100x60 (default: the back-end's)");
  solve->add_option("--mass", a.mass, "consistent or lumped (back-ends that offer both)");
  solve->add_option("--option,-o", a.backend_options,
                    "back-end option KEY=VALUE (repeatable; over the scene's [backend.NAME]; see `modalbench options`)");
  solve->add_flag("--json", a.json, "print one JSON object (schema in README.md)");
  solve->add_flag("--verbose,-v", a.verbose, "also print the method used and the options, in words");
  solve->add_option("--max-memory", a.max_memory_gb,
                    "refuse a request estimated to need more peak memory, GB (default: 80 % of what this process may use)")
      ->check(positive(1e6, "GB"));
  solve->add_option("--max-time", a.max_time_s, "refuse a request estimated to run longer, seconds (default 600)")
      ->check(positive(1e7, "seconds"));
  solve->add_option("--vtk", a.vtk_dir, "write the mode shapes and static deflections as VTK (.vtu) files into DIR");
  return solve;
}

/// The run-time options of `modalbench solve`: mass model, limits, the default path without
/// --mesh, and the back-end options (InputError for one not KEY=VALUE).
mb::Options solve_options(const SolveArgs& a) {
  mb::Options opt;
  opt.mass = mb::parse_mass_model(a.mass, "command line", "--mass");
  opt.max_memory_bytes = a.max_memory_gb * 1e9;
  opt.max_time_s = a.max_time_s;
  opt.refine_to_tolerance = a.mesh_spec.empty();
  for (const auto& kv : a.backend_options) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0)
      throw mb::InputError("command line", "--option", "expected KEY=VALUE (got '" + kv + "')");
    opt.backend.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
  }
  return opt;
}

/// `modalbench solve`: exit 0 on success, 3 for numbers that failed a check or a tolerance, 2 for
/// what was not solved (invalid input, unsupported, over the limits).
int run_solve(const mb::Registry& reg, const SolveArgs& a) {
  const mb::Scene scene = mb::load_scene(resolve_scene(a.scene_path));
  reg.check_backend_tables(scene);
  const mb::Solver* found = nullptr;
  try {
    found = &reg.get(a.backend);
  } catch (const std::invalid_argument& e) {
    std::cerr << "modalbench: --backend: " << e.what() << "\n";
    return 2;
  }
  const mb::Solver& solver = *found;
  const mb::Discretization mesh =
      a.mesh_spec.empty() ? solver.meshes(scene, mb::Options{}).default_mesh : mb::Discretization::parse(a.mesh_spec);
  const mb::Result r = solve_within(solver, scene, mesh, solve_options(a), a.json);
  if (!a.vtk_dir.empty()) {
    for (const auto& f : mb::write_vtk(scene, a.backend, r, a.vtk_dir)) (a.json ? std::cerr : std::cout) << "wrote " << f << "\n";
  }
  if (a.json) std::cout << mb::to_json(scene, a.backend, mesh, r).dump(2) << "\n";
  else
    print_text(scene, a.backend_given->count() > 0 ? a.backend : a.backend + " (default)", mesh, !a.mesh_spec.empty(), r,
               a.verbose);
  if (r.summary.status == mb::Status::InvalidInput || r.summary.status == mb::Status::Unsupported ||
      r.summary.status == mb::Status::ResourceLimit) {
    if (a.json) std::cerr << "modalbench: " << r.summary.message << "\n";
    return 2;
  }
  return r.ok() ? 0 : 3;
}

CLI::App* add_rom(CLI::App& app, RomArgs& a, std::string& scene) {
  auto* rom = app.add_subcommand("rom", "export a reduced-order state-space model (A, B, C, D) as JSON");
  rom->add_option("scene", scene, "scene file (TOML), or a built-in scene's name")->required();
  rom->add_option("--backend,-b", a.backend, "back-end name (default: exact)");
  rom->add_option("--mesh,-m", a.mesh, "discretization (default: the back-end's, refined to the tolerance)");
  rom->add_option("--inputs", a.inputs, "a unit force Fz at each: x (beam) or x,y (plate), m")->required();
  rom->add_option("--outputs", a.outputs, "w, its velocity and acceleration at each: x or x,y, m")->required();
  rom->add_option("--modes", a.modes, "modes retained (default 12)")->check(CLI::Range(1, 100000));
  rom->add_option("--zeta", a.zeta, "modal damping ratio in A (default 0)")->check(CLI::Range(0.0, 100.0));
  rom->add_flag("--no-static-correction", a.no_static_correction, "D without the truncated modes' static part");
  rom->add_option("--out,-o", a.out, "write the JSON here (default: stdout)");
  return rom;
}

struct CompareArgs {
  std::vector<std::string> scenes;
  std::string out_dir = "report", reference;
  double budget_s = 30.0;
  bool quick = false, keep_calculix_files = false;
};

CLI::App* add_compare(CLI::App& app, CompareArgs& a) {
  auto* cmp = app.add_subcommand("compare", "run every back-end on scenes and write a report");
  cmp->add_option("scenes", a.scenes, "scene files (default: every built-in scene)");
  cmp->add_option("--out,-o", a.out_dir, "output directory");
  cmp->add_option("--budget", a.budget_s, "seconds per scene and back-end for its mesh ladder (default 30)")
      ->check(CLI::Validator(
          [](const std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0' || !std::isfinite(v) || !(v > 0) || v > 1e6)
              return "must be a number of seconds in (0, 1e6] (got '" + text + "')";
            return "";
          },
          "SECONDS", "budget"));
  cmp->add_flag("--quick", a.quick, "one timing repeat and at most three meshes per back-end");
  cmp->add_option("--reference", a.reference, "add an external 3D reference: calculix (needs ccx)")
      ->check(CLI::IsMember({"calculix"}));
  cmp->add_flag("--keep-calculix-files", a.keep_calculix_files,
                "keep ccx's working files (.dat, .frd, .sta, ...) beside the decks (default: the decks and the modes read)");
  return cmp;
}

/// CalculiX as the comparison's 3D reference where `ccx` is found (said in the report's preface
/// either way).
void add_calculix(const CompareArgs& a, mb::CompareOptions& opt, mb::ReportOptions& ropt) {
  const std::string version = mb::calculix_version("ccx");
  if (version.empty()) {
    ropt.preface.push_back("3D reference: CalculiX was requested but `ccx` was not found, so it was skipped "
                           "(Debian: apt-get install calculix-ccx).");
    return;
  }
  ropt.preface.push_back("3D reference: " + version + ", 20-node bricks with reduced integration (C3D20R); "
                         "run once per mesh (no repeats), its modes labelled from their shapes.");
  const std::string work = (std::filesystem::path(a.out_dir) / "calculix").string();
  const double budget_s = a.budget_s;
  const bool keep = a.keep_calculix_files;
  opt.extra_references.push_back([work, budget_s, keep](const mb::Scene& sc, std::ostream* progress) {
    return mb::calculix_runs(sc, "ccx", work, budget_s, progress, keep);
  });
}

int run_compare(const mb::Registry& reg, const CompareArgs& a) {
  std::vector<mb::Scene> scenes;
  if (a.scenes.empty())
    for (const auto& f : mb::scene_files(scenes_dir())) scenes.push_back(mb::load_scene(f));
  else
    for (const auto& f : a.scenes) scenes.push_back(mb::load_scene(resolve_scene(f)));
  for (const auto& sc : scenes) reg.check_backend_tables(sc);
  mb::CompareOptions opt;
  opt.budget_s = a.budget_s;
  opt.quick = a.quick;
  opt.progress = &std::cerr;
  mb::ReportOptions ropt;
  if (a.reference == "calculix") add_calculix(a, opt, ropt);
  const auto comparisons = mb::run_comparison(scenes, reg, opt);
  const std::string index = mb::write_report(comparisons, a.out_dir, ropt);
  std::cout << "report written to " << std::filesystem::absolute(index).string()
            << " (and report.md, runs.csv, frequencies.csv, results.json, plots/)\n";
  return 0;
}

int run_stability_sweep(const mb::Registry& reg, const std::string& dir, bool quick) {
  const auto rows = mb::run_stability(mb::stability_cases(quick), reg, &std::cerr);
  const int bad = mb::write_stability_report(rows, dir);
  std::cout << "stability report written to " << std::filesystem::absolute(dir).string()
            << "/stability.html (and stability.md, stability.csv)\n";
  if (bad > 0) {
    std::cerr << "modalbench: " << bad
              << " run(s) claimed success with non-finite, missing or unordered numbers, or beyond their own error "
                 "estimate of the exact values\n";
    return 3;
  }
  return 0;
}

struct StudyArgs {
  std::string spec, out, scheduler;
  int workers = 0;
};

CLI::App* add_study(CLI::App& app, StudyArgs& a) {
  auto* study = app.add_subcommand("study", "run a parameter study (Python driver; see README.md)");
  study->add_option("spec", a.spec, "study spec (TOML)")->required();
  study->add_option("--out,-o", a.out, "output folder")->required();
  study->add_option("--scheduler", a.scheduler, "Dask scheduler address (tcp://HOST:PORT); default: local processes");
  study->add_option("--workers", a.workers, "local processes (default: one per core)")->check(CLI::Range(1, 1024));
  return study;
}

/// The one JSON document `solve --json` prints for invalid input (its file, key and reason).
void print_invalid_input_json(const mb::InputError& e) {
  std::cout << nlohmann::json{{"status", "invalid-input"},
                              {"message", e.what()},
                              {"file", e.source()},
                              {"key", e.key()},
                              {"reason", e.reason()}}
                   .dump(2)
            << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  modalbench::reuse_freed_memory();
  CLI::App app{"modalbench: which beam or plate model to trust, how accurate, at what cost"};
  app.require_subcommand(1);
  auto* list = app.add_subcommand("list", "list the built-in scenes and the back-ends");
  SolveArgs solve_args;
  auto* solve = add_solve(app, solve_args);
  RomArgs rom_args;
  std::string rom_scene;
  auto* rom = add_rom(app, rom_args, rom_scene);
  auto* opts = app.add_subcommand("options", "list a back-end's options with their defaults");
  std::string opts_backend;
  opts->add_option("backend", opts_backend, "back-end name (default: all)");
  CompareArgs cmp_args;
  auto* cmp = add_compare(app, cmp_args);
  auto* stab = app.add_subcommand("stability", "sweep slenderness, spring stiffness, mesh size and high modes");
  std::string stab_dir = "report/stability";
  bool stab_quick = false;
  stab->add_option("--out,-o", stab_dir, "output directory");
  stab->add_flag("--quick", stab_quick, "a few cases per group");
  StudyArgs study_args;
  auto* study = add_study(app, study_args);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help prints and succeeds; every command-line error is invalid input (exit 2).
    return app.exit(e) == 0 ? 0 : 2;
  }

  try {
    const mb::Registry reg = mb::make_default_registry();
    if (*list) return run_list(reg);
    if (*study) return run_study(study_args.spec, study_args.out, study_args.scheduler, study_args.workers);
    if (*opts) return run_options(reg, opts_backend);
    if (*rom) {
      const mb::Scene scene = mb::load_scene(resolve_scene(rom_scene));
      reg.check_backend_tables(scene);
      return run_rom(reg, scene, rom_args);
    }
    if (*solve) return run_solve(reg, solve_args);
    if (*stab) return run_stability_sweep(reg, stab_dir, stab_quick);
    if (*cmp) return run_compare(reg, cmp_args);
  } catch (const mb::InputError& e) {
    std::cerr << "modalbench: " << e.what() << "\n";
    if (*solve && solve_args.json) print_invalid_input_json(e);  // under --json the answer is always one JSON document
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "modalbench: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
