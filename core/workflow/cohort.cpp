#include "core/workflow/cohort.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <numeric>
#include <sstream>

#include "core/io/mesh_io.h"
#include "core/quality/hex_quality.h"
#include "core/util/error.h"
#include "core/util/text_file.h"
#include "core/workflow/report.h"

namespace facehex {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A numeric column of the table: its name (CSV header and JSON key), its heading in cohort.md, its printf format, and
// its value for a patient (none: an empty cell).
struct Column {
  const char* name;
  const char* heading;
  const char* format;
  std::function<std::optional<double>(const CohortPatient&)> value;
};

// Of the mesh, when there is one.
Column mesh_column(const char* name, const char* heading, const char* format, double (*of)(const CohortMesh&)) {
  return {name, heading, format, [of](const CohortPatient& p) -> std::optional<double> {
            if (!p.mesh) return std::nullopt;
            return of(*p.mesh);
          }};
}

// Landmark counts, when the patient's constraints were placed at landmarks.
Column landmark_column(const char* name, const char* heading, int CohortMesh::*count) {
  return {name, heading, "%.0f", [count](const CohortPatient& p) -> std::optional<double> {
            if (!p.mesh || (*p.mesh).*count < 0) return std::nullopt;
            return (*p.mesh).*count;
          }};
}

// Where the standard's landmarks landed, when it was measured.
Column landing_column(const char* name, const char* heading, double CohortMesh::*mm) {
  return {name, heading, "%.1f", [mm](const CohortPatient& p) -> std::optional<double> {
            if (!p.mesh || (*p.mesh).*mm < 0) return std::nullopt;
            return (*p.mesh).*mm;
          }};
}

const std::vector<Column>& numeric_columns() {
  static const std::vector<Column> columns = {
      mesh_column("tets", "tets", "%.0f", [](const CohortMesh& m) { return double(m.tets); }),
      mesh_column("cells", "cells", "%.0f", [](const CohortMesh& m) { return double(m.cells); }),
      mesh_column("inverted", "inverted", "%.0f", [](const CohortMesh& m) { return double(m.inverted); }),
      mesh_column("shape_mean", "mean shape", "%.3f", [](const CohortMesh& m) { return m.shape_mean; }),
      mesh_column("standard_shape_mean", "standard's mean shape", "%.3f",
                  [](const CohortMesh& m) { return m.standard_shape_mean; }),
      mesh_column("dihedral_change_mean_deg", "dihedral change mean (deg)", "%.2f",
                  [](const CohortMesh& m) { return m.dihedral_change_mean_deg; }),
      mesh_column("dihedral_change_max_deg", "dihedral change max (deg)", "%.1f",
                  [](const CohortMesh& m) { return m.dihedral_change_max_deg; }),
      mesh_column("side_distance_p95_mm", "side distance p95 (mm)", "%.3g",
                  [](const CohortMesh& m) { return m.side_distance_p95_mm; }),
      {"seconds", "time (s)", "%.1f", [](const CohortPatient& p) -> std::optional<double> { return p.seconds; }},
      landmark_column("landmarks_found", "landmarks found", &CohortMesh::landmarks_found),
      landmark_column("landmarks_estimated", "landmarks estimated", &CohortMesh::landmarks_estimated),
      landing_column("landing_mean_mm", "landmarks land, mean (mm)", &CohortMesh::landing_mean_mm),
      landing_column("landing_max_mm", "landmarks land, max (mm)", &CohortMesh::landing_max_mm),
  };
  return columns;
}

std::string status_text(const CohortPatient& p) { return p.ok() ? "ok" : "failed"; }

// A required member of the status file, checked with `is` (e.g. &json::is_string).
const json& member(const json& object, const char* key, bool (json::*is)() const noexcept, const std::string& path) {
  const auto it = object.find(key);
  if (it == object.end() || !((*it).*is)())
    throw Error(path, std::string("the status file's \"") + key + "\" is missing or of the wrong type");
  return *it;
}

// From the folder of a run: report.json, patient_hex.vtu and standard_hex.vtu.
CohortMesh read_mesh(const fs::path& folder) {
  const std::string report_path = (folder / "report.json").string(), mesh_path = (folder / "patient_hex.vtu").string();
  const json report = read_run_report(report_path);
  CohortMesh m;
  try {
    const json& quality = report.at("patient_hex").at("quality");
    m.tets = report.at("patient").at("parameterization").at("tets").get<int>();
    m.cells = quality.at("cells").get<int>();
    m.inverted = quality.at("inverted").get<int>();
    m.shape_mean = quality.at("shape_mean").get<double>();
    m.standard_shape_mean = report.at("standard").at("quality").at("shape_mean").get<double>();
    const json& distortion = quality.at("dihedral_distortion");
    m.dihedral_change_mean_deg = distortion.at("mean_deg").get<double>();
    m.dihedral_change_max_deg = distortion.at("max_deg").get<double>();
    m.side_distance_p95_mm = report.at("transfer").at("side_vertex_distance_mm").at("p95").get<double>();
    const json& landmarks = report.at("landmarks");
    if (!landmarks.is_null()) {
      m.landmarks_found = landmarks.at("found").get<int>();
      m.landmarks_estimated = landmarks.at("estimated").get<int>();
    }
    const json& landing = report.at("feature_landing");
    if (!landing.is_null()) {
      m.landing_mean_mm = landing.at("mean_mm").get<double>();
      m.landing_max_mm = landing.at("max_mm").get<double>();
    }
  } catch (const json::exception& e) {
    throw Error(report_path, std::string("a key the cohort report reads is missing or of the wrong type: ") + e.what());
  }
  const VolumeMesh hex = read_volume_mesh(mesh_path);
  const auto shape = hex.cell_data.find("shape");
  if (shape == hex.cell_data.end()) throw Error(mesh_path, "has no cell data \"shape\" (not written by facehex run)");
  m.shapes.assign(shape->second.data(), shape->second.data() + shape->second.size());
  const Eigen::VectorXd changes = dihedral_angle_changes(read_volume_mesh((folder / "standard_hex.vtu").string()), hex);
  m.dihedral_changes.assign(changes.data(), changes.data() + changes.size());
  return m;
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string quoted = "\"";
  for (const char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// A table cell of Markdown: pipes escaped, on one line.
std::string markdown_cell(std::string s) {
  std::string out;
  for (const char c : s) out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}

std::string cell_text(const Column& c, const CohortPatient& p) {
  const std::optional<double> v = c.value(p);
  return v ? fmt(c.format, *v) : "";
}

}  // namespace

CohortPatient read_cohort_patient(const std::string& status_path) {
  json status;
  try {
    status = json::parse(read_text_file(status_path));
  } catch (const json::parse_error&) {
    throw Error(status_path, "not a JSON file");
  }
  if (!status.is_object() || status.value("format", "") != "facehex-cohort-status" ||
      status.value("version", 0) != kCohortStatusVersion)
    throw Error(status_path, "not a cohort status file of version " + std::to_string(kCohortStatusVersion) +
                                 " (\"format\": \"facehex-cohort-status\")");
  CohortPatient p;
  p.id = member(status, "id", &json::is_string, status_path).get<std::string>();
  p.folder = member(status, "folder", &json::is_string, status_path).get<std::string>();
  const json& steps = member(status, "steps", &json::is_array, status_path);
  if (steps.empty()) throw Error(status_path, "lists no step");
  bool transfer_ran = false;
  for (const json& step : steps) {
    const std::string name = member(step, "step", &json::is_string, status_path).get<std::string>();
    const int code = member(step, "exit_code", &json::is_number_integer, status_path).get<int>();
    p.seconds += member(step, "seconds", &json::is_number, status_path).get<double>();
    const auto job = step.find("slurm_job_id");
    if (job != step.end() && job->is_string()) p.slurm_jobs.push_back(job->get<std::string>());
    transfer_ran = transfer_ran || name == "transfer";
    if (code != 0 && p.ok()) {
      p.failed_step = name;
      p.exit_code = code;
      p.error = member(step, "error", &json::is_string, status_path).get<std::string>();
    }
  }
  // The transfer writes its mesh and report also when cells stay inverted (exit code 3), and nothing when it fails.
  const fs::path report = fs::path(p.folder) / "report.json";
  if (transfer_ran && (p.ok() || p.failed_step != "transfer" || p.exit_code == 3) && fs::exists(report))
    p.mesh = read_mesh(p.folder);
  else if (p.ok())
    throw Error(status_path, "says the patient succeeded, but " + report.string() + " is missing");
  return p;
}

CohortSummary summarize_cohort(const std::vector<CohortPatient>& patients) {
  CohortSummary s;
  s.patients = static_cast<int>(patients.size());
  s.ok = static_cast<int>(std::count_if(patients.begin(), patients.end(), [](const auto& p) { return p.ok(); }));
  s.failed = s.patients - s.ok;
  s.success_rate = s.patients ? static_cast<double>(s.ok) / s.patients : 0.0;
  for (const Column& c : numeric_columns()) {
    std::vector<double> values;
    for (const CohortPatient& p : patients)
      if (const std::optional<double> v = c.value(p)) values.push_back(*v);
    ColumnSummary cs;
    cs.column = c.name;
    cs.count = static_cast<int>(values.size());
    if (!values.empty()) {
      cs.min = *std::min_element(values.begin(), values.end());
      cs.max = *std::max_element(values.begin(), values.end());
      cs.mean = std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
      cs.median = median(values);
    }
    s.columns.push_back(cs);
  }
  return s;
}

json cohort_json(const std::vector<CohortPatient>& patients, const CohortSummary& summary) {
  json columns = json::object();
  for (const ColumnSummary& c : summary.columns)
    columns[c.column] = {{"count", c.count}, {"min", c.min}, {"median", c.median}, {"mean", c.mean}, {"max", c.max}};
  json rows = json::array();
  for (const CohortPatient& p : patients) {
    json row = {{"id", p.id},
                {"status", status_text(p)},
                {"failed_step", p.ok() ? json(nullptr) : json(p.failed_step)},
                {"exit_code", p.exit_code},
                {"error", p.error},
                {"folder", p.folder},
                {"slurm_jobs", p.slurm_jobs}};
    for (const Column& c : numeric_columns()) {
      const std::optional<double> v = c.value(p);
      row[c.name] = v ? json(*v) : json(nullptr);
    }
    rows.push_back(row);
  }
  return {{"format", "facehex-cohort-report"},
          {"version", 1},
          {"summary",
           {{"patients", summary.patients},
            {"ok", summary.ok},
            {"failed", summary.failed},
            {"success_rate", summary.success_rate},
            {"columns", columns}}},
          {"patients", rows}};
}

std::string cohort_csv(const std::vector<CohortPatient>& patients) {
  std::ostringstream os;
  os << "id,status,failed_step,exit_code,error";
  for (const Column& c : numeric_columns()) os << "," << c.name;
  os << "\n";
  for (const CohortPatient& p : patients) {
    os << csv_field(p.id) << "," << status_text(p) << "," << p.failed_step << "," << p.exit_code << ","
       << csv_field(p.error);
    for (const Column& c : numeric_columns()) os << "," << cell_text(c, p);
    os << "\n";
  }
  return os.str();
}

std::string cohort_markdown(const std::vector<CohortPatient>& patients, const CohortSummary& summary,
                            const std::vector<std::pair<std::string, std::string>>& plots) {
  std::ostringstream os;
  os << "# Cohort report\n\n"
     << summary.ok << " of " << summary.patients << " patients meshed without error (success rate "
     << fmt("%.0f", 100 * summary.success_rate) << " %); " << summary.failed << " failed.\n\n"
     << "| patient | status | error |";
  for (const Column& c : numeric_columns()) os << " " << c.heading << " |";
  os << "\n| --- | --- | --- |";
  for (size_t i = 0; i < numeric_columns().size(); ++i) os << " ---: |";
  os << "\n";
  for (const CohortPatient& p : patients) {
    const std::string error = p.ok() ? "" : p.failed_step + " (exit " + std::to_string(p.exit_code) + "): " + p.error;
    os << "| " << markdown_cell(p.id) << " | " << status_text(p) << " | " << markdown_cell(error) << " |";
    for (const Column& c : numeric_columns()) os << " " << cell_text(c, p) << " |";
    os << "\n";
  }
  os << "\nOver the patients with a value (a failed patient has a mesh only when its cells stayed inverted):\n\n"
     << "| column | patients | min | median | mean | max |\n| --- | ---: | ---: | ---: | ---: | ---: |\n";
  for (size_t i = 0; i < summary.columns.size(); ++i) {
    const ColumnSummary& s = summary.columns[i];
    const char* f = numeric_columns()[i].format;
    if (s.count == 0) continue;
    os << "| " << numeric_columns()[i].heading << " | " << s.count << " | " << fmt(f, s.min) << " | "
       << fmt(f, s.median) << " | " << fmt(f, s.mean) << " | " << fmt(f, s.max) << " |\n";
  }
  for (const auto& [file, caption] : plots) os << "\n![" << caption << "](" << file << ")\n";
  return os.str();
}

}  // namespace facehex
