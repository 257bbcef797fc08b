#include "core/segment/symmetry_trace.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace facehex {
namespace {

const double kMaxSlope = std::tan(20 * M_PI / 180);

// Levels every 2 mm from z = 0 to 118 whose centres lie on c = 100 + slope (z - 60), within +-0.5 mm, except every
// level that `off` picks, whose centre lies 10 to 30 mm to +x (all on one side, as a clipped nose's plateau or a
// bulging cheek can put them).
std::vector<LevelCentre> levels_on_a_line(double slope, unsigned seed, bool (*off)(int)) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> noise(-0.5, 0.5), away(10, 30);
  std::vector<LevelCentre> levels;
  for (int k = 0; k < 60; ++k) {
    const double z = 2.0 * k;
    const double on_line = 100 + slope * (z - 60);
    levels.push_back({z, off(k) ? on_line + away(rng) : on_line + noise(rng)});
  }
  return levels;
}

bool none_off(int) { return false; }
// 27 of the 60 levels, most of them in one run (a plateau 36 mm tall) and the rest scattered.
bool many_off(int k) { return (k >= 20 && k < 38) || k % 7 == 3; }

TEST(SymmetryTrace, FollowsTheFacesLevelsWhenNearlyHalfLieFarToOneSide) {
  for (const double slope : {0.0, 0.1, -0.2})
    for (const unsigned seed : {1u, 2u, 3u}) {
      const std::vector<LevelCentre> levels = levels_on_a_line(slope, seed, many_off);
      const SymmetryTrace trace = consensus_trace(levels, 3.0, kMaxSlope);
      EXPECT_NEAR(trace.at(60), 100, 0.3) << "slope " << slope << " seed " << seed;
      EXPECT_NEAR(trace.slope, slope, 0.01) << "slope " << slope << " seed " << seed;
      std::vector<int> face;
      for (int k = 0; k < 60; ++k)
        if (!many_off(k)) face.push_back(k);
      EXPECT_EQ(trace.agreeing, face) << "slope " << slope << " seed " << seed;
    }
}

TEST(SymmetryTrace, IsTheLeastSquaresLineWhenEveryLevelAgrees) {
  const std::vector<LevelCentre> levels = levels_on_a_line(0.15, 4, none_off);
  const SymmetryTrace trace = consensus_trace(levels, 3.0, kMaxSlope);
  ASSERT_EQ(trace.agreeing.size(), levels.size());
  double z0 = 0, c0 = 0;
  for (const LevelCentre& l : levels) z0 += l.z / levels.size(), c0 += l.c / levels.size();
  double szz = 0, szc = 0;
  for (const LevelCentre& l : levels) szz += (l.z - z0) * (l.z - z0), szc += (l.z - z0) * (l.c - c0);
  EXPECT_NEAR(trace.z0, z0, 1e-9);
  EXPECT_NEAR(trace.c0, c0, 1e-9);
  EXPECT_NEAR(trace.slope, szc / szz, 1e-12);
}

// The line most levels agree with leans no further than allowed: on every other level the face's centre (vertical,
// x = 100), on the others centres on a line leaning 35 degrees through it (a misread that happens to line up, as the
// clusters of a clipped front, the neck and a bulge can). The steep line holds as many levels as the face's and more
// where it crosses it; bounded at 20 degrees, the trace is the face's.
TEST(SymmetryTrace, LeansNoFurtherThanAllowedWhereAsManyLevelsLieOnASteeperLine) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> noise(-0.5, 0.5);
  const double steep = std::tan(35 * M_PI / 180);
  std::vector<LevelCentre> levels;
  for (int k = 0; k < 60; ++k) {
    const double z = 2.0 * k;
    levels.push_back({z, (k % 2 ? 100 + steep * (z - 60) : 100.0) + noise(rng)});
  }
  const SymmetryTrace bounded = consensus_trace(levels, 3.0, kMaxSlope);
  EXPECT_NEAR(bounded.at(60), 100, 0.5);
  EXPECT_NEAR(bounded.slope, 0, 0.02);
  const SymmetryTrace unbounded = consensus_trace(levels, 3.0, 1.0);
  EXPECT_NEAR(unbounded.slope, steep, 0.02);
}

TEST(SymmetryTrace, OneLevelIsAVerticalTraceThroughItAndNoneIsAnError) {
  const SymmetryTrace trace = consensus_trace({{40, 97}}, 3.0, kMaxSlope);
  EXPECT_EQ(trace.at(0), 97);
  EXPECT_EQ(trace.slope, 0);
  EXPECT_THROW(consensus_trace({}, 3.0, kMaxSlope), std::invalid_argument);
}

}  // namespace
}  // namespace facehex
