// The cohort report's rows from status files (core/workflow/cohort.h).
#include "core/workflow/cohort.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/util/error.h"
#include "core/util/text_file.h"

namespace facehex {
namespace {
namespace fs = std::filesystem;

class Cohort : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("facehex-cohort-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // A status file of patient `id` with these steps (JSON objects).
  std::string status(const std::string& id, const std::string& steps) const {
    const std::string file = path(id + ".status.json");
    write_text_file(file, R"({"format": "facehex-cohort-status", "version": 1, "id": ")" + id + R"(", "folder": ")" +
                              path(id) + R"(", "steps": [)" + steps + "]}");
    return file;
  }
  fs::path dir_;
};

// A patient whose segmentation failed: the failed step, its exit code and error line, the time of the steps that
// ran, the Slurm job, and no mesh.
TEST_F(Cohort, AFailedStepIsThePatientsFailure) {
  const CohortPatient p = read_cohort_patient(
      status("p1", R"({"step": "segment", "exit_code": 1, "error": "error: ct.mha: truncated, \"x\", y",
                       "seconds": 2.5, "slurm_job_id": "17"})"));
  EXPECT_EQ(p.id, "p1");
  EXPECT_FALSE(p.ok());
  EXPECT_EQ(p.failed_step, "segment");
  EXPECT_EQ(p.exit_code, 1);
  EXPECT_EQ(p.error, "error: ct.mha: truncated, \"x\", y");
  EXPECT_DOUBLE_EQ(p.seconds, 2.5);
  EXPECT_EQ(p.slurm_jobs, std::vector<std::string>{"17"});
  EXPECT_FALSE(p.mesh);

  const CohortSummary s = summarize_cohort({p});
  EXPECT_EQ(s.patients, 1);
  EXPECT_EQ(s.failed, 1);
  EXPECT_DOUBLE_EQ(s.success_rate, 0.0);
  // The error line holds a comma and quotes: one quoted CSV field, quotes doubled, and the line ends after the row.
  const std::string csv = cohort_csv({p});
  EXPECT_EQ(csv.substr(0, csv.find('\n')).rfind("id,status,failed_step,exit_code,error,tets,", 0), 0u);
  EXPECT_NE(csv.find("\np1,failed,segment,1,\"error: ct.mha: truncated, \"\"x\"\", y\","), std::string::npos) << csv;
  EXPECT_EQ(cohort_json({p}, s)["patients"][0]["tets"], nullptr);
}

// A status that says the patient succeeded but whose folder has no report, a file of another kind, and a status
// missing a key are one-line errors naming the file.
TEST_F(Cohort, BadStatusFilesAreErrorsNamingThem) {
  const std::string ok = status("p2", R"({"step": "transfer", "exit_code": 0, "error": "", "seconds": 1.0})");
  const std::string other = path("other.json");
  write_text_file(other, R"({"format": "facehex-report", "version": 2})");
  const std::string no_code = status("p3", R"({"step": "transfer", "error": "", "seconds": 1.0})");
  for (const auto& [file, needle] : std::vector<std::pair<std::string, std::string>>{
           {ok, "report.json is missing"}, {other, "not a cohort status file"}, {no_code, "\"exit_code\""}}) {
    try {
      read_cohort_patient(file);
      ADD_FAILURE() << file << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace facehex
