#include "ui/label_layout.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

namespace facehex::gui {
namespace {

// The distance from a marker to the nearest point of a box (lower-left corner, size).
double distance_to_box(const Eigen::Vector2d& a, const Eigen::Vector2d& corner, const Eigen::Vector2d& size) {
  return (a.cwiseMax(corner).cwiseMin(corner + size) - a).norm();
}

// No two names come nearer than the spacing, no name covers another marker's disc (as its square), and each lies within
// the search of its marker, clear of its own disc.
void expect_clear_layout(const Eigen::MatrixX2d& anchors, const Eigen::MatrixX2d& sizes,
                         const Eigen::MatrixX2d& corners, const LabelLayoutOptions& options) {
  const Eigen::Index n = anchors.rows();
  const Eigen::Vector2d disc = Eigen::Vector2d::Constant(2 * options.marker_radius);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector2d ci = corners.row(i).transpose(), si = sizes.row(i).transpose();
    const double d = distance_to_box(anchors.row(i).transpose(), ci, si);
    EXPECT_GE(d, options.marker_radius + options.gap - 1e-9) << "name " << i << " covers its own marker";
    EXPECT_LE(d, options.marker_radius + options.gap + (options.rings - 1) * si.y() + 1e-9) << "name " << i;
    for (Eigen::Index j = 0; j < n; ++j) {
      if (j == i) continue;
      if (j > i) {
        const Eigen::Vector2d spaced_corner = ci.array() - options.spacing,
                              spaced_size = si.array() + 2 * options.spacing;
        EXPECT_EQ(box_overlap(spaced_corner, spaced_size, corners.row(j).transpose(), sizes.row(j).transpose()), 0)
            << i << ", " << j;
      }
      EXPECT_EQ(box_overlap(ci, si, anchors.row(j).transpose() - disc / 2, disc), 0)
          << "name " << i << ", marker " << j;
    }
  }
}

// The view's settings: its handles reach 12 px from their centres.
LabelLayoutOptions gui_options() {
  LabelLayoutOptions options;
  options.marker_radius = 12;
  return options;
}

TEST(LabelLayout, BoxOverlapIsTheSharedArea) {
  EXPECT_DOUBLE_EQ(box_overlap({0, 0}, {4, 2}, {3, 1}, {5, 5}), 1.0);
  EXPECT_DOUBLE_EQ(box_overlap({0, 0}, {4, 2}, {4, 0}, {1, 1}), 0.0);  // touching edges share no area
  EXPECT_DOUBLE_EQ(box_overlap({0, 0}, {4, 2}, {1, 0.5}, {1, 1}), 1.0);
}

TEST(LabelLayout, ALoneNameSitsLevelBesideItsMarker) {
  const LabelLayoutOptions options;
  Eigen::MatrixX2d anchors(1, 2), sizes(1, 2);
  anchors << 100, 200;
  sizes << 80, 16;
  const Eigen::MatrixX2d corners = place_labels(anchors, sizes, options);
  EXPECT_NEAR(corners(0, 0), 100 + options.marker_radius + options.gap, 1e-9);
  EXPECT_NEAR(corners(0, 1), 200 - 8, 1e-9);  // centred on the marker's height
}

TEST(LabelLayout, NamesFanOutFromTheLandmarksCentre) {
  const LabelLayoutOptions options;
  Eigen::MatrixX2d anchors(2, 2), sizes(2, 2);
  anchors << 100, 200, 300, 200;
  sizes << 80, 16, 80, 16;
  const Eigen::MatrixX2d corners = place_labels(anchors, sizes, options);
  EXPECT_NEAR(corners(0, 0) + 80, 100 - options.marker_radius - options.gap, 1e-9);  // the left one to the left
  EXPECT_NEAR(corners(1, 0), 300 + options.marker_radius + options.gap, 1e-9);       // the right one to the right
}

// A marker near the view's edge: its name stays in the view, inwards, rather than cut off outside.
TEST(LabelLayout, NamesStayInsideTheView) {
  LabelLayoutOptions options;
  options.viewport = Eigen::Vector2d(400, 300);
  Eigen::MatrixX2d anchors(3, 2), sizes(3, 2);
  anchors << 5, 150, 200, 150, 390, 295;
  sizes << 80, 16, 80, 16, 100, 16;
  const Eigen::MatrixX2d corners = place_labels(anchors, sizes, options);
  for (Eigen::Index i = 0; i < 3; ++i) {
    EXPECT_GE(corners(i, 0), 0) << i;
    EXPECT_GE(corners(i, 1), 0) << i;
    EXPECT_LE(corners(i, 0) + sizes(i, 0), 400) << i;
    EXPECT_LE(corners(i, 1) + sizes(i, 1), 300) << i;
  }
  // Without bounds the outer two go outwards, out of the view.
  const Eigen::MatrixX2d unbounded = place_labels(anchors, sizes);
  EXPECT_LT(unbounded(0, 0), 0);
  EXPECT_GT(unbounded(2, 0) + sizes(2, 0), 400);
}

// The layout the GUI met on the bundled patient: the lips' and mouth corners' markers within 40 px of each other,
// the stomion between them, and a name that placed at a fixed offset covered the next.
TEST(LabelLayout, CrowdedMouthNamesDoNotCoverEachOther) {
  const LabelLayoutOptions options = gui_options();
  Eigen::MatrixX2d anchors(9, 2), sizes(9, 2);
  anchors << 825, 688, 825, 670, 825, 587, 815, 560, 815, 538, 808, 525, 808, 505, 765, 520, 852, 508;
  for (Eigen::Index i = 0; i < 9; ++i) sizes.row(i) << 60 + 10 * (i % 4), 17;
  expect_clear_layout(anchors, sizes, place_labels(anchors, sizes, options), options);
}

// Clusters of a dozen names over a face-sized patch, several seeds: all clear.
TEST(LabelLayout, RandomClustersAreLaidOutClear) {
  const LabelLayoutOptions options = gui_options();
  for (const unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> x(400, 600), y(300, 600), width(40, 130);
    Eigen::MatrixX2d anchors(12, 2), sizes(12, 2);
    for (Eigen::Index i = 0; i < 12; ++i) {
      anchors.row(i) << x(random), y(random);
      sizes.row(i) << width(random), 17;
    }
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_clear_layout(anchors, sizes, place_labels(anchors, sizes, options), options);
  }
}

TEST(LabelLayout, TheInputOrderDoesNotMatter) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> x(0, 150), width(40, 130);
  Eigen::MatrixX2d anchors(10, 2), sizes(10, 2);
  for (Eigen::Index i = 0; i < 10; ++i) {
    anchors.row(i) << x(random), x(random);
    sizes.row(i) << width(random), 17;
  }
  const Eigen::MatrixX2d corners = place_labels(anchors, sizes);
  std::vector<Eigen::Index> order(10);
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::shuffle(order.begin(), order.end(), random);
  const Eigen::MatrixX2d shuffled = place_labels(anchors(order, Eigen::all), sizes(order, Eigen::all));
  EXPECT_EQ(shuffled, corners(order, Eigen::all));
}

