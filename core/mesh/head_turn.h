#pragma once
// A head turned about the vertical axis (yaw), and the head frame in which its face looks to +y.
//
// The head frame is the model's frame (+y anterior, +z superior) turned about the vertical line x = axis.x(),
// y = axis.y() by `degrees`, counter-clockwise seen from above: a face looking towards (sin t, cos t, 0), t = degrees,
// looks to +y in the head frame. The segmentation places its cuts in the head frame of the CT (core/segment/
// head_frame.h) and the landmark finder reads the profile in the head frame of the model's mid-sagittal plane
// (core/face/face_landmarks.h); the models themselves stay in the CT's frame, so that they overlay it.
#include <Eigen/Core>

#include "core/mesh/mid_sagittal_plane.h"

namespace facehex {

struct HeadTurn {
  double degrees = 0;
  Eigen::Vector2d axis = Eigen::Vector2d::Zero();  // mm, the model's frame

  Eigen::Vector3d to_head(const Eigen::Vector3d& p) const;
  Eigen::Vector3d to_model(const Eigen::Vector3d& head) const;
  // The plane in the other frame; its point (x, y, z) moves with the frame (an unturned plane's y is the axis' y).
  MidSagittalPlane to_head(const MidSagittalPlane& plane) const;
  MidSagittalPlane to_model(const MidSagittalPlane& head) const;
};

// The turn whose head frame has the plane unturned, about the vertical line through the plane's point.
HeadTurn head_turn_of(const MidSagittalPlane& plane);

}  // namespace facehex
