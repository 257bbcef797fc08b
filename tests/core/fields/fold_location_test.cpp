#include "core/fields/fold_location.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

// A box of 6 x 6 x 12 unit cells split into tets, parameterized as the identity scaled to the unit cube (u along x,
// v along z, w along y), each field pinned on its two faces as a model's sides are.
struct BoxParameterization {
  VolumeMesh mesh = test::tet_box_without(6, 6, 12, 6, 6, 12, [](int, int, int) { return false; });
  const Eigen::MatrixXd& V = mesh.V;
  const Eigen::MatrixXi& T = mesh.C;
  Eigen::MatrixXd uvw;
  Eigen::MatrixXi fixed;

  BoxParameterization() {
    uvw.resize(V.rows(), 3);
    uvw << V.col(0) / 6, V.col(2) / 12, V.col(1) / 6;
    fixed = Eigen::MatrixXi::Zero(V.rows(), 3);
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      for (int f = 0; f < 3; ++f) fixed(v, f) = uvw(v, f) == 0 || uvw(v, f) == 1;
  }

  // The tets whose centroid lies in the slab lo <= z <= hi.
  std::vector<int> tets_between(double lo, double hi) const {
    std::vector<int> picked;
    for (Eigen::Index t = 0; t < T.rows(); ++t) {
      double z = 0;
      for (int i = 0; i < 4; ++i) z += V(T(t, i), 2) / 4;
      if (z >= lo && z <= hi) picked.push_back(static_cast<int>(t));
    }
    return picked;
  }
};

TEST(FoldLocation, FoldsUnderTheTopCutAreSaidToLieThereAndTheOptionIsNamed) {
  const BoxParameterization box;
  const std::vector<int> folded = box.tets_between(10, 11);  // in the second cell layer below the top (z = 12)
  const FoldLocation at = fold_location(box.mesh, box.uvw, box.fixed, folded, 4);
  EXPECT_EQ(at.folded, static_cast<int>(folded.size()));
  EXPECT_EQ(at.near_cut[3], at.folded);  // the top cut (v = 1)
  EXPECT_EQ(at.near_cut[2], 0);          // the bottom cut lies 10 cells away
  EXPECT_GT(at.near_cut[0], 0);          // the slab reaches the posterior cuts at its sides
  EXPECT_LT(at.near_cut[0], at.folded);
  const std::string text = fold_location_text(at);
  EXPECT_EQ(text,
            "; 100 % of the folded tets lie within 4 cells of the top cut (v = 1), which a CT's model is cut at "
            "elsewhere with --top-cut");
}

TEST(FoldLocation, RingsBoundTheReachAndFoldsAwayFromEveryCutNameNone) {
  const BoxParameterization box;
  // Five cells below the top: within 6 rings of it, not within 2.
  const std::vector<int> lower = box.tets_between(6.5, 7);
  EXPECT_EQ(fold_location(box.mesh, box.uvw, box.fixed, lower, 6).near_cut[3], static_cast<int>(lower.size()));
  EXPECT_EQ(fold_location(box.mesh, box.uvw, box.fixed, lower, 2).near_cut[3], 0);
  // The tets about the box's middle: their corners 2 cells or more from every cut, near none within 1 ring.
  std::vector<int> middle;
  for (Eigen::Index t = 0; t < box.T.rows(); ++t) {
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    for (int i = 0; i < 4; ++i) c += box.V.row(box.T(t, i)) / 4;
    if ((c - Eigen::RowVector3d(3, 3, 6)).norm() < 1.0) middle.push_back(static_cast<int>(t));
  }
  ASSERT_FALSE(middle.empty());
  const FoldLocation nowhere = fold_location(box.mesh, box.uvw, box.fixed, middle, 1);
  for (int cut = 0; cut < 4; ++cut) EXPECT_EQ(nowhere.near_cut[cut], 0) << cut;
  EXPECT_EQ(fold_location_text(nowhere), "");
  EXPECT_EQ(fold_location_text(fold_location(box.mesh, box.uvw, box.fixed, {}, 4)), "");
}

}  // namespace
}  // namespace facehex
