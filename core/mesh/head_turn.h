#pragma once
// A head turned about the vertical axis (yaw) and pitched about the lateral axis (nodding) in the scanner, and the
// head frame in which its face looks to +y, upright.
//
// The head frame is the model's frame (+y anterior, +z superior) turned about the vertical line x = axis.x(),
// y = axis.y() by `degrees`, counter-clockwise seen from above, and then pitched back about the lateral line
// y = axis.y(), z = axis_z by `pitch`: a face looking towards (sin t cos p, cos t cos p, sin p), t = degrees, p =
// pitch (positive: the chin raised), looks to +y in the head frame. The segmentation places its cuts in the head
// frame of the CT (core/segment/head_frame.h) and the landmark finder reads the profile in the head frame of the
// model's mid-sagittal plane (core/face/face_landmarks.h); the models themselves stay in the CT's frame, so that they
// overlay it.
#include <Eigen/Core>

#include "core/mesh/mid_sagittal_plane.h"

namespace facehex {

struct HeadTurn {
  double degrees = 0;
  Eigen::Vector2d axis = Eigen::Vector2d::Zero();  // mm, the model's frame
  double pitch = 0;                                // degrees, positive: the chin raised
  double axis_z = 0;                               // mm: the height of the pitch's lateral axis

  bool turned() const { return degrees != 0 || pitch != 0; }
  Eigen::Vector3d to_head(const Eigen::Vector3d& p) const;
  Eigen::Vector3d to_model(const Eigen::Vector3d& head) const;
  // The height in the head frame, at its depth head_y, of the model frame's level z = level (a CT's slice plane:
  // tilted in the head frame of a pitched head, level with it otherwise).
  double head_height_of_level(double level, double head_y) const;
  // The plane in the other frame; its point (x, y, z) moves with the frame (an unturned plane's y is the axis' y), and
  // its pitch is the head frame's pitch in that frame (MidSagittalPlane::pitch).
  MidSagittalPlane to_head(const MidSagittalPlane& plane) const;
  MidSagittalPlane to_model(const MidSagittalPlane& head) const;
};

// HeadTurn::to_model with the turn's and the pitch's cosines and sines computed once, for maps of many points (a CT
// resampled in the head frame); the same points as to_model.
class ModelFromHead {
 public:
  explicit ModelFromHead(const HeadTurn& turn);
  Eigen::Vector3d operator()(const Eigen::Vector3d& head) const;

 private:
  HeadTurn turn_;
  double pitch_cos_, pitch_sin_, turn_cos_, turn_sin_;
};

// The turn whose head frame has the plane unturned and unpitched, about the vertical and the lateral line through the
// plane's point.
HeadTurn head_turn_of(const MidSagittalPlane& plane);

}  // namespace facehex