// More names at one point than the search has room for: each still gets a finite place beside the point, and the
// overlap left is the least the search found, not a pile of names at the marker.
TEST(LabelLayout, NamesWithNoRoomLeftTakeTheLeastCrowdedPlace) {
  LabelLayoutOptions options = gui_options();
  options.rings = 2;
  Eigen::MatrixX2d anchors = Eigen::MatrixX2d::Constant(40, 2, 100.0), sizes(40, 2);
  for (Eigen::Index i = 0; i < 40; ++i) sizes.row(i) << 50, 16;
  const Eigen::MatrixX2d corners = place_labels(anchors, sizes, options);
  ASSERT_TRUE(corners.allFinite());
  int most_at_one_place = 0;
  for (Eigen::Index i = 0; i < 40; ++i) {
    const double d = distance_to_box(anchors.row(i).transpose(), corners.row(i).transpose(), sizes.row(i).transpose());
    EXPECT_GE(d, options.marker_radius + options.gap - 1e-9);
    EXPECT_LE(d, options.marker_radius + options.gap + sizes(i, 1) + 1e-9);
    int same = 0;
    for (Eigen::Index j = 0; j < 40; ++j) same += corners.row(j) == corners.row(i);
    most_at_one_place = std::max(most_at_one_place, same);
  }
  EXPECT_LE(most_at_one_place, 4);  // spread over the places, not piled on the first
}

TEST(LabelLayout, NoLandmarksNoNames) {
  EXPECT_EQ(place_labels(Eigen::MatrixX2d(0, 2), Eigen::MatrixX2d(0, 2)).rows(), 0);
}

}  // namespace
}  // namespace facehex::gui
