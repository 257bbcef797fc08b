#pragma once
// The cohort report (`facehex cohort-report`, docs/cohorts.md): one row per patient, from the status file the cohort
// workflow (workflow/Snakefile) writes after the steps of a patient and, once its transfer wrote a mesh, its
// report.json (read_run_report), patient_hex.vtu and standard_hex.vtu; summary statistics; the rows as JSON, CSV and a
// Markdown table.
//
// The status file: {"format": "facehex-cohort-status", "version": kCohortStatusVersion, "id": ID, "folder": DIR,
// "steps": [{"step": "segment" | "transfer" | "export", "exit_code": N, "error": LINE, "seconds": S,
// "slurm_job_id": ID or null}, ...]}, the steps in the order they ran; a step that failed is the last one.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace facehex {

constexpr int kCohortStatusVersion = 1;

// What the patient's run folder says of its mesh.
struct CohortMesh {
  int tets = 0, cells = 0, inverted = 0;  // patient model tets; hex mesh cells; its inverted cells
  double shape_mean = 0, standard_shape_mean = 0;
  double dihedral_change_mean_deg = 0, dihedral_change_max_deg = 0;
  double side_distance_p95_mm = 0;
  int landmarks_found = -1, landmarks_estimated = -1;  // -1: no landmarks (a constraint file was used)
  // Where the standard's landmarks landed against the patient's (report.json feature_landing), mm; -1: not measured.
  double landing_mean_mm = -1, landing_max_mm = -1;
  std::vector<double> dihedral_changes;  // deg, every cell edge's against the standard
  std::vector<double> shapes;            // every cell's shape (cell data "shape")
};

struct CohortPatient {
  std::string id, folder;
  int exit_code = 0;                    // of the step that failed, else 0
  std::string failed_step;              // empty when every step exited 0
  std::string error;                    // the failed step's error line
  double seconds = 0;                   // wall time of its steps
  std::vector<std::string> slurm_jobs;  // the Slurm jobs its steps ran in; empty when run locally
  std::optional<CohortMesh> mesh;       // when the transfer wrote a mesh (also with exit code 3: inverted cells)

  bool ok() const { return failed_step.empty(); }
};

// Throws facehex::Error naming the status file, or the report or mesh file, that cannot be read or is malformed.
CohortPatient read_cohort_patient(const std::string& status_path);

// Of one column over the patients that have a value: count, min, median, mean, max.
struct ColumnSummary {
  std::string column;
  int count = 0;
  double min = 0, median = 0, mean = 0, max = 0;
};

struct CohortSummary {
  int patients = 0, ok = 0, failed = 0;
  double success_rate = 0;  // ok / patients, in [0, 1]
  std::vector<ColumnSummary> columns;
};

CohortSummary summarize_cohort(const std::vector<CohortPatient>& patients);

// {"format": "facehex-cohort-report", "version": 1, "summary": ..., "patients": [...]}, with the same columns as the
// CSV (without the per-edge and per-cell values).
nlohmann::json cohort_json(const std::vector<CohortPatient>& patients, const CohortSummary& summary);
// One header line, then one line per patient; fields quoted where they hold a comma, a quote or a line break.
std::string cohort_csv(const std::vector<CohortPatient>& patients);
// The summary, the table and the plots (`plots`: image file name -> caption).
std::string cohort_markdown(const std::vector<CohortPatient>& patients, const CohortSummary& summary,
                            const std::vector<std::pair<std::string, std::string>>& plots);

}  // namespace facehex
