#include "core/mesh/head_turn.h"

#include <cmath>

namespace facehex {
namespace {

constexpr double kRadians = M_PI / 180;

// Counter-clockwise about +z by the angle of cosine c and sine s.
Eigen::Vector2d rotated(const Eigen::Vector2d& v, double c, double s) {
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// Counter-clockwise about +z by `degrees`.
Eigen::Vector2d rotated(const Eigen::Vector2d& v, double degrees) {
  const double a = degrees * kRadians;
  return rotated(v, std::cos(a), std::sin(a));
}

// (y, z) turned about +x by `degrees` (from +y towards +z) about the line through (y, z) = centre.
Eigen::Vector3d pitched(const Eigen::Vector3d& p, const Eigen::Vector2d& centre, double degrees) {
  const Eigen::Vector2d q = centre + rotated(p.tail<2>() - centre, degrees);
  return {p.x(), q.x(), q.y()};
}

// The plane through `point` with normal n (n.x() != 0).
MidSagittalPlane plane_through(const Eigen::Vector3d& point, const Eigen::Vector3d& n, double pitch) {
  return MidSagittalPlane{point.x(), -n.z() / n.x(), point.z(), -n.y() / n.x(), point.y(), pitch};
}

// The plane's normal (1, -turn, -slope) turned by t about z is (cos t + turn sin t, sin t - turn cos t, -slope).
MidSagittalPlane yawed(const MidSagittalPlane& plane, const Eigen::Vector2d& axis, double degrees) {
  const double a = degrees * kRadians, c = std::cos(a), s = std::sin(a);
  const Eigen::Vector2d q = axis + rotated(Eigen::Vector2d(plane.x, plane.y) - axis, degrees);
  return plane_through(Eigen::Vector3d(q.x(), q.y(), plane.z),
                       Eigen::Vector3d(c + plane.turn * s, s - plane.turn * c, -plane.slope), plane.pitch);
}

MidSagittalPlane pitched(const MidSagittalPlane& plane, const Eigen::Vector2d& centre, double degrees) {
  const Eigen::Vector3d n = pitched(Eigen::Vector3d(1, -plane.turn, -plane.slope), Eigen::Vector2d::Zero(), degrees);
  return plane_through(pitched(Eigen::Vector3d(plane.x, plane.y, plane.z), centre, degrees), n, plane.pitch + degrees);
}

}  // namespace

Eigen::Vector3d HeadTurn::to_head(const Eigen::Vector3d& p) const {
  const Eigen::Vector2d q = axis + rotated(p.head<2>() - axis, degrees);
  const Eigen::Vector3d yawed(q.x(), q.y(), p.z());
  return pitch == 0 ? yawed : pitched(yawed, Eigen::Vector2d(axis.y(), axis_z), -pitch);
}

Eigen::Vector3d HeadTurn::to_model(const Eigen::Vector3d& head) const { return ModelFromHead(*this)(head); }

ModelFromHead::ModelFromHead(const HeadTurn& turn)
    : turn_(turn),
      pitch_cos_(turn.pitch == 0 ? 1.0 : std::cos(turn.pitch * kRadians)),  // unpitched: no trigonometry per call
      pitch_sin_(turn.pitch == 0 ? 0.0 : std::sin(turn.pitch * kRadians)),
      turn_cos_(std::cos(-turn.degrees * kRadians)),
      turn_sin_(std::sin(-turn.degrees * kRadians)) {}

// Pitched about the lateral line (axis.y, axis_z), then turned about the vertical one.
Eigen::Vector3d ModelFromHead::operator()(const Eigen::Vector3d& head) const {
  Eigen::Vector3d q = head;
  if (turn_.pitch != 0) {
    const Eigen::Vector2d centre(turn_.axis.y(), turn_.axis_z);
    q.tail<2>() = centre + rotated(head.tail<2>() - centre, pitch_cos_, pitch_sin_);
  }
  const Eigen::Vector2d r = turn_.axis + rotated(q.head<2>() - turn_.axis, turn_cos_, turn_sin_);
  return {r.x(), r.y(), q.z()};
}

// to_model pitches first, about the lateral line (axis.y, axis_z), and then turns, which keeps heights: the model's
// height of a head point is axis_z + (head_y - axis.y) sin p + (head_z - axis_z) cos p.
double HeadTurn::head_height_of_level(double level, double head_y) const {
  if (pitch == 0) return level;
  const double p = pitch * kRadians;
  return axis_z + (level - axis_z - (head_y - axis.y()) * std::sin(p)) / std::cos(p);
}

MidSagittalPlane HeadTurn::to_head(const MidSagittalPlane& plane) const {
  const MidSagittalPlane yawed_plane = yawed(plane, axis, degrees);
  return pitch == 0 ? yawed_plane : pitched(yawed_plane, Eigen::Vector2d(axis.y(), axis_z), -pitch);
}

MidSagittalPlane HeadTurn::to_model(const MidSagittalPlane& head) const {
  return yawed(pitch == 0 ? head : pitched(head, Eigen::Vector2d(axis.y(), axis_z), pitch), axis, -degrees);
}

// The yaw t that leaves the plane unturned once pitched back: its normal (1, -turn, -slope) turned by t about z has
// y component sin t - turn cos t, which the pitch p back mixes with the z component -slope into
// (sin t - turn cos t) cos p - slope sin p; zero when sin(t - atan(turn)) = slope tan p / sqrt(1 + turn^2).
HeadTurn head_turn_of(const MidSagittalPlane& plane) {
  HeadTurn turn;
  turn.degrees = std::atan(plane.turn) / kRadians;
  if (plane.pitch != 0)
    turn.degrees += std::asin(plane.slope * std::tan(plane.pitch * kRadians) / std::hypot(1.0, plane.turn)) / kRadians;
  turn.axis = Eigen::Vector2d(plane.x, plane.y);
  turn.pitch = plane.pitch;
  turn.axis_z = plane.z;
  return turn;
}

}  // namespace facehex
