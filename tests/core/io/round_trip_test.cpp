// Writing a mesh and reading it back gives the same mesh: coordinates bit for bit, connectivity, cell types and
// (for the VTK formats) every data array.
#include "core/io/mesh_io.h"
#include "io_test_util.h"

#include <gtest/gtest.h>

namespace facehex {
namespace {

using test::TempDir;
namespace fs = std::filesystem;

void expect_same_geometry(const VolumeMesh& a, const VolumeMesh& b) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_cells(), b.num_cells());
  EXPECT_EQ((a.V - b.V).cwiseAbs().maxCoeff(), 0.0) << "coordinates must survive exactly";
  EXPECT_EQ(a.C, b.C);
  EXPECT_EQ(a.types, b.types);
}

void expect_same_arrays(const std::map<std::string, Eigen::MatrixXd>& a,
                        const std::map<std::string, Eigen::MatrixXd>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (const auto& [name, m] : a) {
    ASSERT_TRUE(b.count(name)) << name;
    ASSERT_EQ(m.rows(), b.at(name).rows()) << name;
    ASSERT_EQ(m.cols(), b.at(name).cols()) << name;
    EXPECT_EQ(m, b.at(name)) << name;
  }
}

TEST(SampleMesh, FollowsVtkConventions) {
  // The round trips below compare against this mesh: make sure it is what it claims to be.
  const VolumeMesh m = test::sample_mesh();
  EXPECT_GT(test::base_normal_towards_top(m, 0), 0);
  EXPECT_GT(test::base_normal_towards_top(m, 1), 0);
  EXPECT_LT(test::base_normal_towards_top(m, 2), 0);
  EXPECT_GT(test::signed_volume(m.V, m.C(3, 0), m.C(3, 1), m.C(3, 2), m.C(3, 3)), 0);
}

class VtkRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(VtkRoundTrip, VtkFormatsKeepGeometryAndAllDataArrays) {
  TempDir dir;
  VolumeMesh mesh = test::sample_mesh();
  // Field data: facts about the whole mesh, of any number of tuples (a segmented CT's mid-sagittal plane is one).
  mesh.field_data["mid_sagittal_plane"] = (Eigen::MatrixXd(1, 3) << 258.6262461290185, 0.0122, 80.5).finished();
  mesh.field_data["frame"] = (Eigen::MatrixXd(2, 3) << 1, 0, 0, 0, 0.5, -1.0 / 3).finished();
  const std::string path = dir.file("mesh" + GetParam());
  write_volume_mesh(path, mesh);
  const VolumeMesh back = read_volume_mesh(path);
  expect_same_geometry(mesh, back);
  expect_same_arrays(mesh.point_data, back.point_data);
  expect_same_arrays(mesh.cell_data, back.cell_data);
  expect_same_arrays(mesh.field_data, back.field_data);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"mesh" + GetParam()}) << "temporary file left behind";
}

TEST_P(VtkRoundTrip, SinglePrecisionArraysComeBackRoundedToFloatOthersExact) {
  TempDir dir;
  VolumeMesh mesh = test::sample_mesh();
  Eigen::MatrixXd gradients(mesh.num_cells(), 3);
  for (Eigen::Index i = 0; i < gradients.size(); ++i) gradients(i) = 1.0 / 3.0 + 1e-9 * static_cast<double>(i);
  mesh.cell_data["grad_u"] = gradients;
  const std::string path = dir.file("mesh" + GetParam());
  MeshWriteOptions options;
  options.single_precision_arrays = {"grad_u"};
  write_volume_mesh(path, mesh, options);
  VolumeMesh back = read_volume_mesh(path);
  expect_same_geometry(mesh, back);
  ASSERT_TRUE(back.cell_data.count("grad_u"));
  const Eigen::MatrixXd as_float = gradients.cast<float>().cast<double>();
  EXPECT_EQ(back.cell_data.at("grad_u"), as_float);
  EXPECT_NE(back.cell_data.at("grad_u"), gradients) << "the array was written as doubles";
  back.cell_data.erase("grad_u");
  mesh.cell_data.erase("grad_u");
  expect_same_arrays(mesh.point_data, back.point_data);
  expect_same_arrays(mesh.cell_data, back.cell_data);
}

INSTANTIATE_TEST_SUITE_P(Formats, VtkRoundTrip, ::testing::Values(".vtu", ".vtk", ".VTU"));

