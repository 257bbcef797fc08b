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

ScanSides sides(const GridGeometry& g) { return {{g.lower(0), g.lower(1)}, {g.upper(0), g.upper(1)}, HeadTurn{}}; }

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
  for (const FieldOfViewContact& c : contacts) EXPECT_LT(c.point.y(), 10);  // none where air surrounds the head
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

}  // namespace
}  // namespace facehex
