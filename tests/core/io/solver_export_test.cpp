// The exports in real FE tools: CalculiX (ccx, reads Abaqus input) solves the exported .inp models, and Gmsh reads
// the exported .msh with its physical groups. Skipped when ccx / gmsh are not on PATH (scripts/install-deps.sh
// installs them). Units mm, N, MPa.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/fields/constraint_set.h"
#include "core/io/fe_sets.h"
#include "core/io/mesh_io.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/hex_to_tets.h"
#include "export_test_meshes.h"
#include "io_test_util.h"

namespace facehex {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

constexpr double kPressure = 0.001;  // MPa = 1 kPa, on soft tissue of E = 15 kPa (the placeholder material)

struct CcxResult {
  std::string log, dat;
};

// Writes job.inp = the model + one static step, runs ccx in `dir`; fails the test on a non-zero exit or "*ERROR".
CcxResult run_ccx(const TempDir& dir, const std::string& step) {
  test::write_file(dir.file("job.inp"),
                   "*INCLUDE, INPUT=" + dir.file("model.inp") + "\n*STEP\n*STATIC\n" + step + "*END STEP\n");
  const std::string command = "cd " + dir.path().string() + " && ccx -i job > job.log 2>&1";
  const bool ok = std::system(command.c_str()) == 0;
  CcxResult r{test::read_file(dir.file("job.log")), test::read_file(dir.file("job.dat"))};
  EXPECT_TRUE(ok) << r.log.substr(r.log.size() > 3000 ? r.log.size() - 3000 : 0);
  EXPECT_EQ(r.log.find("*ERROR"), std::string::npos) << r.log;
  EXPECT_NE(r.log.find("Job finished"), std::string::npos) << r.log;
  return r;
}

// The rows under a .dat block header ("displacements (vx,vy,vz) for set SKIN", "total force (fx,fy,fz) for set X"):
// node id (0 for totals) -> vector.
std::map<int, Eigen::Vector3d> dat_block(const std::string& dat, const std::string& header) {
  std::map<int, Eigen::Vector3d> rows;
  const size_t at = dat.find(header);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no '" << header << "' in the .dat file";
    return rows;
  }
  std::istringstream in(dat.substr(dat.find('\n', at) + 1));
  std::string line;
  std::getline(in, line);  // blank
  while (std::getline(in, line) && line.find_first_not_of(' ') != std::string::npos) {
    std::istringstream fields(line);
    std::vector<double> v;
    for (double x; fields >> x;) v.push_back(x);
    if (v.size() == 3) v.insert(v.begin(), 0);
    if (v.size() == 4) rows[static_cast<int>(v[0])] = Eigen::Vector3d(v[1], v[2], v[3]);
  }
  return rows;
}

class CalculiX : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::on_path("ccx")) GTEST_SKIP() << "ccx not found (Debian package calculix-ccx)";
  }
};

TEST_F(CalculiX, EverySideSurfaceCarriesItsPressure) {
  // Each side loaded in turn with the opposite side fixed: the reaction there balances the pressure, p * area * the
  // side's outward normal. A wrong Abaqus face number would load another (or an inner) face and change the total;
  // the slab has every face number of C3D8 and C3D6 on its sides.
  TempDir dir;
  const VolumeMesh m = test::hex_wedge_slab();
  write_volume_mesh(dir.file("model.inp"), m);
  const Eigen::Vector3d size(12, 5, 9);
  const std::array<int, kNumSides> axis = {0, 0, 2, 2, 1, 1};  // u: x, v: z, w: y
  for (int s = 0; s < kNumSides; ++s) {
    const char* opposite = kSideSetNames[s ^ 1];
    const CcxResult r = run_ccx(dir, std::string("*BOUNDARY\n") + opposite + ", 1, 3\n*DSLOAD\n" + kSideSetNames[s] +
                                         kSurfaceSuffix + ", P, " + std::to_string(kPressure) +
                                         "\n*NODE PRINT, NSET=" + opposite + ", TOTALS=ONLY\nRF\n");
    const auto total = dat_block(r.dat, std::string("total force (fx,fy,fz) for set ") + opposite);
    ASSERT_EQ(total.size(), 1u) << kSideSetNames[s];
    Eigen::Vector3d expected = Eigen::Vector3d::Zero();
    expected(axis[s]) = (s % 2 ? 1 : -1) * kPressure * size.prod() / size(axis[s]);
    EXPECT_LT((total.at(0) - expected).norm(), 1e-6 * expected.norm())
        << kSideSetNames[s] << ": " << total.at(0).transpose();
  }
}

