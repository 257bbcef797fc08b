#include "core/mesh/head_turn.h"

#include <gtest/gtest.h>

#include <cmath>

namespace facehex {
namespace {

TEST(HeadTurn, TurnsAboutItsVerticalAxisSoThatTheFaceLooksToPlusY) {
  HeadTurn turn;
  turn.degrees = 30;
  turn.axis = Eigen::Vector2d(10, -5);
  // A face looking towards (sin 30, cos 30, 0) looks to +y in the head frame.
  const Eigen::Vector3d axis_point(10, -5, 7);
  const Eigen::Vector3d forward(std::sin(M_PI / 6), std::cos(M_PI / 6), 0);
  const Eigen::Vector3d head = turn.to_head(axis_point + 20 * forward);
  EXPECT_LT((head - Eigen::Vector3d(10, 15, 7)).norm(), 1e-12);
  const Eigen::Vector3d p(3, 4, -2);
  EXPECT_LT((turn.to_model(turn.to_head(p)) - p).norm(), 1e-12);
  EXPECT_EQ(turn.to_head(p).z(), p.z());
  EXPECT_NEAR((turn.to_head(p) - axis_point).head<2>().norm(), (p - axis_point).head<2>().norm(), 1e-12);
}

TEST(HeadTurn, APlaneTurnsWithTheFrame) {
  // A leaning plane in the head frame, turned into the model's frame: its points turn with it and it is the plane
  // through them; head_turn_of undoes the turn.
  MidSagittalPlane head;
  head.x = 12, head.z = 40, head.slope = 0.1, head.y = -5;
  HeadTurn turn;
  turn.degrees = -17;
  turn.axis = Eigen::Vector2d(10, -5);
  const MidSagittalPlane model = turn.to_model(head);
  EXPECT_NEAR(model.turn, std::tan(-17 * M_PI / 180), 1e-12);  // the face looks towards (sin, cos) of -17 degrees
  for (const Eigen::Vector3d& on :
       {Eigen::Vector3d(head.x_at(30, 0), 30, 0), Eigen::Vector3d(head.x_at(-8, 90), -8, 90)}) {
    const Eigen::Vector3d p = turn.to_model(on);
    EXPECT_NEAR(p.x(), model.x_at(p.y(), p.z()), 1e-9);
    EXPECT_NEAR(model.normal().dot(p - Eigen::Vector3d(model.x, model.y, model.z)), 0, 1e-9);
  }
  const HeadTurn back = head_turn_of(model);
  EXPECT_NEAR(back.degrees, -17, 1e-9);
  const MidSagittalPlane again = back.to_head(model);
  EXPECT_NEAR(again.turn, 0, 1e-12);
  EXPECT_NEAR(again.slope, head.slope, 1e-12);
  // The same plane as `head`, whose point turned about another axis.
  const Eigen::Vector3d q = back.to_head(turn.to_model(Eigen::Vector3d(head.x_at(0, 55), 0, 55)));
  EXPECT_NEAR(q.x(), again.x_at(q.y(), q.z()), 1e-9);
}

TEST(HeadTurn, PitchesAboutItsLateralAxisAfterTheTurnSoThatTheFaceLooksToPlusYUpright) {
  HeadTurn turn;
  turn.degrees = 20;
  turn.axis = Eigen::Vector2d(10, -5);
  turn.pitch = 15;
  turn.axis_z = 40;
  const double t = 20 * M_PI / 180, p = 15 * M_PI / 180;
  // A face looking towards (sin t cos p, cos t cos p, sin p), its chin raised, looks to +y in the head frame; the
  // head's up (the face's up, turned and pitched as it is) is +z there.
  const Eigen::Vector3d centre(10, -5, 40);
  const Eigen::Vector3d forward(std::sin(t) * std::cos(p), std::cos(t) * std::cos(p), std::sin(p));
  const Eigen::Vector3d up(-std::sin(t) * std::sin(p), -std::cos(t) * std::sin(p), std::cos(p));
  EXPECT_LT((turn.to_head(centre + 20 * forward) - Eigen::Vector3d(10, 15, 40)).norm(), 1e-12);
  EXPECT_LT((turn.to_head(centre + 30 * up) - Eigen::Vector3d(10, -5, 70)).norm(), 1e-12);
  for (const Eigen::Vector3d& q : {Eigen::Vector3d(3, 4, -2), Eigen::Vector3d(-50, 80, 120)}) {
    EXPECT_LT((turn.to_model(turn.to_head(q)) - q).norm(), 1e-12);
    EXPECT_NEAR((turn.to_head(q) - centre).norm(), (q - centre).norm(), 1e-12);
  }
  // A slice plane of the model's frame, in the head frame: the head height of each of its points at their depth.
  for (const Eigen::Vector3d& on :
       {Eigen::Vector3d(3, 4, 12), Eigen::Vector3d(-50, 80, 12), Eigen::Vector3d(7, -60, 12)}) {
    const Eigen::Vector3d head = turn.to_head(on);
    EXPECT_NEAR(turn.head_height_of_level(12, head.y()), head.z(), 1e-9);
  }
  // Without a pitch, the height stays as it was, bit for bit.
  turn.pitch = 0;
  EXPECT_EQ(turn.head_height_of_level(12, 80), 12);
  EXPECT_EQ(turn.to_head(Eigen::Vector3d(3, 4, -2)).z(), -2);
}

TEST(HeadTurn, APitchedPlaneGoesWithTheFrameAndHeadTurnOfUndoesTurnAndPitch) {
  // A leaning plane of the head frame, into the model's frame of a head turned by -17 and pitched by -12 degrees: its
  // points go with it, it carries the pitch, and head_turn_of gives a frame where it is unturned and unpitched.
  MidSagittalPlane head;
  head.x = 12, head.z = 40, head.slope = 0.1, head.y = -5;
  HeadTurn turn;
  turn.degrees = -17;
  turn.axis = Eigen::Vector2d(10, -5);
  turn.pitch = -12;
  turn.axis_z = 35;
  const MidSagittalPlane model = turn.to_model(head);
  EXPECT_EQ(model.pitch, -12);
  for (const Eigen::Vector3d& on :
       {Eigen::Vector3d(head.x_at(30, 0), 30, 0), Eigen::Vector3d(head.x_at(-8, 90), -8, 90)}) {
    const Eigen::Vector3d p = turn.to_model(on);
    EXPECT_NEAR(p.x(), model.x_at(p.y(), p.z()), 1e-9);
  }
  const MidSagittalPlane round_trip = turn.to_head(model);
  EXPECT_NEAR(round_trip.slope, head.slope, 1e-12);
  EXPECT_NEAR(round_trip.turn, 0, 1e-12);
  EXPECT_NEAR(round_trip.pitch, 0, 1e-12);
  const HeadTurn back = head_turn_of(model);
  EXPECT_NEAR(back.degrees, -17, 1e-9);
  EXPECT_EQ(back.pitch, -12);
  const MidSagittalPlane again = back.to_head(model);
  EXPECT_NEAR(again.turn, 0, 1e-12);
  EXPECT_NEAR(again.slope, head.slope, 1e-12);
  EXPECT_NEAR(again.pitch, 0, 1e-12);
  // back's frame is turn's up to a shift: the same directions.
  const Eigen::Vector3d a(3, 4, -2), b(-20, 60, 70);
  EXPECT_LT(((back.to_head(b) - back.to_head(a)) - (turn.to_head(b) - turn.to_head(a))).norm(), 1e-9);
}

}  // namespace
}  // namespace facehex
