#include "core/segment/symmetry_trace.h"

#include <cmath>
#include <stdexcept>

namespace facehex {
namespace {

// The levels within `agreement` of the line through (z, c) with that slope, and their squared distances from it.
struct Agreement {
  std::vector<int> levels;
  double squares = 0;
};

Agreement agreeing_levels(const std::vector<LevelCentre>& levels, double z, double c, double slope, double agreement) {
  Agreement a;
  for (size_t i = 0; i < levels.size(); ++i) {
    const double off = levels[i].c - (c + slope * (levels[i].z - z));
    if (std::abs(off) <= agreement) {
      a.levels.push_back(static_cast<int>(i));
      a.squares += off * off;
    }
  }
  return a;
}

}  // namespace

SymmetryTrace consensus_trace(const std::vector<LevelCentre>& levels, double agreement, double max_slope) {
  if (levels.empty()) throw std::invalid_argument("consensus_trace: no levels");
  Agreement best;
  const auto consider = [&](double z, double c, double slope) {
    if (!(std::abs(slope) <= max_slope)) return;
    Agreement a = agreeing_levels(levels, z, c, slope, agreement);
    if (a.levels.size() > best.levels.size() || (a.levels.size() == best.levels.size() && a.squares < best.squares))
      best = std::move(a);
  };
  const size_t n = levels.size();
  for (size_t i = 0; i < n; ++i) {
    consider(levels[i].z, levels[i].c, 0);
    for (size_t j = i + 1; j < n; ++j)
      if (levels[j].z != levels[i].z)
        consider(levels[i].z, levels[i].c, (levels[j].c - levels[i].c) / (levels[j].z - levels[i].z));
  }
  SymmetryTrace trace;
  trace.agreeing = best.levels;
  for (int i : trace.agreeing) trace.z0 += levels[i].z, trace.c0 += levels[i].c;
  trace.z0 /= trace.agreeing.size();
  trace.c0 /= trace.agreeing.size();
  double szz = 0, szc = 0;
  for (int i : trace.agreeing) {
    szz += (levels[i].z - trace.z0) * (levels[i].z - trace.z0);
    szc += (levels[i].z - trace.z0) * (levels[i].c - trace.c0);
  }
  trace.slope = szz > 0 ? szc / szz : 0;
  return trace;
}

}  // namespace facehex
