// The facehex command line as a user runs it: the demo end to end, and bad inputs.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "core/face/landmark_file.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/skin_points.h"
#include "core/quality/hex_quality.h"
#include "core/segment/ct_volume.h"
#include "core/segment/voxel_grid.h"
#include "core/util/resources.h"
#include "core/workflow/report.h"
#include "tests/core/segment/dicom_writer.h"
#include "tests/core/segment/pitched_ct.h"
#include "tests/core/test_meshes.h"

namespace {
namespace fs = std::filesystem;

struct Result {
  int status;
  std::string output;  // stdout and stderr
};

// env: assignments put before the command, e.g. "FACEHEX_RESOURCES=/tmp/r".
Result run_shell(const std::string& command);

Result run(const std::string& args, const std::string& env = "") {
  return run_shell(env + (env.empty() ? "" : " ") + std::string(FACEHEX_CLI) + " " + args);
}

// A shell command's output and exit status.
Result run_shell(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
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
  // The one case of `facehex bench --correspondence` on the bundled CT under the warp `seed` with `ranges`, from its
  // report (the command's output in `output`).
  nlohmann::json ct_warp_case(int seed, const std::string& ranges, std::string& output) const {
    const Result r = run("bench --correspondence -o " + path("bench") +
                         " --models none --deformation-models none --warps none --ct-seeds " + std::to_string(seed) +
                         " --ct-ranges " + ranges);
    output = r.output;
    EXPECT_EQ(r.status, 0) << r.output;
    nlohmann::json report;
    std::ifstream(path("bench/correspondence.json")) >> report;
    EXPECT_EQ(report["cases"].size(), 1u) << r.output;
    return report["cases"].empty() ? nlohmann::json::object() : report["cases"][0];
  }
  fs::path dir_;
};

// The registered skin's transfer of the bundled patient gives the same mesh, byte for byte, on one thread and on two
// (a surface locator built in parallel orders equally close triangles by thread timing, and the registration follows
// whichever comes first).
TEST_F(Cli, TheRegisteredTransferIsTheSameOnOneThreadAndOnTwo) {
  const std::string patient = facehex::default_patient().mesh;
  for (const char* threads : {"1", "2"}) {
    const Result r =
        run("map --patient " + patient + " --threads " + threads + " -o " + path(std::string("t") + threads + ".inp"));
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("skin correspondence: registered; "), std::string::npos) << r.output;
  }
  const auto bytes = [](const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string one = bytes(path("t1.inp"));
  EXPECT_FALSE(one.empty());
  EXPECT_TRUE(one == bytes(path("t2.inp")));
}

// A strong warp of the bundled CT (seed 1 of scale within 10 %, bumps up to 6 mm, a turn up to 10 degrees) folds the
// registered skin's fields where its mapping stretches cells far beyond their size. The repair's last passes move no
// vertex further than twice its edges in the standard (a side vertex sliding along its side's tangent plane would leave
// the patient), so the registered skin gives a usable mesh of the warped face.
TEST_F(Cli, AStronglyWarpedCtTransfersWithTheRegisteredSkin) {
  std::string output;
  const nlohmann::json warped = ct_warp_case(2, "0.10,0.04,6,10", output);
  ASSERT_TRUE(warped.contains("inverted")) << output;
  EXPECT_EQ(warped["skin_correspondence_used"], "registered") << warped.dump();
  EXPECT_EQ(warped["inverted"], 0);
  EXPECT_GT(warped["folded_parametric_tets"].get<int>(), 300);  // the case is a hard one
  EXPECT_GT(warped["inverted_after_mapping"].get<int>(), 0);    // ... which the relaxation and the repair untangle
  EXPECT_GT(warped["shape_solver_seconds"].get<double>(), 0);
  EXPECT_LT(warped["shape_solver_seconds"].get<double>(), warped["seconds"].get<double>());
  // The transfer's inputs against the warp of the original's: the warp keeps the scan's end slices flat, so the bottom
  // cut, the CT's bottom plus a margin on this scan, moves with it; the landmarks found on both are compared (the mouth
  // corners, found off the mid-sagittal profile, follow the turned head).
  EXPECT_NE(warped["warp"].get<std::string>().find("end slices flat"), std::string::npos) << warped["warp"];
  for (const char* cut : {"top", "bottom", "posterior", "mid-sagittal"})
    EXPECT_TRUE(warped["cut_shift_mm"].contains(cut)) << cut;
  EXPECT_LT(std::abs(warped["cut_shift_mm"]["bottom"].get<double>()), 1.0) << warped["cut_shift_mm"];
  for (const char* corner : {"cheilion left", "cheilion right"})
    EXPECT_LT(warped["landmark_shift_mm"][corner].get<double>(), 5.0) << warped["landmark_shift_mm"];
  // The warp leans the head's symmetry fit by about 10 degrees while its tragi stay level: the landmarks are read on
  // the vertical plane (face_cuts.h, landmark_plane). On the leaning one the eye corners, glabella and nasion, which
  // this CT's field-of-view cut leaves to be estimated along the plane, lay 12-23 mm from the warp of the original's.
  double shift = 0;
  for (const auto& [name, mm] : warped["landmark_shift_mm"].items()) {
    EXPECT_LT(mm.get<double>(), 10.0) << name;
    shift += mm.get<double>() / static_cast<double>(warped["landmark_shift_mm"].size());
  }
  EXPECT_LT(shift, 4.0) << warped["landmark_shift_mm"];
  EXPECT_FALSE(warped.contains("landmarks_problem")) << warped["landmarks_problem"];  // said only when none are found
  // Where the error lies: the largest ones by vertex (the first is the maximum), the skin's error across the true skin
  // (the segmentation's surface) well below its error along it (the correspondence), the inner face's, the truth's
  // own shape.
  const auto& largest = warped["largest_errors"];
  ASSERT_EQ(largest.size(), 10u);
  EXPECT_DOUBLE_EQ(largest[0]["mm"].get<double>(), warped["error_mm"]["all"]["max"].get<double>());
  for (size_t i = 1; i < largest.size(); ++i)
    EXPECT_LE(largest[i]["mm"].get<double>(), largest[i - 1]["mm"].get<double>());
  EXPECT_LT(2 * warped["skin_error_split_mm"]["across"].get<double>(),
            warped["skin_error_split_mm"]["along"].get<double>())
      << warped["skin_error_split_mm"];
  EXPECT_TRUE(warped["error_mm"]["regions"].contains("inner face"));
  EXPECT_GT(warped["truth_shape_mean"].get<double>(), 0.5 * warped["standard_shape_mean"].get<double>());
  EXPECT_NE(output.find("| headsq.mhd warp 2 |"), std::string::npos) << output;  // the input shifts' table
}

// The bundled demo with the paper's feature lines and with the registered skin held through the relaxation: the
// report says which correspondence was used, and both meshes are usable.
TEST_F(Cli, DemoWithTheFeatureLinesOrTheSkinHeld) {
  Result r = run("run -o " + path("features") + " --skin-correspondence features");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("skin correspondence: the feature constraints (the paper's)\n"), std::string::npos)
      << r.output;
  nlohmann::json report;
  std::ifstream(path("features/report.json")) >> report;
  EXPECT_EQ(report["skin_correspondence"]["mode"], "features");
  EXPECT_EQ(report["skin_correspondence"]["registered_failure"], "");
  EXPECT_EQ(report["seconds"].count("registration"), 0u);
  EXPECT_EQ(report["patient_hex"]["quality"]["inverted"], 0);

  r = run("run -o " + path("held") + " --hold-skin");
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream(path("held/report.json")) >> report;
  EXPECT_EQ(report["skin_correspondence"]["mode"], "registered");
  EXPECT_EQ(report["patient_hex"]["quality"]["inverted"], 0);
}

