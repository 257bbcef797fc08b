#include "core/segment/field_of_view.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace facehex {
namespace {

constexpr double kAll = std::numeric_limits<double>::infinity();

GridGeometry grid(int nx, int ny, int nz, const Eigen::Vector3d& origin) {
  GridGeometry g;
  g.dims = {nx, ny, nz};
  g.origin = origin;
  return g;
}

ScanSides sides(const GridGeometry& g) {
  return {{g.lower(0), g.lower(1)}, {g.upper(0), g.upper(1)}, std::nullopt, HeadTurn{}};
}

int count(const std::vector<FieldOfViewContact>& contacts, ScanEdge edge) {
  return static_cast<int>(
      std::count_if(contacts.begin(), contacts.end(), [edge](const FieldOfViewContact& c) { return c.edge == edge; }));
}

// A head on a grid that ends with the scan: its back rows fill the grid's width (the scan ends across the sides and
// the back), its front is narrower and ends in air before the grid does.
TEST(FieldOfView, AHeadCutByTheScansSidesAndBackTouchesThemAndNotItsFront) {
  const GridGeometry g = grid(20, 20, 4, Eigen::Vector3d::Zero());
  Mask body(g, 0);
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 17; ++j)
      for (int i = j < 10 ? 0 : 5; i < (j < 10 ? 20 : 15); ++i) body(i, j, k) = 1;
  const std::vector<FieldOfViewContact> contacts = field_of_view_contacts(body, sides(g), -kAll, kAll);
  // The back rows' ends face -x and +x (the back row's corners count there), the rest of the back row -y.
  EXPECT_EQ(count(contacts, ScanEdge::MinusX), 10 * 4);
  EXPECT_EQ(count(contacts, ScanEdge::PlusX), 10 * 4);
  EXPECT_EQ(count(contacts, ScanEdge::MinusY), 18 * 4);
  for (const FieldOfViewContact& c : contacts) {
    EXPECT_LT(c.point.y(), 10);  // none where air surrounds the head
    EXPECT_FALSE(c.on_disc);
  }
  const std::array<bool, 6> cut = cut_grid_faces(body, contacts);
  EXPECT_EQ(cut, (std::array<bool, 6>{true, true, true, false, false, false}));
  // Only the levels asked for.
  EXPECT_EQ(field_of_view_contacts(body, sides(g), 0.5, 2.5).size(), contacts.size() / 2);
}

// The same head on a grid cropped inside a larger scan: where the grid ends the scan goes on, so nothing touches it.
TEST(FieldOfView, AGridCroppedInsideTheScanHasNoContacts) {
  const GridGeometry g = grid(20, 20, 4, Eigen::Vector3d::Zero());
  Mask body(g, 1);
  ScanSides scan = sides(g);
  scan.lo -= Eigen::Vector2d::Constant(5);
  scan.hi += Eigen::Vector2d::Constant(5);
  EXPECT_TRUE(field_of_view_contacts(body, scan, -kAll, kAll).empty());
  // A grid whose last column lies half a voxel inside the scan's last centre ends with the scan: the next column
  // would lie beyond it.
  scan = sides(g);
  scan.hi.x() += 0.5;
  const std::vector<FieldOfViewContact> contacts = field_of_view_contacts(body, scan, -kAll, kAll);
  EXPECT_EQ(count(contacts, ScanEdge::PlusX), 20 * 4);
}

// A head frame turned 90 degrees from the scan's: the scan's narrow x extent (11 mm) runs along the head frame's y.
// Where the scan ends behind the head (head y -5) is a contact; where it ends in front (head y +5) is the face's front;
// the head frame's x ends of the grid lie well inside the scan's long y extent.
TEST(FieldOfView, ATurnedHeadFrameMapsItsNeighboursBackToTheScan) {
  const GridGeometry g = grid(41, 41, 3, Eigen::Vector3d(-20, -20, 0));
  ScanSides scan;
  scan.lo = Eigen::Vector2d(-5.5, -100);
  scan.hi = Eigen::Vector2d(5.5, 100);
  scan.turn.degrees = 90;
  Mask body(g, 0);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 41; ++j)
      for (int i = 0; i < 41; ++i) body(i, j, k) = !scan.outside(g.point(i, j, k));
  ASSERT_EQ(std::count(body.data.begin(), body.data.end(), 1), 41 * 11 * 3);
  const std::vector<FieldOfViewContact> contacts = field_of_view_contacts(body, scan, -kAll, kAll);
  EXPECT_EQ(count(contacts, ScanEdge::MinusY), 41 * 3);
  EXPECT_EQ(contacts.size(), 41u * 3);
  for (const FieldOfViewContact& c : contacts) EXPECT_NEAR(c.point.y(), -5, 1e-9);
}

