#pragma once
// The front of the face read from a CT's own grey values, for the landmarks in narrow slits that the segmentation's
// smoothed skin bridges (closed eyelids, closed lips: eye_corners.h, stomion.h).
//
// In a head frame (core/mesh/head_turn.h: +x the side named left, +y anterior, +z superior): y(x, z), where a ray cast
// along -y from y_start first meets the skin threshold (trilinear, the crossing refined by bisection to 1/256 mm), on
// a grid of (x, z) 0.5 mm apart; bilinear between the grid's points. NaN where the ray starts inside the skin or meets
// none before y_stop. Outside the scan is air, so a field-of-view cut shows as a flat front, not as the border slice
// repeated.
#include <vector>

#include "core/mesh/head_turn.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

class FaceFront {
 public:
  static constexpr double kGrid = 0.5;  // mm

  // ct: intensities in the model's frame; frame: the head frame; the grid covers [x0, x1] x [z0, z1] (head frame).
  FaceFront(const Field& ct, double skin_threshold, const HeadTurn& frame, double x0, double x1, double z0, double z1,
            double y_start, double y_stop);

  // y at (x, z), NaN outside the grid or next to a point without a front.
  double operator()(double x, double z) const;
  // The mean of y at height z over the columns every kGrid mm from x - half_width to x + half_width: a profile's point
  // with a column's noise averaged. NaN where one of them is.
  double mean_across(double x, double half_width, double z) const;

 private:
  double x0_, z0_;
  int nx_, nz_;
  std::vector<double> y_;  // x fastest
};

}  // namespace facehex
