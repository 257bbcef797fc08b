// The error measurement: known answers for the summary, the per-region split, and the bundled standard's regions.
#include "core/evaluation/correspondence_error.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mesh/sides.h"
#include "core/util/resources.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

TEST(CorrespondenceError, SummaryOfOneToTwenty) {
  Eigen::VectorXd e(20);
  for (int i = 0; i < 20; ++i) e(i) = 20 - i;  // unsorted on purpose
  const ErrorSummary s = summarize_errors(e);
  EXPECT_EQ(s.count, 20);
  EXPECT_DOUBLE_EQ(s.mean, 10.5);
  EXPECT_DOUBLE_EQ(s.p95, 19);  // rank ceil(0.95 * 20) = 19
  EXPECT_DOUBLE_EQ(s.max, 20);
  EXPECT_DOUBLE_EQ(s.within_1mm, 0.05);  // 1 mm itself counts as within
  EXPECT_EQ(summarize_errors(Eigen::VectorXd()).count, 0);
}

TEST(CorrespondenceError, VertexErrorsAndRegions) {
  Eigen::MatrixXd truth = Eigen::MatrixXd::Zero(4, 3), mapped = truth;
  mapped.row(1) << 3, 4, 0;   // 5 mm
  mapped.row(3) << 0, 0, -2;  // 2 mm
  const Eigen::VectorXd e = vertex_errors(mapped, truth);
  EXPECT_DOUBLE_EQ(e(1), 5);
  EXPECT_DOUBLE_EQ(e(3), 2);
  const CorrespondenceError c = correspondence_error(e, {{"odd", {1, 3}}, {"even", {0, 2}}, {"none", {}}});
  EXPECT_DOUBLE_EQ(c.all.mean, 7.0 / 4);
  ASSERT_EQ(c.regions.size(), 3u);
  EXPECT_EQ(c.regions[0].name, "odd");
  EXPECT_DOUBLE_EQ(c.regions[0].error.mean, 3.5);
  EXPECT_DOUBLE_EQ(c.regions[0].error.max, 5);
  EXPECT_DOUBLE_EQ(c.regions[1].error.max, 0);
  EXPECT_DOUBLE_EQ(c.regions[1].error.within_1mm, 1);
  EXPECT_EQ(c.regions[2].error.count, 0);
}

TEST(CorrespondenceError, SkinErrorsSplitAcrossAndAlongTheTrueSkin) {
  // hex_box's skin is its y = sy face, normal +y: a shift (0.3, -1.2, 0.4) is 1.2 across it and 0.5 along it, whatever
  // the shift does elsewhere; a shift within the face is along it only.
  const VolumeMesh box = test::hex_box(3, 2, 4, 30, 20, 40);
  Eigen::MatrixXd shifted = box.V;
  shifted.rowwise() += Eigen::RowVector3d(0.3, -1.2, 0.4);
  SkinErrorSplit split = skin_error_split(box, shifted, box.V);
  EXPECT_NEAR(split.across, 1.2, 1e-12);
  EXPECT_NEAR(split.along, 0.5, 1e-12);
  shifted = box.V;
  shifted.col(2).array() += 2.0;
  split = skin_error_split(box, shifted, box.V);
  EXPECT_NEAR(split.across, 0, 1e-12);
  EXPECT_NEAR(split.along, 2, 1e-12);
}

TEST(CorrespondenceError, TheBundledStandardsRegions) {
  const VolumeMesh standard = read_volume_mesh(find_standard("artisynth-refface").mesh);
  const Eigen::VectorXi mask = side_mask_of(standard);
  const std::vector<VertexRegion> regions = correspondence_regions(standard);
  std::map<std::string, const VertexRegion*> by_name;
  for (const VertexRegion& r : regions) by_name[r.name] = &r;
  for (const char* name : {"skin", "bone", "landmarks", "inner face", "rim: eye at -x", "rim: eye at +x", "rim: mouth"})
    ASSERT_TRUE(by_name.count(name)) << name;
  // The inner face keeps kInnerFaceDepth from every cut side's vertex, and holds the eyes and the mouth (but for a few
  // vertices of their rims' deep ends, near the jaw's and the top cut).
  const int cut_sides = side_bit(U0) | side_bit(U1) | side_bit(V0) | side_bit(V1);
  std::set<int> inner(by_name["inner face"]->vertices.begin(), by_name["inner face"]->vertices.end());
  for (int c = 0; c < standard.num_vertices(); ++c) {
    if (!(mask(c) & cut_sides)) continue;
    for (const int v : inner) ASSERT_GE((standard.V.row(v) - standard.V.row(c)).norm(), kInnerFaceDepth);
  }
  for (const char* name : {"rim: eye at -x", "rim: eye at +x", "rim: mouth"}) {
    const std::vector<int>& rim = by_name[name]->vertices;
    const auto held = std::count_if(rim.begin(), rim.end(), [&](int v) { return inner.count(v) > 0; });
    EXPECT_GE(static_cast<double>(held), 0.9 * static_cast<double>(rim.size())) << name;
  }
  EXPECT_GT(inner.size(), standard.num_vertices() / 2u);
  EXPECT_LT(inner.size(), static_cast<size_t>(standard.num_vertices()));
  for (const int v : by_name["skin"]->vertices) EXPECT_TRUE(mask(v) & side_bit(W1));
  for (const int v : by_name["landmarks"]->vertices) EXPECT_TRUE(mask(v) & side_bit(W1));
  EXPECT_GE(by_name["landmarks"]->vertices.size(), 7u);  // at least one vertex at each landmark
  // The eyes lie on either side of the mid-plane, symmetric to a few mm.
  const auto centre = [&](const char* name) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const int v : by_name[name]->vertices) c += standard.V.row(v).transpose();
    return Eigen::Vector3d(c / static_cast<double>(by_name[name]->vertices.size()));
  };
  const Eigen::Vector3d left = centre("rim: eye at -x"), right = centre("rim: eye at +x");
  EXPECT_LT(left.x(), right.x());
  EXPECT_NEAR(left.z(), right.z(), 5.0);
  EXPECT_LT(centre("rim: mouth").z(), left.z() - 40);
}

}  // namespace
}  // namespace facehex
