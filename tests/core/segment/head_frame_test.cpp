#include "core/segment/head_frame.h"

#include <gtest/gtest.h>

#include <cmath>

namespace facehex {
namespace {

// A smooth field on a small anisotropic grid.
Field smooth_field() {
  GridGeometry g;
  g.dims = {30, 24, 9};
  g.spacing = Eigen::Vector3d(2.0, 2.5, 3.0);
  g.origin = Eigen::Vector3d(-10, 5, 2);
  Field f(g, 0);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        f(i, j, k) = static_cast<float>(std::sin(0.1 * p.x()) + std::cos(0.07 * p.y()) + 0.01 * p.z());
      }
  return f;
}

TEST(HeadFrame, TheTurnedFieldHoldsTheFieldWhereItTurnedTo) {
  const Field f = smooth_field();
  HeadTurn turn;
  turn.degrees = 17;
  turn.axis = Eigen::Vector2d(15, 30);
  const Field t = turned_to_head_frame(f, turn, 1.5, -100);
  const GridGeometry& g = t.geometry;
  EXPECT_EQ(g.spacing, Eigen::Vector3d::Constant(1.5));
  int inside = 0;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d source = turn.to_model(g.point(i, j, k));
        const bool in = source.x() >= -11 && source.x() <= 49 && source.y() >= 3.75 && source.y() <= 63.75;
        if (in) {
          EXPECT_FLOAT_EQ(t(i, j, k), static_cast<float>(sample(f, source)));
          ++inside;
        } else if (source.x() < -12 || source.x() > 50 || source.y() < 3 || source.y() > 65) {
          EXPECT_EQ(t(i, j, k), -100.0f);  // nothing was scanned there
        }
      }
  EXPECT_GT(inside, 1000);
}

TEST(HeadFrame, APitchedFieldHoldsTheFieldWhereItPitchedToOverItsWholeTiltedBox) {
  const Field f = smooth_field();
  HeadTurn turn;
  turn.degrees = -9;
  turn.axis = Eigen::Vector2d(15, 30);
  turn.pitch = 25;
  turn.axis_z = 14;
  const Field t = turned_to_head_frame(f, turn, 1.0, -100);
  const GridGeometry& g = t.geometry;
  int inside = 0;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d source = turn.to_model(g.point(i, j, k));
        const bool in = source.x() >= -11 && source.x() <= 49 && source.y() >= 3.75 && source.y() <= 63.75 &&
                        source.z() >= 0.5 && source.z() <= 27.5;
        if (in) {
          EXPECT_FLOAT_EQ(t(i, j, k), static_cast<float>(sample(f, source)));
          ++inside;
        }
      }
  EXPECT_GT(inside, 5000);
  // Every corner of the field's box, pitched, lies within the grid: the pitch tilts the box beyond its own heights.
  const GridGeometry& fg = f.geometry;
  for (const double x : {fg.lower(0), fg.upper(0)})
    for (const double y : {fg.lower(1), fg.upper(1)})
      for (const double z : {fg.lower(2), fg.upper(2)}) {
        const Eigen::Vector3d q = turn.to_head(Eigen::Vector3d(x, y, z));
        for (int a = 0; a < 3; ++a) {
          EXPECT_GE(q(a), g.lower(a) - 1.0 - 1e-9);
          EXPECT_LE(q(a), g.upper(a) + 1.0 + 1e-9);
        }
      }
  EXPECT_GT(g.upper(2) - g.lower(2), fg.upper(2) - fg.lower(2) + 10);
}

TEST(HeadFrame, ARegionIsThePartOfTheWholeGridThatHoldsIt) {
  // The same voxel centres and values as the whole turned grid, over a grid that holds the turned region.
  const Field f = smooth_field();
  HeadTurn turn;
  turn.degrees = -23;
  turn.axis = Eigen::Vector2d(12, 28);
  const Field whole = turned_to_head_frame(f, turn, 1.0, -100);
  const Eigen::Vector2d lo(0, 15), hi(20, 40);
  const Field part = turned_to_head_frame(f, turn, 1.0, -100, lo, hi);
  const GridGeometry &w = whole.geometry, &p = part.geometry;
  EXPECT_LT(p.size(), w.size() / 2);
  const Eigen::Vector3d offset = (p.origin - w.origin) / 1.0;
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(offset(a), std::round(offset(a)), 1e-9);
  for (int k = 0; k < p.dims[2]; ++k)
    for (int j = 0; j < p.dims[1]; ++j)
      for (int i = 0; i < p.dims[0]; ++i) {
        const int wi = i + static_cast<int>(std::lround(offset.x())),
                  wj = j + static_cast<int>(std::lround(offset.y()));
        ASSERT_TRUE(w.contains(wi, wj, k));
        EXPECT_EQ(part(i, j, k), whole(wi, wj, k));
      }
  // Every corner of the region, turned, lies within the part.
  for (const double x : {lo.x(), hi.x()})
    for (const double y : {lo.y(), hi.y()}) {
      const Eigen::Vector3d q = turn.to_head(Eigen::Vector3d(x, y, 0));
      EXPECT_GE(q.x(), p.lower(0) - 1e-9);
      EXPECT_LE(q.x(), p.upper(0) + 1e-9);
      EXPECT_GE(q.y(), p.lower(1) - 1e-9);
      EXPECT_LE(q.y(), p.upper(1) + 1e-9);
    }
}

}  // namespace
}  // namespace facehex