TEST(RoundTripGmsh, KeepsGeometryAndPhysicalTags) {
  TempDir dir;
  const VolumeMesh mesh = test::sample_mesh();
  const std::string path = dir.file("mesh.msh");
  write_volume_mesh(path, mesh);
  const VolumeMesh back = read_volume_mesh(path);
  expect_same_geometry(mesh, back);
  ASSERT_TRUE(back.cell_data.count("gmsh_physical"));
  EXPECT_EQ(back.cell_data.at("gmsh_physical"), mesh.cell_data.at("gmsh_physical"));
  EXPECT_EQ(test::read_file(path).rfind("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n", 0), 0u);
}

TEST(RoundTripGmsh, WritesPrismsInGmshOrder) {
  // Gmsh's prism has its bottom normal pointing towards the top triangle: the written prism must be positive in
  // that convention, i.e. the VTK wedge (4, 7, 5, 12, 14, 13) becomes "4 5 7 12 13 14" (1-based: 5 6 8 13 14 15).
  TempDir dir;
  const std::string path = dir.file("mesh.msh");
  write_volume_mesh(path, test::sample_mesh());
  const std::string text = test::read_file(path);
  EXPECT_NE(text.find("\n3 5 6 8 13 14 15\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n3 2 6 1\n"), std::string::npos) << "block header: volume entity 2, type 6, 1 element";
}

TEST(RoundTripGmsh, MeshWithoutPhysicalTagsReadsBackWithoutThem) {
  TempDir dir;
  VolumeMesh mesh = test::sample_mesh();
  mesh.cell_data.clear();
  const std::string path = dir.file("mesh.msh");
  write_volume_mesh(path, mesh);
  const VolumeMesh back = read_volume_mesh(path);
  expect_same_geometry(mesh, back);
  EXPECT_TRUE(back.cell_data.empty());
}

TEST(RoundTrip, TetMeshThroughAllWritableFormats) {
  TempDir dir;
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1;
  Eigen::MatrixXi T(2, 4);
  T << 0, 1, 2, 3, 1, 2, 3, 4;
  const VolumeMesh mesh = VolumeMesh::from_tets(V, T);
  for (const std::string& ext : writable_volume_extensions()) {
    const std::string path = dir.file("tets" + ext);
    write_volume_mesh(path, mesh);
    const VolumeMesh back = read_volume_mesh(path);
    expect_same_geometry(mesh, back);
    EXPECT_TRUE(back.is_tet_mesh()) << ext;
  }
}

TEST(WriteVolumeMesh, OverwritesAnExistingFile) {
  TempDir dir;
  const std::string path = dir.file("mesh.vtu");
  test::write_file(path, "old");
  write_volume_mesh(path, test::sample_mesh());
  EXPECT_EQ(read_volume_mesh(path).num_cells(), 4);
}

TEST(WriteVolumeMesh, UnknownExtensionIsAnErrorAndWritesNothing) {
  TempDir dir;
  test::expect_error([&] { write_volume_mesh(dir.file("mesh.stl"), test::sample_mesh()); }, "mesh.stl");
  test::expect_error([&] { write_volume_mesh(dir.file("mesh"), test::sample_mesh()); }, "cannot write volume meshes");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(WriteVolumeMesh, IntoMissingFolderIsAnError) {
  TempDir dir;
  for (const std::string& ext : writable_volume_extensions()) {
    test::expect_error([&] { write_volume_mesh(dir.file("missing/mesh" + ext), test::sample_mesh()); },
                       "does not exist");
  }
}

TEST(WriteVolumeMesh, InconsistentMeshIsRejectedBeforeWriting) {
  TempDir dir;
  VolumeMesh bad = test::sample_mesh();
  bad.C(1, 3) = 99;
  test::expect_error([&] { write_volume_mesh(dir.file("bad.vtu"), bad); }, "refers to point 99");
  VolumeMesh short_data = test::sample_mesh();
  short_data.point_data["temperature"].conservativeResize(3, 1);
  test::expect_error([&] { write_volume_mesh(dir.file("bad.msh"), short_data); }, "'temperature' has 3 rows");
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Extensions, ListsAreConsistent) {
  for (const std::string& ext : writable_volume_extensions()) {
    const auto readable = readable_volume_extensions();
    EXPECT_NE(std::find(readable.begin(), readable.end(), ext), readable.end()) << ext << " written but not read";
  }
  EXPECT_TRUE(is_surface_file("face.STL"));
  EXPECT_TRUE(is_surface_file("/a/b.vtp"));
  EXPECT_FALSE(is_surface_file("mesh.vtu"));
  EXPECT_FALSE(is_surface_file("stl"));
}

}  // namespace
}  // namespace facehex