// The bundled demo: CT -> patient model -> automatic constraints -> fields -> transfer -> repair -> report.
TEST_F(Cli, DemoRunsTheWholeChainFromTheBundledCt) {
  const Result r = run("run -o " + path("demo") + " --threads 2");
  ASSERT_EQ(r.status, 0) << r.output;  // 3 would mean inverted or flat cells remain
  for (const char* f : {"patient_model.vtu", "standard_hex.vtu", "patient_hex.vtu", "report.json"})
    EXPECT_TRUE(fs::exists(path("demo/") + f)) << f;
  nlohmann::json report;
  std::ifstream(path("demo/report.json")) >> report;
  EXPECT_EQ(report["format"], "facehex-report");
  EXPECT_EQ(report["version"], facehex::kRunReportVersion);
  EXPECT_EQ(report["threads"], 2);  // --threads, as the process ran
  // How the CT was segmented: its thresholds and cuts as the terminal said, its noise measured and left as it is.
  const auto& segmentation = report["segmentation"];
  EXPECT_NEAR(segmentation["bone_threshold"].get<double>(), 1169.4, 0.1);
  EXPECT_GT(segmentation["noise"]["sigma"].get<double>(), 0);
  EXPECT_EQ(segmentation["noise"]["blur_mm"].get<double>(), 0);
  EXPECT_NEAR(segmentation["cuts"]["top_z"].get<double>(), 135.0, 0.05);
  EXPECT_NEAR(segmentation["edge_length_mm"].get<double>(), 3.2, 1e-6);
  EXPECT_NE(r.output.find(segmentation["summary"].get<std::string>()), std::string::npos) << r.output;
  // The bundled CT's landmarks are found, those in its field-of-view cut estimated (docs/benchmarks.md).
  EXPECT_EQ(report["landmarks"]["source"], "found");
  EXPECT_GT(report["landmarks"]["found"].get<int>(), 0);
  EXPECT_EQ(report["landmarks"]["estimated"].get<int>(), report["landmarks"]["estimated_names"].size());
  // Nothing lies on its skin (core/segment/skin_objects.h): no edge of its forehead or nose read as an object's.
  EXPECT_EQ(report["landmarks"]["skin_objects"], nlohmann::json::array());
  // Found on the plane the segmentation stored with the model, near the hand-placed reference's x = 99 (upright:
  // vertical).
  EXPECT_EQ(report["landmarks"]["mid_sagittal_plane"]["source"], "model");
  EXPECT_NEAR(report["landmarks"]["mid_sagittal_plane"]["x"].get<double>(), 99.0, 1.5);
  EXPECT_EQ(report["landmarks"]["mid_sagittal_plane"]["slope"].get<double>(), 0.0);
  // The registered skin, by default: most of the skin matched, the features at the found landmarks left out.
  const auto& skin = report["skin_correspondence"];
  EXPECT_EQ(skin["mode"], "registered");
  EXPECT_NE(r.output.find("skin correspondence: registered; "), std::string::npos) << r.output;
  EXPECT_GT(skin["vertices"].get<int>(), 5 * skin["too_far"].get<int>());
  EXPECT_LT(skin["distance_mm"]["mean"].get<double>(), 2.0);
  EXPECT_EQ(skin["left_out_constraints"].size(), 4u);
  EXPECT_EQ(report["seconds"].count("registration"), 1u);
  const auto& q = report["patient_hex"]["quality"];
  EXPECT_EQ(q["cells"], 6342);
  EXPECT_EQ(q["hexes"], 6024);
  double percent = 0;
  for (const auto& bin : q["dihedral_distortion"]["bins"]) percent += bin["percent"].get<double>();
  EXPECT_NEAR(percent, 100.0, 1e-6);
  // Side vertices land on the patient's surface (p95, issue 17's bar), except a few the repair's last passes had to
  // move off it around a fold, by millimetres, and could not step back (docs/method.md section 7): they alone make
  // the mean, which moves with the folds the mapping leaves. Which folds those are changes with the last bits of the
  // registration's sums and with the relaxation's schedule: the farthest, on the bone side of the squeezed nose, has
  // been from 2 to 11 mm off (docs/benchmarks.md). Without the step back about 150 of them stay off by more than a
  // millimetre and the mean is above 0.1 mm.
  const auto& distance = report["transfer"]["side_vertex_distance_mm"];
  EXPECT_LT(distance["mean"].get<double>(), 0.06);
  EXPECT_LT(distance["p95"].get<double>(), 0.05);
  EXPECT_LT(distance["max"].get<double>(), 12.0);
  // The mapping leaves folds (the sample CT squeezes the nose); the shape relaxation opens most of them and brings
  // the angles closer to the standard's; the repair leaves no inverted or flat cell.
  const auto& plain = report["plain_mapping"]["quality"];
  EXPECT_GT(plain["inverted"].get<int>(), 0);
  EXPECT_EQ(report["relaxation"]["inverted_before"], plain["inverted"]);
  // Measured 10-17 of 179: which few folds stay open for the repair changes with rounding and the Newton steps.
  EXPECT_LT(report["relaxation"]["inverted_after"].get<int>(), plain["inverted"].get<int>() / 5);
  EXPECT_GT(report["relaxation"]["free_vertices"].get<int>(), 8000);
  const double dihedral = q["dihedral_distortion"]["mean_deg"].get<double>();
  EXPECT_LT(dihedral, plain["dihedral_distortion"]["mean_deg"].get<double>() - 1.0);
  EXPECT_LT(dihedral, 12.0);  // the paper's 6.8 is not met on this patient (docs/results.md)
  const double standard_shape = report["standard"]["quality"]["shape_mean"].get<double>();
  EXPECT_GE(q["shape_mean"].get<double>(), 0.95 * standard_shape);
  EXPECT_EQ(report["untangle"]["inverted_after"].get<int>(), 0);
  EXPECT_EQ(report["untangle"]["degenerate_after"].get<int>(), 0);
  // Where the angles changed and how far vertices moved from the mapping, per cell and vertex in patient_hex.vtu.
  const facehex::VolumeMesh hex = facehex::read_volume_mesh(path("demo/patient_hex.vtu"));
  const Eigen::MatrixXd& change = hex.cell_data.at("dihedral_change");
  ASSERT_EQ(change.rows(), 6342);
  EXPECT_LE(change.maxCoeff(), q["dihedral_distortion"]["max_deg"].get<double>() + 1e-9);
  EXPECT_NEAR(change.mean(), dihedral, 1.0);  // per-cell means (hexes have 12 edges, wedges 9)
  EXPECT_NEAR(hex.point_data.at("moved_from_mapping").maxCoeff(),
              report["relaxation"]["moved_from_mapping_mm"]["max"].get<double>(), 1e-9);
  EXPECT_EQ(q["inverted"].get<int>(), 0);
  EXPECT_EQ(q["degenerate"].get<int>(), 0);
  // The segmentation says where it cut, so that a user can check and give other cuts (docs/segmentation.md).
  // The bundled CT ends just above the brows (top 3 mm inside it) and just below the chin (bottom 3 mm inside it).
  // The posterior cut 9 mm in front of the tragi (at y 91.2).
  EXPECT_NE(r.output.find("cuts (mm, segmentation frame): top z 135.0, bottom z 3.0, posterior y 100.2"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("found: mid-sagittal plane x 97.6"), std::string::npos) << r.output;
  // Its voxels are 3.2 mm wide: the tets are no finer (docs/segmentation.md step 8).
  EXPECT_NE(r.output.find("tets of edge length 3.2 mm (the CT's coarsest voxel spacing; --edge-length sets it)"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(path("demo/landmarks.json")));
  // The standard's parameterization came from its cache.
  const std::string source = report["standard"]["parameterization_source"].get<std::string>();
  EXPECT_NE(source.find("standard.param.vtu"), std::string::npos) << source;
  // The patient's parameterization is reported, with its angles before and after the improvement.
  const auto& p = report["patient"]["parameterization"];
  EXPECT_GT(p["tets"].get<int>(), 10000);
  EXPECT_LT(p["gradient_angles_after"]["mean_deviation_from_90_deg"].get<double>(),
            p["gradient_angles_before"]["mean_deviation_from_90_deg"].get<double>());
}

// Usage errors exit 2 (README), with one line naming the command or the option, and write nothing. Among them a
// surplus argument: a mistyped glob (`convert dir/*.vtu out.msh` with two .vtu files) must not overwrite an input.
TEST_F(Cli, UsageErrorsExitTwoAndWriteNothing) {
  const std::string tets = std::string(FACEHEX_TEST_DATA_DIR) + "/io/tets1.node";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"convert " + tets + " " + path("a.vtu") + " " + path("b.vtu"), "unexpected argument '" + path("b.vtu") + "'"},
      {"info " + tets + " extra", "unexpected argument 'extra'"},
      {"convert " + tets, "missing OUT"},
      {"convert " + tets + " " + path("a.vtu") + " --no-such-option", "unknown option --no-such-option"},
      {"convert " + tets + " " + path("a.vtu") + " --edge-length", "option --edge-length needs a value"},
      {"convert " + tets + " " + path("a.vtu") + " --edge-length two", "--edge-length expects a number"},
      {"run " + tets, "missing -o"},
      {"map --patient " + tets + " -o " + path("a.vtu") + " --method other", "--method: expects harmonic"},
      // Options that scale the work have a range: a typo must not start a run for days or exhaust the machine.
      {"convert " + tets + " " + path("a.vtu") + " --edge-length 0.05",
       "--edge-length expects a number from 0.5 to 50"},
      {"segment " + tets + " -o " + path("a.vtu") + " --edge-length inf", "--edge-length expects a number from"},
      {"fields " + tets + " -o " + path("a.vtu") + " --iterations 1e9", "--iterations expects a number from 0 to 100"},
      {"sides " + tets + " -o " + path("a.vtu") + " --max-layers 1e12", "--max-layers expects a number from 1 to 64"},
      {"fields " + tets + " -o " + path("a.vtu") + " --iterations 2.5", "--iterations expects an integer"},
      {"convert " + tets + " " + path("a.vtu") + " --threads 0", "--threads expects a number from 1 to 1024"},
      {"bench --sizes 1000000000000", "--sizes: expects tet counts up to"},
      {"bench --correspondence -o " + path("c") + " --ct-ranges 0.1,0.04,6",
       "--ct-ranges: expects SCALE,SHEAR,BUMP,TURN"},
      {"bench --correspondence -o " + path("c") + " --ct-ranges 0.1,0.04,6,90", "a turn of at most 45 degrees"},
      {"bench --correspondence -o " + path("c") + " --ct-ranges 0.1,0.04,6,0,40", "a pitch and a roll of at most 30"},
      {"bench --correspondence -o " + path("c") + " --ct-ranges 0.1,0.04,6,0,0,40", "a pitch and a roll of at most 30"},
      {"bench --correspondence -o " + path("c") + " --ct-ranges 0.1,0.04,6,0,0,0,1",
       "SCALE,SHEAR,BUMP,TURN[,PITCH[,ROLL]]"},
  };
  for (const auto& [args, needle] : cases) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find("error: "), std::string::npos) << args << ": " << r.output;
    EXPECT_NE(r.output.find(needle), std::string::npos) << args << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists(path("a.vtu")));
  EXPECT_FALSE(fs::exists(path("b.vtu")));
}

