// The facehex command line as a user runs it: the demo end to end, and bad inputs.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace {
namespace fs = std::filesystem;

struct Result {
  int status;
  std::string output;  // stdout and stderr
};

Result run(const std::string& args) {
  const std::string command = std::string(FACEHEX_CLI) + " " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  std::string out;
  char buffer[4096];
  while (pipe && fgets(buffer, sizeof buffer, pipe)) out += buffer;
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("facehex-cli-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(path(name)) << text; }
  fs::path dir_;
};

// The bundled demo: CT -> patient model -> automatic constraints -> fields -> transfer -> repair -> report.
TEST_F(Cli, DemoRunsTheWholeChainFromTheBundledCt) {
  const Result r = run("run -o " + path("demo"));
  ASSERT_EQ(r.status == 0 || r.status == 3, true) << r.output;  // 3: inverted or flat cells remain (reported)
  for (const char* f : {"patient_model.vtu", "standard_hex.vtu", "patient_hex.vtu", "report.json"})
    EXPECT_TRUE(fs::exists(path("demo/") + f)) << f;
  nlohmann::json report;
  std::ifstream(path("demo/report.json")) >> report;
  const auto& q = report["patient_hex"]["quality"];
  EXPECT_EQ(q["cells"], 6342);
  EXPECT_EQ(q["hexes"], 6024);
  double percent = 0;
  for (const auto& bin : q["dihedral_distortion"]["bins"]) percent += bin["percent"].get<double>();
  EXPECT_NEAR(percent, 100.0, 1e-6);
  // Side vertices land on the patient's surface.
  EXPECT_LT(report["transfer"]["side_vertex_distance_mm"]["p95"].get<double>(), 0.05);
  // The repair never adds inverted cells, and the exit code says whether any remain.
  const int before = report["untangle"]["inverted_before"], after = report["untangle"]["inverted_after"];
  EXPECT_LE(after, before);
  EXPECT_EQ(after, q["inverted"].get<int>());
  EXPECT_EQ(r.status == 0, after + q["degenerate"].get<int>() == 0);
  // The patient's parameterization is reported, with its angles before and after the improvement.
  const auto& p = report["patient"]["parameterization"];
  EXPECT_GT(p["tets"].get<int>(), 10000);
  EXPECT_LT(p["gradient_angles_after"]["mean_deviation_from_90_deg"].get<double>(),
            p["gradient_angles_before"]["mean_deviation_from_90_deg"].get<double>());
}

TEST_F(Cli, BadInputsGiveOneLineErrorsNamingTheFileAndNoOutput) {
  Result r = run("info " + path("missing.vtu"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("missing.vtu"), std::string::npos) << r.output;

  write("garbage.vtu", "this is not a mesh");
  r = run("convert " + path("garbage.vtu") + " " + path("out.vtu"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("garbage.vtu"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("out.vtu")));

  r = run("frobnicate");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("unknown command"), std::string::npos);

  r = run("fields " + std::string(FACEHEX_TEST_DATA_DIR) + "/io/tets1.node -o " + path("f.vtu"));
  EXPECT_NE(r.status, 0);  // no side labels and no constraint set
  EXPECT_NE(r.output.find("side_mask"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("f.vtu")));
}

TEST_F(Cli, ConstraintSetErrorsNameTheConstraint) {
  const std::string standard = std::string(FACEHEX_RESOURCE_DIR) + "/standards/artisynth-refface/standard.vtu";
  write("conflict.json", R"({"format": "facehex-constraints", "version": 1, "constraints": [
    {"name": "left", "field": "u", "value": 0, "select": {"side": "u0"}},
    {"name": "right", "field": "u", "value": 1, "select": {"side": "u1"}},
    {"name": "down", "field": "v", "value": 0, "select": {"side": "v0"}},
    {"name": "up", "field": "v", "value": 1, "select": {"side": "v1"}},
    {"name": "bone", "field": "w", "value": 0, "select": {"side": "w0"}},
    {"name": "skin", "field": "w", "value": 1, "select": {"side": "w1"}},
    {"name": "clash", "field": "u", "value": 0.5, "select": {"side": "u0"}}]})");
  Result r = run("fields " + standard + " --constraints " + path("conflict.json") + " -o " + path("f.vtu"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'clash'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("f.vtu")));

  write("missing_end.json", R"({"format": "facehex-constraints", "version": 1, "constraints": [
    {"name": "left", "field": "u", "value": 0, "select": {"side": "u0"}}]})");
  r = run("fields " + standard + " --constraints " + path("missing_end.json") + " -o " + path("f.vtu"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("missing its 1 end"), std::string::npos) << r.output;

  write("empty.json", R"({"format": "facehex-constraints", "version": 1, "constraints": [
    {"name": "nowhere", "field": "u", "value": 0, "select": {"plane": {"point": [0, 0, 1000], "normal": [0, 0, 1]}}},
    {"name": "right", "field": "u", "value": 1, "select": {"side": "u1"}}]})");
  r = run("fields " + standard + " --constraints " + path("empty.json") + " -o " + path("f.vtu"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("'nowhere' selects no vertex"), std::string::npos) << r.output;
}

}  // namespace
