#include "core/mesh/head_turn.h"

#include <cmath>

namespace facehex {
namespace {

// Counter-clockwise about +z by `degrees`.
Eigen::Vector2d rotated(const Eigen::Vector2d& v, double degrees) {
  const double a = degrees * M_PI / 180, c = std::cos(a), s = std::sin(a);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

}  // namespace

Eigen::Vector3d HeadTurn::to_head(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d q = axis + rotated(p.head<2>() - axis, degrees);
  return {q.x(), q.y(), p.z()};
}

Eigen::Vector3d HeadTurn::to_model(const Eigen::Vector3d& head) const {
  const Eigen::Vector2d q = axis + rotated(head.head<2>() - axis, -degrees);
  return {q.x(), q.y(), head.z()};
}

// A plane's normal (1, -turn, -slope) turned by t about z is (cos t + turn sin t, sin t - turn cos t, -slope); scaled
// to a first component of 1 it gives the turned plane's turn and slope.
MidSagittalPlane HeadTurn::to_head(const MidSagittalPlane& plane) const {
  const double a = degrees * M_PI / 180, c = std::cos(a), s = std::sin(a);
  const double nx = c + plane.turn * s, ny = s - plane.turn * c;
  const Eigen::Vector3d point = to_head(Eigen::Vector3d(plane.x, plane.y, plane.z));
  return MidSagittalPlane{point.x(), plane.slope / nx, point.z(), -ny / nx, point.y()};
}

MidSagittalPlane HeadTurn::to_model(const MidSagittalPlane& head) const {
  HeadTurn back = *this;
  back.degrees = -degrees;
  return back.to_head(head);
}

HeadTurn head_turn_of(const MidSagittalPlane& plane) {
  HeadTurn turn;
  turn.degrees = std::atan(plane.turn) * 180 / M_PI;
  turn.axis = Eigen::Vector2d(plane.x, plane.y);
  return turn;
}

}  // namespace facehex
