// The `modalbench` command line, run as a user would run it.
#define BOOST_TEST_MODULE cli
#include <boost/test/unit_test.hpp>

#include "temp_dir.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

namespace {

struct Run {
  int status;
  std::string out;  // stdout and stderr together
};

/// Runs a shell command line; its stdout (and whatever it redirects there) and exit status.
Run run_command(const std::string& cmd) {
  FILE* p = popen(cmd.c_str(), "r");
  BOOST_REQUIRE(p);
  std::string out;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

Run run(const std::string& args, bool merge_stderr = true) {
  return run_command(std::string(MODALBENCH_EXE) + " " + args + (merge_stderr ? " 2>&1" : " 2>/dev/null"));
}

std::string scene(const char* f) { return std::string(MODALBENCH_SCENES_DIR) + "/" + f; }
std::string data(const char* f) { return std::string(MODALBENCH_TEST_DATA_DIR) + "/" + f; }

}  // namespace

BOOST_AUTO_TEST_CASE(solve_json_prints_table1) {
  const Run r = run("solve " + scene("paper_fixed_beam.toml") + " --backend exact --json", false);
  BOOST_TEST_REQUIRE(r.status == 0, r.out);
  const auto j = nlohmann::json::parse(r.out);
  BOOST_TEST(j["scene"] == "paper-fixed-beam");
  BOOST_TEST(j["backend"] == "exact");
  BOOST_TEST(j["status"] == "success");
  const double ref[] = {6211.15, 13848.36, 22763.93, 32186.47, 41982.17, 47172.88};
  BOOST_REQUIRE(j["frequencies_rad_s"].size() == 6u);
  for (int i = 0; i < 6; ++i) {
    BOOST_TEST(std::abs(j["frequencies_rad_s"][i].get<double>() / ref[i] - 1) < 1e-6);
    BOOST_TEST(j["mode_families"][i] == "bending-xz");
  }
  BOOST_TEST(j["deflections"].size() == 2u);
  BOOST_TEST(j["deflections"][0].contains("w"));
  BOOST_TEST(j["deflections"][0].contains("rotation"));
  BOOST_TEST(j.contains("frf"));
  BOOST_TEST(j.contains("timing_s"));
  BOOST_TEST(j.contains("diagnostics"));
  BOOST_TEST(j["warnings"].is_array());
  BOOST_TEST(j.contains("unknowns"));
  BOOST_TEST(j["method"].contains("requested"));
  BOOST_TEST(j["method"].contains("used"));
  BOOST_TEST(j["mesh"] == "-");
}

BOOST_AUTO_TEST_CASE(malformed_scenes_are_rejected) {
  struct Case { const char* file; const char* key; const char* reason; };
  const Case cases[] = {
      {"bad_negative_length.toml", "geometry.length", "must be > 0"},
      {"bad_unknown_support.toml", "supports.x0", "unknown support 'glued'"},
      {"bad_syntax.toml", "line", "TOML syntax"},
      {"bad_nan.toml", "material.E", "NaN"},
  };
  for (const auto& c : cases) {
    const Run r = run("solve " + data(c.file) + " --backend exact --json");
    BOOST_TEST(r.status == 2, c.file << ": exit " << r.status << ": " << r.out);
    BOOST_TEST(r.out.find(c.file) != std::string::npos, r.out);
    BOOST_TEST(r.out.find(c.key) != std::string::npos, r.out);
    BOOST_TEST(r.out.find(c.reason) != std::string::npos, r.out);
  }
  const Run missing = run("solve /nonexistent.toml");
  BOOST_TEST(missing.status == 2);
  BOOST_TEST(missing.out.find("no such file") != std::string::npos, missing.out);
}

// Things that are not scene files are named for what they are, without reading them.
BOOST_AUTO_TEST_CASE(paths_that_are_not_scene_files) {
  const struct {
    const char* path;
    const char* says;
  } cases[] = {{"/tmp", "is a directory"}, {"/dev/null", "not a regular file"}, {"/dev/zero", "not a regular file"}};
  for (const auto& c : cases) {
    const Run r = run(std::string("solve ") + c.path);
    BOOST_TEST(r.status == 2, c.path);
    BOOST_TEST(r.out.find(c.says) != std::string::npos, r.out);
  }
  // Under --json the answer is one JSON object on stdout, also for a scene that fails to load.
  const Run j = run("solve /tmp --json", false);
  BOOST_TEST(j.status == 2);
  const auto doc = nlohmann::json::parse(j.out);
  BOOST_TEST(doc["status"] == "invalid-input");
  BOOST_TEST(doc["file"] == "/tmp");
}

// Exit codes are docs/command-line.md's 0 / 1 / 2 / 3 for every command-line mistake.
BOOST_AUTO_TEST_CASE(command_line_mistakes_exit_2) {
  for (const char* args : {"", "frobnicate", "solve", "compare --budget -1", "compare --budget nan",
                           "compare --budget 1e400"}) {
    const Run r = run(args);
    BOOST_TEST(r.status == 2, "'" << args << "': exit " << r.status << ": " << r.out);
  }
  const Run s2 = run("solve " + scene("paper_fixed_beam.toml") + " " + scene("paper_ss_plate.toml"));
  BOOST_TEST(s2.status == 2);
  const Run mass = run("solve " + scene("paper_fixed_beam.toml") + " --mass heavy", false);
  BOOST_TEST(mass.status == 2);
  BOOST_TEST(mass.out.find("--mass") == std::string::npos, "the error goes to stderr, not stdout: " << mass.out);
  BOOST_TEST(run("--help").status == 0);
}

BOOST_AUTO_TEST_CASE(unknown_backend_lists_known_ones) {
  const Run r = run("solve " + scene("paper_fixed_beam.toml") + " --backend nosuch");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.out.find("unknown back-end 'nosuch'") != std::string::npos, r.out);
  BOOST_TEST(r.out.find("exact") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(bad_mesh_is_rejected) {
  const Run r = run("solve " + scene("paper_fixed_beam.toml") + " --backend exact --mesh 0");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(r.out.find("--mesh") != std::string::npos, r.out);
}

BOOST_AUTO_TEST_CASE(list_names_scenes_and_backends) {
  const Run r = run("list");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(r.out.find("paper_fixed_beam ") != std::string::npos);
  BOOST_TEST(r.out.find("paper_ss_plate ") != std::string::npos);
  BOOST_TEST(r.out.find("exact") != std::string::npos);
  // Names, not the build machine's folder.
  BOOST_TEST(r.out.find(MODALBENCH_SCENES_DIR) == std::string::npos, r.out);
}

// The text output says what was solved: the mesh kept and where it came from, the model and
// whether it is the scene's theory, every probe component the scene carries; the method only
// with --verbose; no estimate printed as nan.
BOOST_AUTO_TEST_CASE(text_output_says_what_was_solved) {
  const Run de = run("solve paper_fixed_beam --backend difference_eq");
  BOOST_TEST(de.out.find("(default") != std::string::npos, de.out);
  BOOST_TEST(de.out.find("model: a regular chain of Hermite Euler-Bernoulli elements") != std::string::npos, de.out);
  BOOST_TEST(de.out.find("NOT the scene's theory, timoshenko beam") != std::string::npos, de.out);
  BOOST_TEST(de.out.find("method:") == std::string::npos, de.out);
  BOOST_TEST(de.out.find("nan") == std::string::npos, de.out);
  const Run ex = run("solve paper_fixed_beam --backend exact --verbose");
  BOOST_TEST(ex.out.find("model: the exact timoshenko beam (the scene's theory") != std::string::npos, ex.out);
  BOOST_TEST(ex.out.find("method:") != std::string::npos, ex.out);
  const Run rf = run("solve paper_fixed_beam --backend rfem --mesh 64");
  BOOST_TEST(rf.out.find("| mesh 64 (given) |") != std::string::npos, rf.out);
  const Run ts = run("solve two_span_beam --backend exact");
  BOOST_TEST(ts.out.find("reaction points[0] (x = 10 m)") != std::string::npos, ts.out);
  const Run dt = run("solve two_span_beam --backend dtfm");  // reactions from every back-end that models them
  BOOST_TEST(dt.out.find("reaction points[0] (x = 10 m)") != std::string::npos, dt.out);
  const Run implicit = run("solve two_span_beam");  // no --backend: exact, and said
  BOOST_TEST(implicit.out.find("| backend exact (default) |") != std::string::npos, implicit.out);
  const Run pl = run("solve paper_ss_plate --backend exact");
  BOOST_TEST(pl.out.find("theta_x = ") != std::string::npos, pl.out);
  const Run j = run("solve paper_fixed_beam --backend dtfm --json", false);
  const auto doc = nlohmann::json::parse(j.out);
  BOOST_TEST(doc["model"]["is_scene_theory"] == true);
  BOOST_TEST(doc["model"]["solved"].get<std::string>().find("one prism") != std::string::npos);
}

// The names `list` shows are what `solve` takes, with or without .toml.
BOOST_AUTO_TEST_CASE(solve_takes_a_builtin_scene_name) {
  for (const char* name : {"paper_fixed_beam", "paper_fixed_beam.toml"}) {
    const Run r = run(std::string("solve ") + name + " --backend exact");
    BOOST_TEST(r.status == 0, name << ": " << r.out);
    BOOST_TEST(r.out.find("scene paper-fixed-beam") != std::string::npos, r.out);
  }
  const Run missing = run("solve no_such_scene --backend exact");
  BOOST_TEST(missing.status == 2);
  BOOST_TEST(missing.out.find("no_such_scene") != std::string::npos, missing.out);
}

BOOST_AUTO_TEST_CASE(compare_writes_a_report) {
  const modalbench_test::TempDir tmp("modalbench_cli_report");
  const auto dir = tmp.path();
  const Run r = run("compare " + scene("paper_fixed_beam.toml") + " --out " + dir.string());
  BOOST_TEST_REQUIRE(r.status == 0, r.out);
  for (const char* f : {"index.html", "report.md", "results.json"}) BOOST_TEST(std::filesystem::exists(dir / f), f);
  // Scene files are named relative to the working directory, or by their name: never by the build
  // machine's absolute path (the test runs outside the scenes' folder).
  std::ifstream in(dir / "index.html");
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  BOOST_TEST(html.find(MODALBENCH_SCENES_DIR) == std::string::npos);
  BOOST_TEST(html.find("scene file: paper_fixed_beam.toml") != std::string::npos);
}

// Issue 18 (1): short of memory, a solve is refused up front or reports resource-limit; it never
// crashes. `ulimit -v` caps the address space of the command (Eigen's SparseLU segfaulted in the
// FRF, and OpenBLAS spun forever on a failed buffer allocation, with 2 GB and less).
BOOST_AUTO_TEST_CASE(short_of_memory_is_resource_limit_never_a_crash) {
  auto limited = [](const std::string& kb, const std::string& args) {
    return run_command("sh -c 'ulimit -v " + kb + "; exec " + std::string(MODALBENCH_EXE) + " " + args + " 2>/dev/null'");
  };
  const std::string beam = scene("paper_fixed_beam.toml");
  // The estimate (0.68 GB for 200,000 segments with the FRF) exceeds what 0.7 GB of address space
  // leaves: refused before anything is allocated.
  Run r = limited("700000", "solve " + beam + " --backend rfem --mesh 200000 --json");
  BOOST_TEST(r.status == 2, r.out);
  auto j = nlohmann::json::parse(r.out);
  BOOST_TEST(j["status"] == "resource-limit");
  BOOST_TEST(j["message"].get<std::string>().find("estimated peak memory") != std::string::npos);
  BOOST_TEST(j["message"].get<std::string>().find("--max-memory") != std::string::npos);
  // With the limit raised past what the machine gives, the allocation itself fails: still a clean
  // resource-limit with one JSON document.
  r = limited("450000", "solve " + beam + " --backend rfem --mesh 100000 --max-memory 100 --json");
  BOOST_TEST(r.status == 2, r.out);
  j = nlohmann::json::parse(r.out);
  BOOST_TEST(j["status"] == "resource-limit");
  BOOST_TEST(j["message"].get<std::string>().find("out of memory") != std::string::npos);
  // Bad limits are command-line mistakes.
  BOOST_TEST(run("solve " + beam + " --max-memory -1").status == 2);
  BOOST_TEST(run("solve " + beam + " --max-time nan").status == 2);
}

// `modalbench rom`: one JSON document with A (2N x 2N), B, C (w, velocity, acceleration per output)
// and D; a point off the body is named with its option.
BOOST_AUTO_TEST_CASE(rom_writes_a_state_space_model) {
  const Run r = run("rom " + scene("beam_step_load.toml") + " --inputs 1.0 --outputs 0.5 --outputs 1.5 --modes 4", false);
  BOOST_TEST_REQUIRE(r.status == 0, r.out);
  const auto doc = nlohmann::json::parse(r.out);
  BOOST_TEST(doc["A"].size() == 8u);
  BOOST_TEST(doc["B"].size() == 8u);
  BOOST_TEST(doc["B"][0].size() == 1u);
  BOOST_TEST(doc["C"].size() == 6u);
  BOOST_TEST(doc["D"].size() == 6u);
  BOOST_TEST(doc["static_correction"].get<bool>());
  BOOST_TEST(doc["outputs"][2].get<std::string>().find("dw/dt") == 0u);
  const Run bad = run("rom " + scene("beam_step_load.toml") + " --inputs 3.0 --outputs 0.5");
  BOOST_TEST(bad.status == 2);
  BOOST_TEST(bad.out.find("--inputs") != std::string::npos, bad.out);
}
