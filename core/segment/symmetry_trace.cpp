#include "core/segment/symmetry_trace.h"

#include <cmath>
#include <stdexcept>

namespace facehex {
namespace {

// A line c(z) = c + slope (z - z) through the level (z, c).
struct Line {
  double z = 0, c = 0, slope = 0;
};

// The levels within `agreement` of a line, and their squared distances from it.
struct Agreement {
  std::vector<int> levels;
  double squares = 0;
};

Agreement agreeing_levels(const std::vector<LevelCentre>& levels, const Line& line, double agreement) {
  Agreement a;
  for (size_t i = 0; i < levels.size(); ++i) {
    const double off = levels[i].c - (line.c + line.slope * (levels[i].z - line.z));
    if (std::abs(off) <= agreement) {
      a.levels.push_back(static_cast<int>(i));
      a.squares += off * off;
    }
  }
  return a;
}

// The least-squares line through the levels `use` (at least one).
SymmetryTrace least_squares(const std::vector<LevelCentre>& levels, const std::vector<int>& use) {
  SymmetryTrace trace;
  trace.agreeing = use;
  for (int i : use) trace.z0 += levels[i].z, trace.c0 += levels[i].c;
  trace.z0 /= use.size();
  trace.c0 /= use.size();
  double szz = 0, szc = 0;
  for (int i : use) {
    szz += (levels[i].z - trace.z0) * (levels[i].z - trace.z0);
    szc += (levels[i].z - trace.z0) * (levels[i].c - trace.c0);
  }
  trace.slope = szz > 0 ? szc / szz : 0;
  return trace;
}

}  // namespace

SymmetryTrace consensus_trace(const std::vector<LevelCentre>& levels, double agreement, double max_slope) {
  if (levels.empty()) throw std::invalid_argument("consensus_trace: no levels");
  Line best_line;
  Agreement best;
  const auto consider = [&](const Line& line) {
    if (!(std::abs(line.slope) <= max_slope)) return;
    Agreement a = agreeing_levels(levels, line, agreement);
    if (a.levels.size() > best.levels.size() || (a.levels.size() == best.levels.size() && a.squares < best.squares)) {
      best = std::move(a);
      best_line = line;
    }
  };
  const size_t n = levels.size();
  for (size_t i = 0; i < n; ++i) {
    consider({levels[i].z, levels[i].c, 0});
    for (size_t j = i + 1; j < n; ++j)
      if (levels[j].z != levels[i].z)
        consider({levels[i].z, levels[i].c, (levels[j].c - levels[i].c) / (levels[j].z - levels[i].z)});
  }
  const SymmetryTrace face = least_squares(levels, agreeing_levels(levels, best_line, 2 * agreement).levels);
  const std::vector<int> near = agreeing_levels(levels, {face.z0, face.c0, face.slope}, agreement).levels;
  return near.size() >= 3 ? least_squares(levels, near) : face;
}

}  // namespace facehex
