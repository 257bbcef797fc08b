// The sets, surfaces and frames every FE export shares (fe_sets.h), and the refusal of inverted meshes.
#include <gtest/gtest.h>

#include "core/io/fe_sets.h"
#include "core/io/mesh_io.h"
#include "core/mesh/cell_faces.h"
#include "export_test_meshes.h"
#include "io_test_util.h"

namespace facehex {
namespace {

TEST(FeSets, SideNodesAndFacesOfABox) {
  const VolumeMesh m = test::hex_box(3, 2, 4, 3, 2, 4);
  const SideSets sets = side_sets(m);
  ASSERT_TRUE(sets.present);
  // hex_box: x -> u, y -> w, z -> v; a side's nodes are a grid, its faces the cells touching it.
  EXPECT_EQ(sets.nodes[U0].size(), 3u * 5u);
  EXPECT_EQ(sets.faces[U0].size(), 2u * 4u);
  EXPECT_EQ(sets.nodes[W1].size(), 4u * 5u);
  EXPECT_EQ(sets.faces[W1].size(), 3u * 4u);
  EXPECT_EQ(sets.faces[V0].size(), 3u * 2u);
  for (int s = 0; s < kNumSides; ++s)
    for (const CellFace& cf : sets.faces[s])
      for (int v : face_vertices(m, cf.cell, cf.face)) {
        EXPECT_TRUE(std::binary_search(sets.nodes[s].begin(), sets.nodes[s].end(), v)) << kSideSetNames[s];
      }
}

TEST(FeSets, FaceTouchingASideWithAnEdgeIsNotOnIt) {
  // One hex with only its bottom edge (nodes 0 and 1) on the skin: no face has all vertices there.
  VolumeMesh m = test::hex_box(1, 1, 1);
  m.point_data[kSideMaskArray].setZero();
  m.point_data[kSideMaskArray](0) = m.point_data[kSideMaskArray](1) = side_bit(W1);
  const SideSets sets = side_sets(m);
  EXPECT_EQ(sets.nodes[W1], (std::vector<int>{0, 1}));
  EXPECT_TRUE(sets.faces[W1].empty());
}

TEST(FeSets, MeshWithoutSideMaskHasNoSets) {
  VolumeMesh m = test::hex_box(1, 1, 1);
  m.point_data.clear();
  EXPECT_FALSE(side_sets(m).present);
  EXPECT_FALSE(export_frames(m));
}

TEST(FeSets, FramesComeFromUvwOrFromStoredArrays) {
  VolumeMesh m = test::hex_wedge_slab();
  const auto frames = export_frames(m);
  ASSERT_TRUE(frames);
  for (int c = 0; c < m.num_cells(); ++c) {
    EXPECT_LT((frames->e1.row(c) - Eigen::RowVector3d(-1, 0, 0)).norm(), 1e-12) << c;
    EXPECT_LT((frames->e3.row(c) - Eigen::RowVector3d(0, 1, 0)).norm(), 1e-12) << c;
  }
  attach_fe_arrays(m);
  m.point_data.erase("uvw");
  m.cell_data["frame_e1"](0, 0) = 0.5;  // stored arrays win over the (now absent) uvw
  EXPECT_EQ(export_frames(m)->e1(0, 0), 0.5);
}

TEST(FeSets, AttachesSetsAsArrays) {
  VolumeMesh m = test::hex_wedge_slab();
  attach_fe_arrays(m);
  const SideSets sets = side_sets(m);
  EXPECT_EQ(m.point_data.at("nset_SKIN").sum(), static_cast<double>(sets.nodes[W1].size()));
  int faces = 0;
  for (int c = 0; c < m.num_cells(); ++c) faces += __builtin_popcount(static_cast<int>(m.cell_data.at("surf_BONE")(c)));
  EXPECT_EQ(faces, static_cast<int>(sets.faces[W0].size()));
  EXPECT_EQ(m.cell_data.at("frame_e2").rows(), m.num_cells());
}

TEST(FeExport, InvertedMeshIsRefusedWithItsElementIdsUnlessForced) {
  test::TempDir dir;
  VolumeMesh m = test::hex_wedge_slab();
  m.V.row(m.C(4, 6)) += Eigen::RowVector3d(0, 0, -30);  // pulls a top node of cell 4 through its bottom
  for (const std::string ext : {".inp", ".feb"}) {
    const std::string path = dir.file("bad" + ext);
    test::expect_error([&] { write_volume_mesh(path, m); }, "element ids 5");
    test::expect_error([&] { write_volume_mesh(path, m); }, "are inverted");
    EXPECT_FALSE(std::filesystem::exists(path)) << "nothing written";
    MeshWriteOptions force;
    force.allow_inverted = true;
    write_volume_mesh(path, m, force);
    EXPECT_TRUE(std::filesystem::exists(path));
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"bad.feb", "bad.inp"})) << "no temporary files left";
  write_volume_mesh(dir.file("bad.vtu"), m);  // data formats keep bad meshes inspectable
}

}  // namespace
}  // namespace facehex