// constraints writes the landmarks it found (both formats), reads them back with --landmarks to the same constraint
// values, and a bad or implausible landmark file is a one-line error naming it.
TEST_F(Cli, ConstraintsWriteAndTakeLandmarkFiles) {
  const std::string model = facehex::default_patient().mesh;
  Result r = run("constraints " + model + " -o " + path("found.json") + " --write-landmarks " + path("l.mrk.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const std::vector<facehex::NamedLandmark> found = facehex::read_landmark_file(path("l.mrk.json"));
  EXPECT_GE(found.size(), 7u);
  r = run("constraints " + model + " -o " + path("given.json") + " --landmarks " + path("l.mrk.json") +
          " --write-landmarks " + path("given-landmarks.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const facehex::ConstraintSet a = facehex::read_constraint_set(path("found.json")),
                               b = facehex::read_constraint_set(path("given.json"));
  ASSERT_EQ(a.constraints.size(), b.constraints.size());
  for (std::size_t i = 0; i < a.constraints.size(); ++i) EXPECT_EQ(a.constraints[i].value, b.constraints[i].value);
  for (const auto& l : facehex::read_landmark_file(path("given-landmarks.json")))
    EXPECT_EQ(l.status, facehex::LandmarkStatus::given) << l.name;

  std::ofstream(path("bad.json")) << R"({"format": "facehex-landmarks", "landmarks": [{"name": "nose"}]})";
  r = run("constraints " + model + " -o " + path("x.json") + " --landmarks " + path("bad.json"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(path("bad.json") + ": unknown landmark 'nose'"), std::string::npos) << r.output;
  // The stomion moved above the upper lip: implausible, named.
  std::vector<facehex::NamedLandmark> moved = found;
  for (auto& l : moved)
    if (l.name == "stomion") l.position.z() += 30;
  facehex::write_landmark_file(path("moved.json"), moved);
  r = run("constraints " + model + " -o " + path("x.json") + " --landmarks " + path("moved.json"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("implausible stomion"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("x.json")));
  // The mouth corners' sides swapped (a Slicer file placed with the patient's sides read as the viewer's): named.
  std::vector<facehex::NamedLandmark> swapped = found;
  for (auto& l : swapped)
    if (l.name.rfind("cheilion", 0) == 0) l.name = l.name == "cheilion left" ? "cheilion right" : "cheilion left";
  facehex::write_landmark_file(path("swapped.mrk.json"), swapped);
  r = run("constraints " + model + " -o " + path("x.json") + " --landmarks " + path("swapped.mrk.json"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("implausible cheilion"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("across the mid-sagittal plane"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("x.json")));
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

  for (const char* bad : {"--ct 512,512", "--ct 512,x,300", "--ct 1,512,300", "--sizes 100,-5"}) {
    r = run(std::string("bench ") + bad);
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;  // a usage error
    EXPECT_NE(r.output.find(std::string(bad).substr(0, std::string(bad).find(' '))), std::string::npos) << r.output;
  }
}

// A DICOM folder as scanners export it, the axial series beside a localizer: segmenting it asks which series (exit
// 1, the list numbered, the option named, nothing written); named, it is segmented; named for a file, an error. The
// landmarks it writes as a Slicer file are in the series' LPS frame with the patient's sides (the left eye's and
// mouth's corners at larger x than the right's), and read back onto the model by constraints, they are written again
// the same.
TEST_F(Cli, ADicomFolderWithSeveralSeriesIsSegmentedByTheOneNamed) {
  const fs::path folder = dir_ / "export";
  fs::create_directories(folder);
  facehex::testing::write_bundled_series(folder, [](int) { return 0; });
  facehex::testing::SliceSpec localizer;
  localizer.series_uid = "1.2.826.0.1.3680043.9.7777.9";
  localizer.description = "localizer";
  facehex::testing::write_slice((folder / "scout.dcm").string(), localizer, std::vector<std::int16_t>(6, 5));
  Result r = run("segment " + folder.string() + " -o " + path("m.vtu"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("2: 1 files of series 1.2.826.0.1.3680043.9.7777.9 (localizer)"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("--series"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("m.vtu")));
  r = run("segment " + folder.string() + " --series 1 -o " + path("m.vtu") + " --write-landmarks " +
          path("l.mrk.json"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(path("m.vtu")));
  std::map<std::string, Eigen::Vector3d> written;
  for (const facehex::NamedLandmark& l : facehex::read_landmark_file(path("l.mrk.json"))) written[l.name] = l.position;
  for (const std::string pair : {"exocanthion", "endocanthion", "cheilion"}) {
    ASSERT_TRUE(written.count(pair + " left") && written.count(pair + " right")) << pair;
    EXPECT_GT(written.at(pair + " left").x(), written.at(pair + " right").x() + 20) << pair;
  }
  r = run("constraints " + path("m.vtu") + " -o " + path("c.json") + " --landmarks " + path("l.mrk.json") +
          " --write-landmarks " + path("back.mrk.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const std::vector<facehex::NamedLandmark> back = facehex::read_landmark_file(path("back.mrk.json"));
  ASSERT_EQ(back.size(), written.size());
  for (const facehex::NamedLandmark& l : back) EXPECT_LT((l.position - written.at(l.name)).norm(), 1e-6) << l.name;
  r = run("info " + path("m.vtu"));
  EXPECT_NE(r.output.find("scan frame: the patient's left at -x of the model; model (x, y, z) at scan (-x, -y, z) mm"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("landmarks found in the CT by the segmentation:\n    tragus left ("), std::string::npos)
      << r.output;
  r = run("segment " + facehex::default_ct() + " --series 1 -o " + path("n.vtu"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("not a DICOM folder"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("n.vtu")));
}

TEST_F(Cli, SegmentTakesTheCutsGivenAndRejectsBadOnes) {
  const std::string ct = facehex::default_ct();
  // Automatic: the posterior cut 10 mm in front of the ears (y = 102 on this CT); given: 8 mm further forward.
  Result r = run("segment " + ct + " --edge-length 4 --posterior-cut 110 --mid-plane 100 -o " + path("cut.vtu"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("posterior y 110.0, mid-plane x 100.0"), std::string::npos) << r.output;
  const facehex::VolumeMesh model = facehex::read_volume_mesh(path("cut.vtu"));
  EXPECT_GE(model.V.col(1).minCoeff(), 110.0 - 1e-6);
  EXPECT_LT(model.V.col(1).minCoeff(), 110.0 + 1.0);  // the lateral ends lie on the plane
  // The mid-sagittal plane given (or found) travels with the model, for the landmark finder.
  r = run("info " + path("cut.vtu"));
  EXPECT_NE(r.output.find("mid_sagittal_plane(field,1x3)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mid-sagittal plane x = 100.0 mm at z = 0.0 mm, leaning 0.0 degrees"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("skin points "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("scan frame: the patient's left at +x of the model; model (x, y, z) at scan (x, y, z) mm"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("landmarks found in the CT by the segmentation:\n    tragus right ("), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("\n    exocanthion left "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\n    stomion ("), std::string::npos) << r.output;
  // The bundled CT's 3.2 mm voxels do not show the lips' slit's ends: its mouth corners are the skin's.
  EXPECT_NE(r.output.find("\n    cheilion right unseen\n    cheilion left unseen\n    bony menton ("),
            std::string::npos)
      << r.output;
  // A turn given: the cuts are placed in the head frame turned by it, the model stays in the CT's frame and its plane
  // says how it is turned.
  r = run("segment " + ct + " --edge-length 4 --head-turn -5 -o " + path("turned.vtu"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("head turned -5.0 deg about the vertical axis"), std::string::npos) << r.output;
  r = run("info " + path("turned.vtu"));
  EXPECT_NE(r.output.find("mid_sagittal_plane(field,1x5)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(", turned -5.0 degrees"), std::string::npos) << r.output;
  // A pitch given: the same, about the lateral axis, and the plane carries the pitch.
  r = run("segment " + ct + " --edge-length 4 --head-pitch -8 -o " + path("pitched.vtu"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("head pitched -8.0 deg (chin lowered) about the lateral axis"), std::string::npos)
      << r.output;
  r = run("info " + path("pitched.vtu"));
  EXPECT_NE(r.output.find("mid_sagittal_plane(field,1x6)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(", pitched -8.0 degrees"), std::string::npos) << r.output;
  // A turn or a pitch far from the head's: no face in the head frame (this upright face's front, clipped flat by the
  // field of view, shows a "nose" on the forehead, over 115 mm above the chin), and the error names the option.
  for (const char* option : {"--head-turn 5", "--head-turn 12", "--head-pitch 8"}) {
    const std::string wrong = option;
    r = run("segment " + ct + " --edge-length 4 " + wrong + " -o " + path("wrong.vtu"));
    EXPECT_EQ(r.status, 1) << wrong << ": " << r.output;
    EXPECT_NE(r.output.find("above the chin's lowest bone"), std::string::npos) << wrong << ": " << r.output;
    EXPECT_NE(r.output.find(wrong.substr(0, wrong.find(' '))), std::string::npos) << wrong << ": " << r.output;
    EXPECT_FALSE(fs::exists(path("wrong.vtu")));
  }

  for (const char* bad : {"--ear-clearance -1", "--brow-clearance -2", "--top-cut nan", "--chin-clearance x",
                          "--max-depth 0", "--smoothing -1", "--bone-gap x", "--min-thickness -3", "--cavity-closing y",
                          "--head-turn 60", "--head-turn x", "--head-pitch -50", "--head-pitch x"}) {
    r = run("segment " + ct + " " + bad + " -o " + path("bad.vtu"));
    EXPECT_EQ(r.status, 2) << bad << ": " << r.output;  // a usage error
    EXPECT_NE(r.output.find(std::string(bad).substr(0, std::string(bad).find(' '))), std::string::npos) << r.output;
  }
  r = run("segment " + ct + " --top-cut 40 --bottom-cut 35 -o " + path("bad.vtu"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("top cut (z = 40"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("bad.vtu")));
}

// At 3.5 mm edges the remeshed surface of the bundled CT crosses itself once; the segmentation remeshes 3 % finer and
// goes on.
TEST_F(Cli, SegmentRemeshesASurfaceThatCrossesItself) {
  // Cuts pinned where this crossing was seen (the automatic ones move with the anatomy rules).
  const Result r = run("segment " + facehex::default_ct() +
                       " --edge-length 3.5 --top-cut 135 --mid-plane 98.4 --posterior-cut 100 -o " + path("p.vtu"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("remeshing the surface again"), std::string::npos) << r.output;
  EXPECT_GT(facehex::read_volume_mesh(path("p.vtu")).num_cells(), 80000);
}

// The landmarks are read from the CT's skin points the model carries (core/mesh/skin_points.h): segmenting the CT
// and reading the model it wrote find the same landmarks, to the bit.
TEST_F(Cli, TheModelsStoredSkinGivesTheSameLandmarksAsItsSegmentation) {
  Result r = run("segment " + facehex::default_ct() + " --edge-length 4 -o " + path("m.vtu") + " --write-landmarks " +
                 path("segmented.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  r = run("constraints " + path("m.vtu") + " -o " + path("c.json") + " --write-landmarks " + path("read.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  const std::vector<facehex::NamedLandmark> segmented = facehex::read_landmark_file(path("segmented.json"));
  const std::vector<facehex::NamedLandmark> read = facehex::read_landmark_file(path("read.json"));
  ASSERT_EQ(read.size(), segmented.size());
  EXPECT_GE(read.size(), 9u);
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].name, segmented[i].name);
    EXPECT_EQ(read[i].position, segmented[i].position) << read[i].name;
  }
}

// segment --write-landmarks checks the landmarks before it writes: a model cut below the nose (top cut at z 62) reads
// the lips as a nose too short for an adult, and the command fails naming the landmark and the ways out, with neither
// the model nor the landmark file written.
TEST_F(Cli, SegmentWritesNothingWhenItsLandmarksAreImplausible) {
  const Result r = run("segment " + facehex::default_ct() + " --edge-length 4 --top-cut 62 -o " + path("cut.vtu") +
                       " --write-landmarks " + path("cut.json"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("error: landmarks: implausible subnasale"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--landmarks FILE"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("without --write-landmarks"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("cut.vtu")));
  EXPECT_FALSE(fs::exists(path("cut.json")));
}

// The bundled CT meshed at 3 mm: the repair's first five last-resort passes left one fold here (the nose, where the
// coarse model is thin); the later passes and keeping the best state leave none.
TEST_F(Cli, TheBundledCtMeshedAt3mmEndsWithNoInvertedCell) {
  const Result r = run("run " + facehex::default_ct() + " --edge-length 3 -o " + path("run"));
  ASSERT_EQ(r.status, 0) << r.output;  // 3 would mean inverted or flat cells remain
  nlohmann::json report;
  std::ifstream(path("run/report.json")) >> report;
  EXPECT_GT(report["untangle"]["inverted_before"].get<int>(), 0);
  EXPECT_EQ(report["untangle"]["inverted_after"].get<int>(), 0);
  EXPECT_EQ(report["patient_hex"]["quality"]["inverted"].get<int>(), 0);
  EXPECT_EQ(report["patient_hex"]["quality"]["degenerate"].get<int>(), 0);
  // Where the standard's landmarks landed: the profile's, the eye and mouth corners, each against the patient's. The
  // registration snaps them onto the patient's, and the repair untangles the folds around them (the clipped nose's
  // pronasale is in one here) without moving them: every one within 1.5 mm.
  EXPECT_NE(r.output.find("anatomy: the standard's 13 landmarks land "), std::string::npos) << r.output;
  ASSERT_EQ(report["feature_landing"]["landmarks"].size(), 13u);
  for (const auto& l : report["feature_landing"]["landmarks"]) {
    EXPECT_GE(l["mm"].get<double>(), 0.0);
    EXPECT_LE(l["mm"].get<double>(), report["feature_landing"]["max_mm"].get<double>());
  }
  EXPECT_LT(report["feature_landing"]["max_mm"].get<double>(), 1.5) << r.output;
  // The profile's landmarks lie on the skin, where the registration pins the fields under them: exactly there.
  for (const auto& l : report["feature_landing"]["landmarks"])
    for (const char* on_skin : {"glabella", "nasion", "pronasale", "subnasale", "labrale superius", "labrale inferius"})
      if (l["name"] == on_skin) {
        EXPECT_LT(l["mm"].get<double>(), 0.2) << on_skin;
      }
  // Pulled by the landmarks found on the patient (the default), the standard's land on them: the stomion and the mouth
  // corners, which the registered skin alone leaves several millimetres off, and the found ones on average by half.
  // Against the hand-placed landmarks (tests/data/landmarks), where the standard's landed is within 2.5 mm on average.
  const auto found_landing = [](const nlohmann::json& landing) {
    std::map<std::string, double> mm;
    for (const auto& l : landing["landmarks"])
      if (l["patient"] == "found") mm[l["name"].get<std::string>()] = l["mm"].get<double>();
    return mm;
  };
  const std::map<std::string, double> pulled = found_landing(report["feature_landing"]);
  const Result free_run =
      run("run " + facehex::default_ct() + " --edge-length 3 --pull-found-landmarks off -o " + path("free"));
  ASSERT_EQ(free_run.status, 0) << free_run.output;
  nlohmann::json free_report;
  std::ifstream(path("free/report.json")) >> free_report;
  EXPECT_EQ(free_report["patient_hex"]["quality"]["inverted"].get<int>(), 0);
  const std::map<std::string, double> free = found_landing(free_report["feature_landing"]);
  ASSERT_EQ(pulled.size(), free.size());
  double free_sum = 0, pulled_sum = 0;
  for (const auto& [name, mm] : free) free_sum += mm, pulled_sum += pulled.at(name);
  EXPECT_LT(pulled_sum, 0.5 * free_sum);
  EXPECT_LT(pulled.at("stomion"), 1.5);
  EXPECT_GT(free.at("stomion"), 5.0);
  for (const char* corner : {"cheilion left", "cheilion right"})
    EXPECT_LT(pulled.at(corner), 0.6 * free.at(corner)) << corner;
  const auto against_hand_placed = [](const nlohmann::json& landing) {
    const std::vector<facehex::NamedLandmark> reference =
        facehex::read_landmark_file(std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/headsq.json");
    double sum = 0;
    int count = 0;
    for (const auto& l : landing["landmarks"])
      for (const facehex::NamedLandmark& r : reference)
        if (r.name == l["name"].get<std::string>()) {
          const auto at = l["landed"].get<std::vector<double>>();
          sum += std::hypot(at[0] - r.position.x(), at[2] - r.position.z());
          ++count;
        }
    return count > 0 ? sum / count : 1e9;
  };
  EXPECT_LT(against_hand_placed(report["feature_landing"]), 2.5);
  EXPECT_GT(against_hand_placed(free_report["feature_landing"]), 4.0);
  const Result bad = run("run " + facehex::default_ct() + " --pull-found-landmarks maybe -o " + path("bad"));
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--pull-found-landmarks: expects on or off, got 'maybe'"), std::string::npos) << bad.output;
  const Result objects = run("segment " + facehex::default_ct() + " --skin-objects maybe -o " + path("bad.vtu"));
  EXPECT_EQ(objects.status, 2) << objects.output;
  EXPECT_NE(objects.output.find("--skin-objects: expects on or off, got 'maybe'"), std::string::npos) << objects.output;
  EXPECT_FALSE(fs::exists(path("bad.vtu")));
  // A landmark left out of the pull by name: that one lands where the skin's registration puts it (the right mouth
  // corner millimetres off), the others as pulled.
  const Result some = run("run " + facehex::default_ct() +
                          " --edge-length 3 --landmarks-not-pulled 'cheilion right' -o " + path("some"));
  ASSERT_EQ(some.status, 0) << some.output;
  nlohmann::json some_report;
  std::ifstream(path("some/report.json")) >> some_report;
  const std::map<std::string, double> some_pulled = found_landing(some_report["feature_landing"]);
  ASSERT_EQ(some_pulled.size(), pulled.size());
  EXPECT_GT(some_pulled.at("cheilion right"), 1.0);
  for (const auto& [name, mm] : pulled) {
    if (name == "cheilion right") continue;
    EXPECT_LT(some_pulled.at(name), mm + 0.5) << name;
  }
  for (const auto& l : some_report["feature_landing"]["landmarks"])
    EXPECT_EQ(l["pulled"].get<bool>(), l["name"] != "cheilion right") << l["name"];
  EXPECT_NE(some.output.find("; not pulled: cheilion right\n"), std::string::npos) << some.output;
  const Result unknown =
      run("run " + facehex::default_ct() + " --landmarks-not-pulled 'glabella,chelion left' -o " + path("unknown"));
  EXPECT_EQ(unknown.status, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("--landmarks-not-pulled: 'chelion left' is no landmark FaceHex knows (glabella, "),
            std::string::npos)
      << unknown.output;
}

// The bundled CT with its chin lowered 8 degrees on its own grid (tests/core/segment/pitched_ct.h): its last slice
// leans down to the front and crosses the forehead's front below the head's highest level. A top cut at that level
// less the margin left the forehead's front ending in the tilted slice, and the fields folded there (2 % of the tets,
// the run refused); cut below where the slice crosses the front (face_anatomy.h, rule 3b), the run ends with no
// inverted cell.
TEST_F(Cli, TheBundledCtPitchedOnItsGridIsCutBelowItsTiltedLastSlice) {
  const facehex::HeadTurn scan = facehex::testing::bundled_ct_pitch(8);
  facehex::write_ct_volume(path("pitched.mha"),
                           facehex::testing::pitched_on_its_grid(facehex::read_ct_volume(facehex::default_ct()), scan));
  const Result r = run("run " + path("pitched.mha") + " -o " + path("run"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("the forehead's front whole up to z"), std::string::npos) << r.output;
  nlohmann::json report;
  std::ifstream(path("run/report.json")) >> report;
  EXPECT_EQ(report["patient_hex"]["quality"]["inverted"].get<int>(), 0);
  EXPECT_EQ(report["patient_hex"]["quality"]["degenerate"].get<int>(), 0);
}

// The bundled CT under a warp that pitches it 7.3 degrees with the chin raised (the benchmark's pitched ranges, seed
// 3): the warped volume ends where the original's tilted last slice does, which crosses the face region from the
// posterior cut (z 133) to the forehead (z 141). A top cut at 138.3 left the back of the region ending in that slice,
// and the registered skin's fields folded there (half the folds at the top cut), the feature lines diverged: no mesh.
// Below where the region's section is whole (face_cuts.h, section_end_z), the transfer makes one with no inverted cell.
TEST_F(Cli, ACtWhoseLastSliceLeansAcrossTheFaceRegionIsCutBelowIt) {
  std::string output;
  const nlohmann::json pitched = ct_warp_case(3, "0.08,0.04,4,0,15", output);
  ASSERT_FALSE(pitched.contains("failure")) << pitched["failure"];
  EXPECT_EQ(pitched["skin_correspondence_used"], "registered");
  EXPECT_EQ(pitched["inverted"], 0);
}

// The bundled CT stored with other voxel axes (the face towards the file's -z, the top of the head towards +y), read
// with --anterior -z --superior +y: the same model, moved (the flipped axis starts elsewhere). The turned CT's
// resampling differs a little, and its automatic cuts make a surface that touches itself; the cuts moved by a
// fraction of a voxel make a closed one (level_surface_with_cuts in soft_tissue.cpp).
TEST_F(Cli, ACtStoredWithOtherAxesGivesTheSameModel) {
  const facehex::CtVolume ct = facehex::read_ct_volume(facehex::default_ct());
  const facehex::GridGeometry& g = ct.intensity.geometry;
  facehex::CtVolume turned = ct;
  facehex::GridGeometry& t = turned.intensity.geometry;
  t.dims = {g.dims[0], g.dims[2], g.dims[1]};
  t.spacing = Eigen::Vector3d(g.spacing.x(), g.spacing.z(), g.spacing.y());
  t.origin.setZero();
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) turned.intensity(i, k, g.dims[1] - 1 - j) = ct.intensity(i, j, k);
  facehex::write_ct_volume(path("turned.mha"), turned);
  const Result a = run("segment " + facehex::default_ct() + " --edge-length 4 -o " + path("a.vtu"));
  const Result b =
      run("segment " + path("turned.mha") + " --anterior -z --superior +y --edge-length 4 -o " + path("b.vtu"));
  ASSERT_EQ(a.status, 0) << a.output;
  ASSERT_EQ(b.status, 0) << b.output;
  const facehex::VolumeMesh ma = facehex::read_volume_mesh(path("a.vtu")),
                            mb = facehex::read_volume_mesh(path("b.vtu"));
  // Nearly the same: the cuts of one were moved by a third of a millimetre, where the sides slope and the bottom cut
  // grazes the surface (a sliver there changes the count of small boundary triangles by a few per cent).
  EXPECT_NEAR(mb.num_vertices(), ma.num_vertices(), 0.05 * ma.num_vertices()) << a.output << b.output;
  const Eigen::RowVector3d extent_a = ma.V.colwise().maxCoeff() - ma.V.colwise().minCoeff(),
                           extent_b = mb.V.colwise().maxCoeff() - mb.V.colwise().minCoeff();
  EXPECT_LT((extent_a - extent_b).cwiseAbs().maxCoeff(), 2.0) << extent_a << " / " << extent_b;
  // The same x and z; y shifted by the flipped axis' length (the file's z extent).
  EXPECT_NEAR(mb.V.col(0).minCoeff(), ma.V.col(0).minCoeff(), 1.0);
  EXPECT_NEAR(mb.V.col(2).minCoeff(), ma.V.col(2).minCoeff(), 1.0);
  EXPECT_NEAR(mb.V.col(1).minCoeff(), ma.V.col(1).minCoeff() - (g.dims[1] - 1) * g.spacing.y(), 1.0);
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

// A tiny standard (a slab of 4 x 2 x 5 hexes) and a tiny patient (a finer tet mesh of the slab, sheared, scaled and
// moved), each with its six sides as constraint set beside it (NAME.json).
void write_tiny_models(const fs::path& dir) {
  using namespace facehex;
  auto path = [&](const char* name) { return (dir / name).string(); };
  const VolumeMesh standard = test::hex_box(4, 2, 5, 40, 10, 50);
  write_volume_mesh(path("std.vtu"), standard);
  write_constraint_set(path("std.json"), side_constraints());
  const VolumeMesh fine = test::hex_box(6, 3, 8, 40, 10, 50);
  Eigen::MatrixXd V = fine.V;
  V.col(0) = 1.2 * fine.V.col(0) + 0.1 * fine.V.col(2);
  V.col(2) *= 0.9;
  V.rowwise() += Eigen::RowVector3d(100, 50, -20);
  VolumeMesh patient = VolumeMesh::from_tets(V, split_into_tets(fine).T);
  patient.point_data = fine.point_data;
  write_volume_mesh(path("box.vtu"), patient);
  write_constraint_set(path("box.json"), side_constraints());
}

bool is_png(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  char signature[4] = {};
  in.read(signature, 4);
  return std::string(signature + 1, 3) == "PNG";
}

int nonempty_lines(const std::string& text) {
  int n = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) n += !line.empty();
  return n;
}

// facehex template on a tiny model: a standard folder that --standard takes, and one-line errors for bad inputs.
TEST_F(Cli, TemplateBuildsAStandardThatRunAccepts) {
  write_tiny_models(dir_);
  Result r = run("template " + path("box.vtu") + " --constraints " + path("box.json") +
                 " --cell-size 10 --layers 2 -o " + path("tpl"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"standard.vtu", "constraints.json", "README.md"})
    EXPECT_TRUE(fs::exists(path("tpl/") + f)) << f;
  const facehex::VolumeMesh tpl = facehex::read_volume_mesh(path("tpl/standard.vtu"));
  EXPECT_EQ(tpl.count(facehex::CellType::Hex), tpl.num_cells());
  EXPECT_GT(tpl.num_cells(), 10);
  r = run("run " + path("box.vtu") + " --constraints " + path("box.json") + " --standard " + path("tpl/standard.vtu") +
          " -o " + path("out"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(path("out/patient_hex.vtu")));

  r = run("template " + path("box.vtu") + " --constraints " + path("box.json"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("missing -o"), std::string::npos) << r.output;
  r = run("template " + path("nothing.vtu") + " -o " + path("bad"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("nothing.vtu"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("bad/standard.vtu")));
  r = run("template " + path("box.vtu") + " --constraints " + path("box.json") + " --layers 0 -o " + path("bad"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("layers"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("bad/standard.vtu")));

  r = run("standards");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("artisynth-refface"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("headsq-template"), std::string::npos) << r.output;
}

// A bundled standard's parameterization cache: written by `facehex standards --write-cache`, read by `run`, and when
// the standard's constraint set changes, not used: the run says so, recomputes, and succeeds.
TEST_F(Cli, StaleParameterizationCacheIsReportedAndRecomputed) {
  write_tiny_models(dir_);
  fs::create_directories(path("res/standards/tiny"));
  fs::copy_file(path("std.vtu"), path("res/standards/tiny/standard.vtu"));
  fs::copy_file(path("std.json"), path("res/standards/tiny/constraints.json"));
  const std::string env = "FACEHEX_RESOURCES=" + path("res");
  Result r = run("standards --write-cache", env);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(path("res/standards/tiny/standard.param.vtu")));
  EXPECT_TRUE(fs::exists(path("res/standards/tiny/standard.param.json")));
  const std::string patient = path("box.vtu") + " --constraints " + path("box.json") + " --standard tiny";
  auto source = [&](const std::string& out) {
    nlohmann::json report;
    std::ifstream(path(out + "/report.json")) >> report;
    return report["standard"]["parameterization_source"].get<std::string>();
  };
  r = run("run " + patient + " -o " + path("fresh"), env);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(source("fresh"), path("res/standards/tiny/standard.param.vtu"));
  EXPECT_EQ(r.output.find("note:"), std::string::npos) << r.output;

  facehex::ConstraintSet renamed = facehex::side_constraints();
  renamed.constraints[0].name = "left end";
  facehex::write_constraint_set(path("res/standards/tiny/constraints.json"), renamed);
  r = run("run " + patient + " -o " + path("stale"), env);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("made from another standard mesh, constraint set or field options"), std::string::npos)
      << r.output;
  EXPECT_EQ(source("stale"), "computed");
}

// The registered skin on tiny meshes; and on a patient whose skin faces -y, which the registration cannot take (its
// frame check): the run goes on with the feature lines (here the constraint file's sides) and says why.
TEST_F(Cli, ARegistrationThatCannotRunFallsBackToTheFeatureLines) {
  write_tiny_models(dir_);
  const std::string standard = " --standard " + path("std.vtu");
  Result r = run("run " + path("box.vtu") + standard + " -o " + path("box"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("skin correspondence: registered; "), std::string::npos) << r.output;
  nlohmann::json report;
  std::ifstream(path("box/report.json")) >> report;
  EXPECT_EQ(report["skin_correspondence"]["left_out_constraints"].size(), 0u);  // a constraint file is kept whole

  facehex::VolumeMesh turned = facehex::read_volume_mesh(path("box.vtu"));
  turned.V.col(0) *= -1;  // a half turn about z: the skin now behind the bone, the tets still positive
  turned.V.col(1) *= -1;
  facehex::write_volume_mesh(path("turned.vtu"), turned);
  fs::copy_file(path("box.json"), path("turned.json"));
  r = run("run " + path("turned.vtu") + standard + " -o " + path("turned"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("skin correspondence: the feature constraints (the paper's), since the registered skin gave "
                          "no usable map ("),
            std::string::npos)
      << r.output;
  std::ifstream(path("turned/report.json")) >> report;
  EXPECT_EQ(report["skin_correspondence"]["mode"], "features");
  EXPECT_NE(report["skin_correspondence"]["registered_failure"].get<std::string>().find("+y"), std::string::npos);
  EXPECT_EQ(report["patient_hex"]["quality"]["inverted"], 0);

  // With the lateral ends swapped in its constraint file the feature lines fail too (the opposite handedness): one
  // error giving both reasons, the registered skin's first.
  nlohmann::json swapped;
  std::ifstream(path("box.json")) >> swapped;
  for (auto& c : swapped["constraints"])
    if (c["field"] == "u" && c["select"].contains("side")) c["value"] = 1.0 - c["value"].get<double>();
  fs::copy_file(path("turned.vtu"), path("swapped.vtu"));
  std::ofstream(path("swapped.json")) << swapped;
  r = run("run " + path("swapped.vtu") + standard + " -o " + path("swapped"));
  EXPECT_EQ(r.status, 1) << r.output;
  const size_t registered = r.output.find("the registered skin gave no usable map ("),
               features = r.output.find("), nor did the feature lines: "), handedness = r.output.find("handedness");
  EXPECT_NE(registered, std::string::npos) << r.output;
  EXPECT_NE(features, std::string::npos) << r.output;
  EXPECT_NE(handedness, std::string::npos) << r.output;
  EXPECT_LT(registered, features);
  EXPECT_LT(features, handedness);
  EXPECT_FALSE(fs::exists(path("swapped")));

  // Without its constraint file no feature lines can be placed on a box either: one error naming both reasons.
  fs::copy_file(path("turned.vtu"), path("bare.vtu"));
  r = run("run " + path("bare.vtu") + standard + " -o " + path("bare"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("note: the registered skin places the face without them"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the registered skin gave no usable map ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("and the facial feature lines cannot be placed ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--landmarks FILE"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("bare")));
}

// The bundled CT meshed at 6 mm, whose mid-sagittal profile has too few vertices for the landmark finder to read the
// lips: the registered skin places the face without the feature lines and says so; with the feature lines the run
// stops naming --landmarks.
TEST_F(Cli, TheRegisteredSkinNeedsNoLandmarks) {
  // A model meshed at 6 mm edges without the CT's skin points (a mesh from elsewhere): its own skin is too sparse
  // for the landmarks (with the posterior cut at y 100 and the mid-plane at x 98.4; how a 6 mm mesh's few profile
  // vertices fall depends on them).
  Result r = run("segment " + facehex::default_ct() + " --edge-length 6 --posterior-cut 100 --mid-plane 98.4 -o " +
                 path("coarse.vtu"));
  ASSERT_EQ(r.status, 0) << r.output;
  facehex::VolumeMesh model = facehex::read_volume_mesh(path("coarse.vtu"));
  ASSERT_EQ(model.field_data.erase(facehex::kSkinPointsField), 1u);
  facehex::write_volume_mesh(path("coarse.vtu"), model);
  r = run("run " + path("coarse.vtu") + " -o " + path("coarse"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("only: no facial features (landmarks: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("note: the registered skin places the face without them"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("skin correspondence: registered; "), std::string::npos) << r.output;
  r = run("run " + path("coarse.vtu") + " --skin-correspondence features -o " + path("features"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("--landmarks FILE"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("features")));
}

TEST_F(Cli, CompareOnTinyMeshesWritesTheReportAndMapRunsTheBaseline) {
  write_tiny_models(dir_);
  Result r = run("compare " + path("box.vtu") + " -o " + path("out") + " --standard " + path("std.vtu"));
  ASSERT_EQ(r.status, 0) << r.output;
  nlohmann::json report;
  std::ifstream(path("out/report.json")) >> report;
  ASSERT_EQ(report["patients"].size(), 1u);
  const auto& patient = report["patients"][0];
  EXPECT_EQ(patient["name"], "box");
  EXPECT_EQ(patient["constraints"], path("box.json"));
  for (const char* method : {"harmonic", "mesh-matching"}) {
    const auto& m = patient["methods"][method];
    for (const char* key : {"shape_mean", "dihedral_mean", "inverted", "seconds"}) EXPECT_TRUE(m.contains(key)) << key;
    EXPECT_EQ(m["inverted"], 0) << method;
    EXPECT_GT(m["shape_mean"].get<double>(), 0.7) << method;  // the standard's is 0.84, the map nearly affine
    EXPECT_LT(m["dihedral_mean"].get<double>(), 5.0) << method;
    EXPECT_GT(m["seconds"].get<double>(), 0.0) << method;
  }
  EXPECT_EQ(report["paper"]["table1"]["harmonic"]["mean"], 6.8);
  for (const auto& [kind, file] : patient["plots"].items())
    EXPECT_TRUE(is_png(path("out/") + file.get<std::string>())) << kind;
  std::ifstream md(path("out/report.md"));
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Table 1"), std::string::npos);
  EXPECT_NE(text.find("| box |"), std::string::npos);

  r = run("map --method mesh-matching --patient " + path("box.vtu") + " --standard " + path("std.vtu") + " -o " +
          path("mm.vtu") + " --report " + path("mm.json"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(path("mm.vtu")));
  nlohmann::json mm;
  std::ifstream(path("mm.json")) >> mm;
  EXPECT_EQ(mm["method"], "mesh-matching");
  EXPECT_LT(mm["transfer"]["side_vertex_distance_mm"]["max"].get<double>(), 0.5);
}

// The tiny standard onto a slab bent into a ring of 300 degrees (about the y axis, so the skin side stays in front):
// the baseline's registration folds cells there and writes them as they are, the harmonic transfer mends its folds.
// `map` exits 3 exactly when the mesh it wrote has unusable cells (README), whichever method made it.
TEST_F(Cli, MapExitsThreeExactlyWhenTheResultHasUnusableCells) {
  using namespace facehex;
  write_tiny_models(dir_);
  const VolumeMesh fine = test::hex_box(24, 3, 10, 40, 10, 50);
  Eigen::MatrixXd V = fine.V;
  for (int v = 0; v < V.rows(); ++v) {
    const double a = fine.V(v, 0) / 40 * 300 * M_PI / 180, r = 10 + fine.V(v, 2);
    V.row(v) << r * std::cos(a), fine.V(v, 1), -r * std::sin(a);
  }
  VolumeMesh ring = VolumeMesh::from_tets(V, split_into_tets(fine).T);
  ring.point_data = fine.point_data;
  for (int t = 0; t < ring.num_cells(); ++t) {  // the patient itself is valid
    const auto c = ring.C.row(t);
    const Eigen::Vector3d a = V.row(c(0)), b = V.row(c(1)), d = V.row(c(2)), e = V.row(c(3));
    ASSERT_GT((b - a).dot((d - a).cross(e - a)), 0) << t;
  }
  write_volume_mesh(path("ring.vtu"), ring);
  write("ring.json", to_json(side_constraints()));

  int exit_three = 0;
  for (const std::string method : {"mesh-matching", "harmonic"}) {
    const Result r = run("map --method " + method + " --patient " + path("ring.vtu") + " --standard " +
                         path("std.vtu") + " -o " + path(method + ".vtu"));
    ASSERT_TRUE(r.status == 0 || r.status == 3) << method << ": " << r.output;
    ASSERT_TRUE(fs::exists(path(method + ".vtu"))) << r.output;
    const VolumeMesh hex = read_volume_mesh(path(method + ".vtu"));
    const QualitySummary q = summarize(hex, element_quality(hex));
    EXPECT_EQ(r.status, q.inverted + q.degenerate > 0 ? 3 : 0) << method << ": " << r.output;
    exit_three += r.status == 3;
  }
  EXPECT_EQ(exit_three, 1);  // the baseline's folds; the harmonic transfer's result is whole
}

// A finished run's report is written last and lists every output with its size and SHA-256; a second run into the
// same folder removes the exports of the first that it does not make, so the folder holds one run only.
TEST_F(Cli, RunWritesItsReportLastWithEveryOutputAndRemovesStaleExports) {
  write_tiny_models(dir_);
  const std::string args = "run " + path("box.vtu") + " --standard " + path("std.vtu") + " -o " + path("out");
  Result r = run(args + " --export inp,feb");
  ASSERT_EQ(r.status, 0) << r.output;
  nlohmann::json report;
  std::ifstream(path("out/report.json")) >> report;
  const auto& outputs = report["outputs"];
  EXPECT_TRUE(outputs["complete"].get<bool>());
  std::set<std::string> names;
  for (const auto& f : outputs["files"]) {
    const std::string name = f["name"];
    names.insert(name);
    EXPECT_EQ(f["bytes"].get<uintmax_t>(), fs::file_size(path("out/" + name))) << name;
    const Result sum = run_shell("sha256sum " + path("out/" + name));
    EXPECT_EQ(sum.output.substr(0, 64), f["sha256"].get<std::string>()) << name;
  }
  EXPECT_EQ(names, (std::set<std::string>{"patient_model.vtu", "standard_hex.vtu", "patient_hex.vtu", "patient_hex.inp",
                                          "patient_hex.feb"}));

  r = run(args);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("removed " + path("out/patient_hex.inp") + " of an earlier run"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(path("out/patient_hex.inp")));
  EXPECT_FALSE(fs::exists(path("out/patient_hex.feb")));
  std::ifstream(path("out/report.json")) >> report;
  EXPECT_EQ(report["outputs"]["files"].size(), 3u);
}

// map writes its mesh and its report, or neither: a report that cannot be written takes the mesh back.
TEST_F(Cli, MapLeavesNoMeshWhenItsReportCannotBeWritten) {
  write_tiny_models(dir_);
  for (const std::string method : {"harmonic", "mesh-matching"}) {
    const Result r = run("map --method " + method + " --patient " + path("box.vtu") + " --standard " + path("std.vtu") +
                         " -o " + path("hex.vtu") + " --report " + path("missing/folder/r.json"));
    EXPECT_EQ(r.status, 1) << method << ": " << r.output;
    EXPECT_NE(r.output.find("missing/folder/r.json"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("hex.vtu"))) << method;
  }
}

// A patient whose constraints cannot be placed (no side labels, no file): one line naming the model and the option of
// the command that takes its constraint set, and no output.
TEST_F(Cli, APatientWithoutConstraintsNamesTheOptionThatGivesThem) {
  const std::string tets = std::string(FACEHEX_TEST_DATA_DIR) + "/io/tets1.node";
  Result r = run("map --patient " + tets + " -o " + path("hex.vtu"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("error: " + tets + ": "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--patient-constraints"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("hex.vtu")));
  r = run("run " + tets + " -o " + path("out"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("with --constraints"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("out")));
}

TEST_F(Cli, CompareAndMapRejectBadInputsWithOneLineErrors) {
  write_tiny_models(dir_);
  Result r = run("compare " + path("missing.vtu") + " -o " + path("out"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("missing.vtu: no such patient file"), std::string::npos) << r.output;
  EXPECT_EQ(nonempty_lines(r.output), 1) << r.output;
  EXPECT_FALSE(fs::exists(path("out")));

  write("file.txt", "not a folder");
  r = run("compare " + path("box.vtu") + " --standard " + path("std.vtu") + " -o " + path("file.txt/out"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("file.txt/out: cannot create the output folder"), std::string::npos) << r.output;
  EXPECT_EQ(nonempty_lines(r.output), 1) << r.output;

  r = run("map --method elastic --patient " + path("box.vtu") + " -o " + path("m.vtu"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--method: expects harmonic or mesh-matching"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("m.vtu")));

  for (const char* value : {"2", "-0.1"}) {
    r = run("map --shape-relaxation " + std::string(value) + " --patient " + path("box.vtu") + " -o " + path("m.vtu"));
    EXPECT_NE(r.status, 0) << value;
    EXPECT_NE(r.output.find("--shape-relaxation: expects off or a fraction from 0 to 1"), std::string::npos)
        << r.output;
    EXPECT_EQ(nonempty_lines(r.output), 1) << r.output;
    EXPECT_FALSE(fs::exists(path("m.vtu")));
  }
  for (const char* value : {"-1", "heavy"}) {
    r = run("map --shape-tether " + std::string(value) + " --patient " + path("box.vtu") + " -o " + path("m.vtu"));
    EXPECT_EQ(r.status, 2) << value;
    EXPECT_NE(r.output.find("--shape-tether expects a number"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("m.vtu")));
  }
  r = run("run " + path("box.vtu") + " --shape-relaxation 2 -o " + path("run_out"));
  EXPECT_NE(r.status, 0);
  EXPECT_FALSE(fs::exists(path("run_out")));  // not even an empty folder
  r = run("run " + path("box.vtu") + " --skin-correspondence dense -o " + path("run_out"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--skin-correspondence: expects registered or features, got 'dense'"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(path("run_out")));
}

TEST_F(Cli, BenchTimesTheStagesOfAGivenPatient) {
  write_tiny_models(dir_);  // box.json beside box.vtu is its constraint set
  Result r = run("bench --patient " + path("box.vtu") + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json results = nlohmann::json::parse(r.output.substr(r.output.find('[')));
  ASSERT_EQ(results.size(), 1u);
  const nlohmann::json& b = results[0];
  EXPECT_EQ(b["patient"], path("box.vtu"));
  EXPECT_EQ(b["tets"].get<int>(), 6 * 3 * 8 * 6);  // the 6 x 3 x 8 hex box, 6 tets per hex
  double sum = 0;
  for (const char* stage : {"mesh_check", "constraints", "laplacian_assembly", "factorization", "harmonic_solves",
                            "locator_build", "point_location_and_interpolation", "orthogonality_iteration_6"}) {
    ASSERT_TRUE(b["stages"].contains(stage)) << stage;
    sum += b["stages"][stage].get<double>();
  }
  EXPECT_GT(sum, 0.0);
  EXPECT_LE(sum, b["total_seconds"].get<double>() + 1e-9);

  // The field options apply, as in run: two orthogonality iterations timed, not six.
  r = run("bench --patient " + path("box.vtu") + " --iterations 2 --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json two = nlohmann::json::parse(r.output.substr(r.output.find('[')))[0]["stages"];
  EXPECT_TRUE(two.contains("orthogonality_iteration_2"));
  EXPECT_FALSE(two.contains("orthogonality_iteration_3"));
  r = run("bench --patient " + path("box.vtu") + " --standard-domain cubes");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--standard-domain: expects closed or auxiliary"), std::string::npos) << r.output;

  r = run("bench --patient " + path("missing.vtu"));
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("missing.vtu: no such patient file or DICOM folder"), std::string::npos) << r.output;
}

TEST_F(Cli, AFailedRunOrTemplateRemovesTheFoldersItCreatedAndKeepsAnExistingOne) {
  write("bad.vtu", "not a VTK file");
  for (const std::string command : {"run", "template"}) {
    Result r = run(command + " " + path("bad.vtu") + " -o " + path("new/nested/out"));
    EXPECT_NE(r.status, 0) << command;
    EXPECT_NE(r.output.find("bad.vtu: reading VTK XML failed"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("new"))) << command;  // the outermost folder it created, not only the last

    fs::create_directories(path("existing"));
    write("existing/earlier.txt", "a user's file");
    r = run(command + " " + path("bad.vtu") + " -o " + path("existing"));
    EXPECT_NE(r.status, 0) << command;
    EXPECT_TRUE(fs::exists(path("existing/earlier.txt"))) << command;
  }
}

// The options an error names, each "--word" in it.
std::set<std::string> options_named(const std::string& text) {
  std::set<std::string> options;
  for (size_t at = text.find("--"); at != std::string::npos; at = text.find("--", at + 2)) {
    size_t end = at + 2;
    while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '-')) ++end;
    options.insert(text.substr(at, end - at));
  }
  return options;
}

// README: "1 error (one line on stderr naming the file or stage)". A run on what is no head says so, and every option
// its error suggests is one `run` has.
TEST_F(Cli, ErrorsExitOneWithOneLineAndSuggestOnlyOptionsThatExist) {
  write("garbage.vtu", "this is not a mesh");
  write("garbage.mha",
        "ObjectType = Image\nNDims = 3\nDimSize = 4 4 4\nElementType = MET_SHORT\n"
        "ElementDataFile = LOCAL\ntoo short");
  facehex::CtVolume box;  // a tall box of soft tissue around a bone core: no face
  facehex::GridGeometry& g = box.intensity.geometry;
  g.dims = {34, 40, 64};
  g.spacing = Eigen::Vector3d::Constant(4.0);
  box.intensity.data.assign(g.size(), -1000.0f);
  for (int k = 2; k < 62; ++k)
    for (int j = 2; j < 38; ++j)
      for (int i = 2; i < 32; ++i) box.intensity(i, j, k) = (i > 12 && i < 22 && j > 12 && j < 28) ? 1500.0f : 40.0f;
  facehex::write_ct_volume(path("box.mha"), box);
  facehex::CtVolume cheeks = facehex::read_ct_volume(facehex::default_ct());  // a scan that ends across the cheeks
  cheeks.intensity = facehex::crop(cheeks.intensity, {13, 0, 0}, {51, 64, 93});
  facehex::write_ct_volume(path("cheeks.mha"), cheeks);
  const std::string help = run("run --help").output;
  for (const auto& [args, file] : std::vector<std::pair<std::string, std::string>>{
           {"info " + path("garbage.vtu"), path("garbage.vtu")},
           {"convert " + path("garbage.vtu") + " " + path("out.vtu"), path("garbage.vtu")},
           {"segment " + path("garbage.mha") + " -o " + path("out.vtu"), path("garbage.mha")},
           {"run " + path("box.mha") + " -o " + path("out"), "not a plausible head"},
           {"run " + path("cheeks.mha") + " -o " + path("out"), "the scan ends across the head"}}) {
    const Result r = run_shell("(" + std::string(FACEHEX_CLI) + " " + args + " 2>&1 1>/dev/null)");  // stderr only
    EXPECT_EQ(r.status, 1) << args << ": " << r.output;
    // Progress lines may come first; the error is the last line, and the only one.
    const size_t at = r.output.find("error: ");
    ASSERT_NE(at, std::string::npos) << args << ": " << r.output;
    const std::string error = r.output.substr(at);
    EXPECT_EQ(nonempty_lines(error), 1) << args << ": " << r.output;
    EXPECT_EQ(r.output.find("\nerror: ", at), std::string::npos) << args << ": " << r.output;
    EXPECT_NE(error.find(file), std::string::npos) << args << ": " << r.output;
    if (args.rfind("run ", 0) == 0) {
      for (const std::string& option : options_named(error))
        EXPECT_NE(help.find(option + " "), std::string::npos) << option << " suggested by: " << error;
    }
  }
  EXPECT_FALSE(fs::exists(path("out.vtu")));
  EXPECT_FALSE(fs::exists(path("out")));
}

// README: "Every command has --help": it prints the command's usage and exits 0, as --help of the tool does.
TEST_F(Cli, EveryCommandHasHelp) {
  const std::string commands = run("--help").output;
  int listed = 0;
  for (const char* command : {"info", "convert", "sides", "fields", "map", "quality", "run", "standards", "template",
                              "segment", "constraints", "bench", "compare"}) {
    listed += commands.find(std::string("  ") + command + " ") != std::string::npos;
    const Result r = run(std::string(command) + " --help");
    EXPECT_EQ(r.status, 0) << command << ": " << r.output;
    EXPECT_EQ(r.output.rfind(std::string("usage: facehex ") + command, 0), 0u) << command << ": " << r.output;
  }
  EXPECT_EQ(listed, 13) << commands;
}

// An output that cannot be written is refused before the work starts (segmenting the bundled CT takes a while).
TEST_F(Cli, OutputsAreCheckedBeforeTheWork) {
  write("file.txt", "not a folder");
  const std::string tets = std::string(FACEHEX_TEST_DATA_DIR) + "/io/tets1.node", out = path("file.txt/out");
  for (const std::string& args :
       {"segment " + facehex::default_ct() + " -o " + out + ".vtu", "convert " + tets + " " + out + ".vtu",
        "fields " + tets + " -o " + out + ".vtu", "constraints " + tets + " -o " + out + ".json",
        "sides " + tets + " -o " + out + ".vtu", "map --patient " + tets + " -o " + out + ".vtu",
        "segment " + facehex::default_ct() + " -o " + path("m.vtu") + " --write-landmarks " + out + ".json"}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 1) << args << ": " << r.output;
    EXPECT_NE(r.output.find("error: " + out), std::string::npos) << args << ": " << r.output;
    EXPECT_EQ(r.output.find("segmentation:"), std::string::npos) << args << ": " << r.output;
  }
  // A mesh name without a format is refused before the work too, naming the formats.
  const std::string no_format = path("model");
  for (const std::string& args :
       {"segment " + facehex::default_ct() + " -o " + no_format, "convert " + tets + " " + no_format,
        "fields " + tets + " -o " + no_format, "sides " + tets + " -o " + no_format,
        "map --patient " + tets + " -o " + no_format + ".txt"}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 1) << args << ": " << r.output;
    EXPECT_NE(r.output.find("cannot write volume meshes as"), std::string::npos) << args << ": " << r.output;
    EXPECT_NE(r.output.find(".vtu, .vtk"), std::string::npos) << args << ": " << r.output;
    EXPECT_EQ(r.output.find("segmentation:"), std::string::npos) << args << ": " << r.output;
  }
}

// A mesh with an inverted and a flat tet reads, and info says so.
TEST_F(Cli, InfoReportsInvertedAndFlatCells) {
  write("bad.node", "5 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n4 1 1 1e-9\n");
  write("bad.ele", "3 4 0\n0 0 1 2 3\n1 1 0 2 3\n2 0 1 2 4\n");  // sound, inverted, flat (height 1e-9)
  Result r = run("info " + path("bad.node"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("inverted cells 1, flat cells 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("warning: " + path("bad.node")), std::string::npos) << r.output;
  r = run("info " + std::string(FACEHEX_TEST_DATA_DIR) + "/io/tets1.node");
  EXPECT_NE(r.output.find("inverted cells 0, flat cells 0"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
}

}  // namespace
