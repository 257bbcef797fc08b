#pragma once
// Where the landmarks' names go on the screen: each beside its marker, clear of the other names and markers.
//
// Landmarks crowd where the face has its features (the stomion between the two mouth corners and the lips), and names
// drawn at a fixed offset from their markers cover each other there. Each name is tried at places around its marker,
// nearest first, on the side away from the landmarks' centre first (names fan out from the face), and takes the first
// place that overlaps no name placed before it and no other marker and lies inside the view; a name with no free place
// within the search takes the place it overlaps least. Names are placed from the outermost landmark in, so the crowded
// middle takes what is left and its names move furthest. Display pixels throughout; the result does not depend on the
// order of the input.
#include <Eigen/Core>
#include <vector>

namespace facehex::gui {

struct LabelLayoutOptions {
  double marker_radius = 6;  // px: a marker's disc, which no name covers
  double gap = 4;            // px between a marker's disc and its name
  double spacing = 3;        // px kept between two names
  int rings = 6;             // how far out places are tried, in name heights
  // px, (width, height): the view; the part of a name outside it counts as covered. Zero: no bounds.
  Eigen::Vector2d viewport = Eigen::Vector2d::Zero();
};

// anchors: #L x 2 display positions of the markers; sizes: #L x 2 (width, height) of each name's box. Returns #L x 2:
// each box's lower-left corner.
Eigen::MatrixX2d place_labels(const Eigen::MatrixX2d& anchors, const Eigen::MatrixX2d& sizes,
                              const LabelLayoutOptions& options = {});

// The area two boxes (lower-left corner, size) share.
double box_overlap(const Eigen::Vector2d& corner_a, const Eigen::Vector2d& size_a, const Eigen::Vector2d& corner_b,
                   const Eigen::Vector2d& size_b);

}  // namespace facehex::gui