TEST_F(CalculiX, SoftTissueSlabUnderSkinPressure) {
  // Bone fixed, 1 kPa on the skin: the skin moves towards the bone by between the confined (p t / M, M the P-wave
  // modulus, 0.088 mm) and the unconfined (p t / E, 0.33 mm) compression of the 5 mm layer.
  TempDir dir;
  write_volume_mesh(dir.file("model.inp"), test::hex_wedge_slab());
  const CcxResult r = run_ccx(dir, "*BOUNDARY\nBONE, 1, 3\n*DSLOAD\nSKIN_SURF, P, " + std::to_string(kPressure) +
                                       "\n*NODE PRINT, NSET=SKIN\nU\n*NODE FILE\nU\n");
  const auto u = dat_block(r.dat, "displacements (vx,vy,vz) for set SKIN");
  ASSERT_EQ(u.size(), 4u * 4u);
  double mean_depth = 0;
  for (const auto& [node, d] : u) {
    ASSERT_TRUE(d.allFinite()) << node;
    EXPECT_LT(d.norm(), 1.0) << node;
    mean_depth += d.y() / u.size();
  }
  EXPECT_LT(mean_depth, -0.088 * 0.9);
  EXPECT_GT(mean_depth, -0.33 * 1.1);
  const std::string frd = test::read_file(dir.file("job.frd"));
  EXPECT_NE(frd.find("DISP"), std::string::npos);
  EXPECT_EQ(frd.find("nan"), std::string::npos);
  RecordProperty("mean_skin_displacement_mm", std::to_string(mean_depth));
}

TEST_F(CalculiX, UsesThePerElementMaterialFrame) {
  // Orthotropic tissue, 10x stiffer along one local axis; the slab's frame is e1 = -x, e2 = z (up), e3 = y (depth).
  // Stiff along e3 the 5 mm layer compresses by p t / E3; stiff along e1 or e2 it moves as soft tissue does. Were the
  // orientations ignored (local = global axes), the run stiff along local 2 = y would be the one that barely moves.
  const auto skin_depth_motion = [](const std::string& constants) {
    TempDir dir;
    write_volume_mesh(dir.file("model.inp"), test::hex_wedge_slab());
    std::string model = test::read_file(dir.file("model.inp"));
    const std::string placeholder = "*ELASTIC\n0.015, 0.45\n";
    EXPECT_NE(model.find(placeholder), std::string::npos);
    model.replace(model.find(placeholder), placeholder.size(), "*ELASTIC, TYPE=ENGINEERING CONSTANTS\n" + constants);
    test::write_file(dir.file("model.inp"), model);
    const CcxResult r = run_ccx(dir, "*BOUNDARY\nBONE, 1, 3\n*DSLOAD\nSKIN_SURF, P, " + std::to_string(kPressure) +
                                         "\n*NODE PRINT, NSET=SKIN\nU\n");
    double mean = 0;
    const auto u = dat_block(r.dat, "displacements (vx,vy,vz) for set SKIN");
    for (const auto& [node, d] : u) mean += d.y() / u.size();
    return mean;
  };
  // E1, E2, E3, nu12, nu13, nu23, G12, G13 / G23 (nu small enough for a positive definite stiffness)
  const double stiff_depth = skin_depth_motion("0.015, 0.015, 0.15, 0.1, 0.1, 0.1, 0.006, 0.006\n0.006\n");
  const double stiff_lateral = skin_depth_motion("0.15, 0.015, 0.015, 0.1, 0.1, 0.1, 0.006, 0.006\n0.006\n");
  const double stiff_up = skin_depth_motion("0.015, 0.15, 0.015, 0.1, 0.1, 0.1, 0.006, 0.006\n0.006\n");
  const double along_e3 = kPressure * 5 / 0.15;  // p t / E3: the 5 mm layer compressed along its stiff axis
  EXPECT_NEAR(stiff_depth, -along_e3, 0.2 * along_e3);
  EXPECT_LT(stiff_lateral, -5 * along_e3);
  EXPECT_LT(stiff_up, -5 * along_e3) << "e2 is up (z), not the depth";
  RecordProperty("skin_motion_mm_stiff_depth_lateral_up",
                 std::to_string(stiff_depth) + " " + std::to_string(stiff_lateral) + " " + std::to_string(stiff_up));
}

