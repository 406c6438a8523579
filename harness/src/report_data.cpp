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
  js["scene_file"] = c.scene.source;
  js["notes"] = c.notes;
  js["reference"] = {{"source", c.reference.source}, {"frequencies_rad_s", nlohmann::json::array()},
                     {"uncertainty_rad_s", nlohmann::json::array()}, {"families", nlohmann::json::array()}};
  for (std::size_t i = 0; i < c.reference.frequencies_rad_s.size(); ++i) {
    js["reference"]["frequencies_rad_s"].push_back(num(c.reference.frequencies_rad_s[i]));
    js["reference"]["uncertainty_rad_s"].push_back(num(c.reference.frequency_uncertainty[i]));
    js["reference"]["families"].push_back(to_string(c.reference.families[i]));
  }
  js["runs"] = nlohmann::json::array();
  for (const auto& r : c.runs) {
    auto jr = to_json(c.scene, r.backend, r.mesh, r.result);
    jr["median_s"] = num(r.median_s);
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

void write_runs_csv(const std::string& path, const std::vector<SceneComparison>& all) {
  std::string csv = "scene,backend,mesh,dofs,status,median_s,repeats,max_frequency_error,deflection_error,frf_error_db,reference\n";
  for (const auto& c : all)
    for (const auto& r : c.runs) {
      const auto& s = r.result.summary;
      csv += fmt::format("{},{},{},{},{},{},{},{},{},{},{}\n", c.scene.name, r.backend, r.mesh.spec(), s.unknowns,
                         to_string(s.status), r.median_s, r.repeats, r.max_frequency_error, r.deflection_error,
                         r.frf_error_db, c.reference.source);
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
  write_text_file(path, root.dump(2) + "\n");
}

}  // namespace modalbench::report_detail
