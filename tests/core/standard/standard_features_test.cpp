#include "core/standard/standard_features.h"

#include <gtest/gtest.h>

#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mesh/sides.h"
#include "core/util/resources.h"

namespace facehex {
namespace {

TEST(StandardFeatures, TheBundledStandardsOpeningsAndTheCornersOfItsEyesAndMouth) {
  const VolumeMesh standard = read_volume_mesh(default_standard().mesh);
  const StandardFeatures f = standard_features(standard);
  for (const char* rim : {"eye at -x", "eye at +x", "mouth", "nostril at -x"}) EXPECT_TRUE(f.rims.count(rim)) << rim;
  // Every profile landmark the finder found has its vertex, on the skin, within the skin's spacing of it.
  const Eigen::VectorXi mask = side_mask_of(standard);
  for (const auto& [name, p] : f.landmarks.points) {
    if (name.rfind("cheilion", 0) == 0) continue;  // the open mouth's rim gives its corners
    ASSERT_TRUE(f.landmark_vertices.count(name)) << name;
    EXPECT_LT((standard.V.row(f.landmark_vertices.at(name)).transpose() - p).norm(), 3.0) << name;
  }
  FaceLandmarks with_corners = f.landmarks;
  for (const char* corner : {"endocanthion right", "exocanthion right", "endocanthion left", "exocanthion left",
                             "cheilion right", "cheilion left"}) {
    ASSERT_TRUE(f.landmark_vertices.count(corner)) << corner;
    const int v = f.landmark_vertices.at(corner);
    EXPECT_TRUE(mask(v) & side_bit(W1)) << corner;
    with_corners.points[corner] = standard.V.row(v).transpose();
  }
  // The standard is mirror-symmetric about x = 0: so are its corners; the outer eye corners lie outside the inner,
  // and the whole set has adult proportions (eye and mouth widths, heights).
  const auto at = [&](const char* name) { return with_corners.points.at(name); };
  for (const auto& [right, left] :
       {std::pair{"endocanthion right", "endocanthion left"}, std::pair{"exocanthion right", "exocanthion left"},
        std::pair{"cheilion right", "cheilion left"}}) {
    EXPECT_NEAR(at(right).x(), -at(left).x(), 1e-6) << right;
    EXPECT_NEAR(at(right).z(), at(left).z(), 1e-6) << right;
  }
  EXPECT_LT(at("exocanthion right").x(), at("endocanthion right").x());
  EXPECT_NO_THROW(check_plausible(with_corners, ""));
}

}  // namespace
}  // namespace facehex