// A real facial mesh: the bundled standard, with "uvw" from its harmonic parameterization (on its auxiliary tets).
TEST_F(CalculiX, SolvesTheBundledFaceMesh) {
  const std::string folder = std::string(FACEHEX_RESOURCE_DIR) + "/standards/artisynth-refface";
  ASSERT_TRUE(fs::exists(folder + "/standard.vtu")) << "no bundled standard at " << folder;
  VolumeMesh face = read_volume_mesh(folder + "/standard.vtu");
  const ModelParameterization p =
      parameterize_model(face.V, split_into_tets(face).T, side_mask_of(face),
                         read_constraint_set(folder + "/constraints.json"), folder, HarmonicFieldsOptions{});
  face.point_data["uvw"] = p.fields.uvw;
  TempDir dir;
  write_volume_mesh(dir.file("model.inp"), face);
  const CcxResult r = run_ccx(dir, "*BOUNDARY\nBONE, 1, 3\n*DSLOAD\nSKIN_SURF, P, " + std::to_string(kPressure) +
                                       "\n*NODE PRINT, NSET=SKIN\nU\n");
  const auto u = dat_block(r.dat, "displacements (vx,vy,vz) for set SKIN");
  ASSERT_EQ(u.size(), side_sets(face).nodes[W1].size());
  double largest = 0;
  for (const auto& [node, d] : u) {
    ASSERT_TRUE(d.allFinite()) << node;
    largest = std::max(largest, d.norm());
  }
  EXPECT_GT(largest, 0.01);  // mm; the soft tissue is 5 to 20 mm thick
  EXPECT_LT(largest, 5.0);
  RecordProperty("largest_skin_displacement_mm", std::to_string(largest));
}

// The demo patient of `facehex run`: the whole chain from the bundled CT, exported and solved.
TEST_F(CalculiX, SolvesTheDemoPatientHexMesh) {
  if (!fs::exists(FACEHEX_CLI)) GTEST_SKIP() << "facehex CLI not built";
  TempDir dir;
  ASSERT_TRUE(test::run_quietly(std::string(FACEHEX_CLI) + " run -o " + dir.file("run") + " --export inp"));
  fs::copy_file(dir.file("run/patient_hex.inp"), dir.file("model.inp"));
  const CcxResult r = run_ccx(dir, "*BOUNDARY\nBONE, 1, 3\n*DSLOAD\nSKIN_SURF, P, " + std::to_string(kPressure) +
                                       "\n*NODE PRINT, NSET=SKIN\nU\n");
  // Sane for 1 kPa on E = 15 kPa tissue: every node moves, finitely; the typical skin node by about p/E times the
  // tissue's thickness (5-30 mm), and no node by more than that thickness (the lips, free flaps over the mouth slit,
  // bend furthest, about 9 mm).
  std::vector<double> moved;
  for (const auto& [node, d] : dat_block(r.dat, "displacements (vx,vy,vz) for set SKIN")) {
    ASSERT_TRUE(d.allFinite()) << node;
    moved.push_back(d.norm());
  }
  ASSERT_GT(moved.size(), 1000u);
  std::sort(moved.begin(), moved.end());
  EXPECT_GT(moved.front(), 0.0);
  EXPECT_GT(moved[moved.size() / 2], 0.05);
  EXPECT_LT(moved[moved.size() / 2], 2.0);
  EXPECT_LT(moved.back(), 20.0);
  RecordProperty("median_skin_displacement_mm", std::to_string(moved[moved.size() / 2]));
  RecordProperty("largest_skin_displacement_mm", std::to_string(moved.back()));
}