// A volume of air (-1000) whose columns beyond `radius` of `centre` hold a fill of -3024, as a scanner writes outside
// its reconstruction disc; a ball of tissue inside so that the air is not the lowest value everywhere.
Field disc_volume(const GridGeometry& g, const Eigen::Vector2d& centre, double radius) {
  Field f(g, -1000.0f);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        if ((p.head<2>() - centre).norm() > radius) f(i, j, k) = -3024.0f;
        if ((p - Eigen::Vector3d(centre.x(), centre.y(), 5)).norm() < 10) f(i, j, k) = 40.0f;
      }
  return f;
}

TEST(FieldOfView, AReconstructionDiscIsFoundWhereItsFillIs) {
  GridGeometry g = grid(120, 100, 6, Eigen::Vector3d(-10, 5, 0));
  g.spacing = Eigen::Vector3d(1.5, 1.5, 2);
  // Whole within the box, and clipped by it on three sides (a disc wider than the scan's box: its corners only).
  for (const auto& [centre, radius] : {std::pair{Eigen::Vector2d(80, 75), 60.0}, {Eigen::Vector2d(85, 80), 95.0}}) {
    const std::optional<ReconstructionDisc> disc = find_reconstruction_disc(disc_volume(g, centre, radius));
    ASSERT_TRUE(disc) << radius;
    EXPECT_NEAR((disc->centre - centre).norm(), 0, 0.5) << radius;
    // The border columns' centres lie within a voxel inside the circle.
    EXPECT_NEAR(disc->radius, radius - 0.5 * g.spacing.x(), g.spacing.x()) << radius;
  }
}

TEST(FieldOfView, AFillThatIsNoDiscIsNone) {
  const GridGeometry g = grid(80, 80, 4, Eigen::Vector3d::Zero());
  // No fill: the lowest value is in a few voxels only, not whole columns.
  Field f(g, -1000.0f);
  f(3, 4, 1) = -1100.0f;
  EXPECT_FALSE(find_reconstruction_disc(f));
  // A fill beyond a square (air set to one value around a body's box), and beyond a straight line.
  for (int j = 0; j < 80; ++j)
    for (int i = 0; i < 80; ++i) {
      const bool beyond_square = i < 15 || i > 65 || j < 15 || j > 65;
      for (int k = 0; k < 4; ++k) f(i, j, k) = beyond_square ? -3024.0f : (k == 1 ? 40.0f : -1000.0f);
    }
  EXPECT_FALSE(find_reconstruction_disc(f));
  for (int j = 0; j < 80; ++j)
    for (int i = 0; i < 80; ++i)
      for (int k = 0; k < 4; ++k) f(i, j, k) = i < 10 ? -3024.0f : (k == 1 ? 40.0f : -1000.0f);
  EXPECT_FALSE(find_reconstruction_disc(f));
}

// A head wider than the disc: where the disc cuts its sides and its back there are contacts, facing out of the disc;
// where it clips the nose at the front there are none.
TEST(FieldOfView, ADiscCutsTheSidesAndTheBackButNotTheFront) {
  const GridGeometry g = grid(61, 61, 2, Eigen::Vector3d(-30, -30, 0));
  ScanSides scan = sides(g);
  scan.disc = ReconstructionDisc{Eigen::Vector2d::Zero(), 20.5};
  Mask body(g, 0);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 61; ++j)
      for (int i = 0; i < 61; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        // A head 50 mm wide whose nose (10 mm wide) reaches y 25, all within the scan's disc.
        const bool head = std::abs(p.x()) <= 25 && p.y() <= 10, nose = std::abs(p.x()) <= 5 && p.y() <= 25;
        body(i, j, k) = (head || nose) && !scan.outside(p);
      }
  const std::vector<FieldOfViewContact> contacts = field_of_view_contacts(body, scan, -kAll, kAll);
  ASSERT_FALSE(contacts.empty());
  double front = -kAll;
  for (const FieldOfViewContact& c : contacts) {
    front = std::max(front, c.point.y());
    EXPECT_LE(scan.disc_normal(c.point).y(), 0.5) << c.point.transpose();
    EXPECT_TRUE(c.on_disc) << c.point.transpose();
  }
  // The sides meet the disc up to where it faces 60 degrees from the front (y = 20.5 cos 60).
  EXPECT_NEAR(front, 10, 1.0);
  EXPECT_EQ(count(contacts, ScanEdge::MinusY) > 0, true);
  EXPECT_EQ(cut_grid_faces(body, contacts), (std::array<bool, 6>{false, false, false, false, false, false}));
}

}  // namespace
}  // namespace facehex
