// The report's machine-readable files: runs.csv, frequencies.csv and results.json.

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "modalbench/harness/files.hpp"
#include "modalbench/json_output.hpp"
#include "report_document.hpp"

namespace modalbench::report_detail {

namespace {

nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json scene_json(const SceneComparison& c) {
  nlohmann::json js;
  js["scene"] = c.scene.name;
  js["scene_file"] = display_path(c.scene.source);
  js["notes"] = c.notes;
  js["reference"] = {{"source", c.reference.source}, {"frequencies_rad_s", nlohmann::json::array()},
                     {"uncertainty_rad_s", nlohmann::json::array()}, {"families", nlohmann::json::array()}};
  for (std::size_t i = 0; i < c.reference.frequencies_rad_s.size(); ++i) {
    js["reference"]["frequencies_rad_s"].push_back(num(c.reference.frequencies_rad_s[i]));
    js["reference"]["uncertainty_rad_s"].push_back(num(c.reference.frequency_uncertainty[i]));
    js["reference"]["families"].push_back(to_string(c.reference.families[i]));
  }
  js["best_reference"] = c.best_label;
  js["limits"] = nlohmann::json::array();
  for (const auto& lim : c.limits)
    js["limits"].push_back({{"label", lim.label},
                            {"backend", lim.backend},
                            {"source", lim.source},
                            {"observed_order", {num(lim.order[0]), num(lim.order[1]), num(lim.order[2])}},
                            {"gci", num(lim.gci)},
                            {"safety_factor", num(lim.safety_factor)},
                            {"note", lim.convergence_note},
                            {"model_error", num(lim.model_error)},
                            {"model_error_uncertainty", num(lim.model_error_uncertainty)}});
  js["runs"] = nlohmann::json::array();
  for (const auto& r : c.runs) {
    auto jr = to_json(c.scene, r.backend, r.mesh, r.result);
    // The shapes' values are the MAC's input (pair_mac below keeps what they gave): 85 % of the file
    // with them (33 of 37 MB). `modalbench solve --json` of the run gives them.
    jr.erase("mode_shapes");
    jr["median_s"] = num(r.median_s);
    jr["time_s"] = {{"modes", num(r.time_s.modes)}, {"statics", num(r.time_s.statics)}, {"frf", num(r.time_s.frf)}};
    jr["limit"] = r.limit;
    jr["discretization_error"] = {{"frequencies", num(r.disc_frequency_error)},
                                  {"deflections", num(r.disc_deflection_error)},
                                  {"frf_db", num(r.disc_frf_error_db)}};
    jr["repeats"] = r.repeats;
    jr["max_frequency_error"] = num(r.max_frequency_error);
    jr["deflection_error"] = num(r.deflection_error);
    jr["frf_error_db"] = num(r.frf_error_db);
    jr["frequency_errors"] = nlohmann::json::array();
    for (double e : r.frequency_errors) jr["frequency_errors"].push_back(num(e));
    jr["pairing"] = r.paired_by_mac ? "mac" : "family order";
    jr["pair_mac"] = nlohmann::json::array();
    for (double v : r.pair_mac) jr["pair_mac"].push_back(num(v));
    js["runs"].push_back(jr);
  }
  return js;
}

}  // namespace

namespace {

/// A CSV field: quoted (with doubled quotes) when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& v) {
  if (v.find_first_of(",\"\n") == std::string::npos) return v;
  std::string q = "\"";
  for (char ch : v) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

std::string csv_num(double v) { return std::isfinite(v) ? fmt::format("{}", v) : ""; }

}  // namespace

void write_runs_csv(const std::string& path, const std::vector<SceneComparison>& all) {
  std::string csv = "scene,backend,method,mesh,dofs,status,quantity,time_s,repeats,error,error_kind,reference,"
                    "observed_order,gci\n";
  for (const auto& c : all) {
    for (const auto& lim : c.limits) {
      // The finest successful run of the limit carries its GCI.
      const RunRecord* finest_run = nullptr;
      for (const auto& r : c.runs)
        if (r.limit == lim.label && !r.failed()) finest_run = &r;
      for (const auto& r : c.runs) {
        if (r.limit != lim.label) continue;
        const auto& s = r.result.summary;
        for (Quantity q : kQuantities) {
          if (!std::isfinite(r.time_s.of(q))) continue;
          const double gci = q == Quantity::Frequencies && &r == finest_run ? lim.gci : kNaN;
          csv += fmt::format("{},{},{},{},{},{},{},{},{},{},discretization,{},{},{}\n", csv_field(c.scene.name),
                             csv_field(r.backend), csv_field(lim.label), csv_field(r.mesh.spec()), s.unknowns,
                             to_string(s.status), to_string(q), csv_num(r.time_s.of(q)), r.repeats,
                             csv_num(r.disc_error(q)), csv_field(lim.source), csv_num(lim.order[static_cast<int>(q)]),
                             csv_num(gci));
        }
      }
      csv += fmt::format("{},{},{},limit,,,frequencies,,,{},model,{},{},{}\n", csv_field(c.scene.name),
                         csv_field(lim.backend), csv_field(lim.label), csv_num(lim.model_error), csv_field(c.best_label),
                         csv_num(lim.order[0]), csv_num(lim.model_error_uncertainty));
    }
  }
  write_text_file(path, csv);
}

void write_frequencies_csv(const std::string& path, const std::vector<SceneComparison>& all) {
  std::string csv =
      "scene,backend,mesh,mode,family,omega_rad_s,reference_rad_s,reference_uncertainty_rad_s,relative_error,mac\n";
  for (const auto& c : all)
    for (const auto& r : c.runs) {
      // Each run's modes with the reference mode they were matched to.
      const auto& m = r.match;
      for (std::size_t i = 0; i < r.result.frequencies_rad_s.size(); ++i) {
        double refv = kNaN, unc = kNaN, err = kNaN, mac = kNaN;
        for (std::size_t k = 0; k < m.size(); ++k)
          if (m[k] == static_cast<int>(i)) {
            refv = c.reference.frequencies_rad_s[k];
            unc = c.reference.frequency_uncertainty[k];
            err = r.frequency_errors[k];
            mac = r.pair_mac[k];
          }
        csv += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", c.scene.name, r.backend, r.mesh.spec(), i + 1,
                           to_string(r.result.mode_families[i]), r.result.frequencies_rad_s[i], refv, unc, err, mac);
      }
    }
  write_text_file(path, csv);
}

void write_results_json(const std::string& path, const std::vector<SceneComparison>& all,
                        const std::vector<std::pair<std::string, std::string>>& env,
                        const std::vector<std::string>& problems) {
  nlohmann::json root;
  root["environment"] = nlohmann::json::object();
  for (auto& [k, v] : env) root["environment"][k] = v;
  root["scenes"] = nlohmann::json::array();
  for (const auto& c : all) root["scenes"].push_back(scene_json(c));
  root["problems"] = problems;
  write_text_file(path, root.dump() + "\n");  // one line: indenting doubled the file
}

}  // namespace modalbench::report_detail