// ---- Gmsh

// A Gmsh 2.2 file as written by Gmsh: physical names ("dim tag" -> name) and element counts per (type, physical).
struct Msh22 {
  std::map<std::string, std::string> names;
  std::map<std::pair<int, int>, int> counts;
};

Msh22 read_msh22(const std::string& path) {
  Msh22 r;
  std::istringstream in(test::read_file(path));
  std::string line;
  while (std::getline(in, line)) {
    if (line == "$PhysicalNames") {
      int n;
      in >> n;
      for (int i = 0; i < n; ++i) {
        int dim, tag;
        std::string name;
        in >> dim >> tag >> name;
        r.names[std::to_string(dim) + " " + std::to_string(tag)] = name.substr(1, name.size() - 2);
      }
    } else if (line == "$Elements") {
      int n;
      in >> n;
      std::getline(in, line);
      for (int i = 0; i < n && std::getline(in, line); ++i) {
        std::istringstream f(line);
        int id, type, tags, physical;
        f >> id >> type >> tags >> physical;
        ++r.counts[{type, physical}];
      }
    }
  }
  return r;
}

TEST(Gmsh, ReadsTheExportWithItsPhysicalGroups) {
  if (!test::on_path("gmsh")) GTEST_SKIP() << "gmsh not found (Debian package gmsh)";
  TempDir dir;
  const VolumeMesh m = test::hex_wedge_slab();
  write_volume_mesh(dir.file("slab.msh"), m);
  // Gmsh reads our 4.1 file and saves what it understood as 2.2, keeping only elements in physical groups.
  ASSERT_TRUE(test::run_quietly("gmsh " + dir.file("slab.msh") + " -save -format msh22 -o " + dir.file("gmsh.msh")));
  const Msh22 back = read_msh22(dir.file("gmsh.msh"));
  EXPECT_EQ(back.names.at("3 1"), "ALL");
  EXPECT_EQ(back.counts.at({5, 1}), m.count(CellType::Hex));    // hexahedra
  EXPECT_EQ(back.counts.at({6, 1}), m.count(CellType::Wedge));  // prisms
  const SideSets sets = side_sets(m);
  for (int s = 0; s < kNumSides; ++s) {
    EXPECT_EQ(back.names.at("2 " + std::to_string(s + 1)), std::string(kSideSetNames[s]) + kSurfaceSuffix);
    const int faces = (back.counts.count({2, s + 1}) ? back.counts.at({2, s + 1}) : 0) +
                      (back.counts.count({3, s + 1}) ? back.counts.at({3, s + 1}) : 0);
    EXPECT_EQ(faces, static_cast<int>(sets.faces[s].size())) << kSideSetNames[s];
  }
  // Our reader still takes the file (the surfaces are annotations), with the volume group as "gmsh_physical".
  const VolumeMesh ours = read_volume_mesh(dir.file("slab.msh"));
  EXPECT_EQ(ours.C, m.C);
  EXPECT_EQ(ours.cell_data.at("gmsh_physical"), Eigen::MatrixXd::Ones(m.num_cells(), 1));
}

}  // namespace
}  // namespace facehex
