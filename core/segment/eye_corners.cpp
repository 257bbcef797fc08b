#include "core/segment/eye_corners.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <vector>

#include "core/mesh/head_turn.h"
#include "core/segment/face_front.h"

namespace facehex {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Rule 1: the front of the face.
constexpr double kFieldHalfWidth = 64;  // mm either side of the plane: past the widest adult exocanthion and the track
constexpr double kBelow = 30;           // mm below the nasion: the lowest level of the slit's line
constexpr double kAbove = 10;           // mm above the nasion: the highest
constexpr double kFieldMargin = 6;      // mm the front reaches beyond those levels (the chord and the floor's window)
constexpr double kRayFront = 10;        // mm in front of the pronasale where the rays start
constexpr double kRayBack = 60;         // mm behind the nasion where they give up
// Rule 2: the notch and the slit's line.
constexpr double kChord = 3;       // mm: half the chord the notch depth is measured against
constexpr double kSeedInner = 26;  // mm out: the seed's columns, on the lids between the nose and the corner
constexpr double kSeedOuter = 34;
constexpr double kSeedLowest = 15;  // mm below the nasion: the seed's lowest level (the nasion's height the highest)
constexpr double kSeedColumn = 30;  // mm out: the column the line is followed from
constexpr int kReach = 1;           // mm in z the line may move between neighbouring columns
constexpr double kOuter = 60;       // mm out: the outer line's end
constexpr double kInner = 5;        // mm out: the inner line's end
// Rule 3: the slit seen.
constexpr double kNarrowChord = 1.5;   // mm: the closed slit is 1 to 2 mm tall; wider chords see the lids' folds
constexpr double kMinSlitDepth = 1.5;  // mm: walls steeper than 45 degrees on average
constexpr double kExoInner = 35;       // mm out: the exocanthion's window (a biocular width of 70 to 104 mm)
constexpr double kExoOuter = 52;
// Rule 4: the slit's end.
constexpr double kFloorBand = 2;  // mm either side of the line's height where the floor is looked for
constexpr double kPitRise = 0.3;  // mm the floor rises beyond the slit's end (above a CT's noise on the front)
constexpr double kPitReach = 3;   // mm outwards within which it does
// mm: depths this close to the pit's bottom are its bottom (the front's grid)
constexpr double kBottomTolerance = 0.25;
constexpr double kLidsNear = 3;  // mm above and below the line from which the lids' skin is read (past the slit)
constexpr double kLidsFar = 6;   // mm above and below the line up to which it is (short of the brow and the cheek)
// Rule 5: the nose's side.
constexpr double kWallSlope = 1;  // mm of y per mm inwards: steeper than 45 degrees
// The farthest out an inner end is, in the fraction of its side's exocanthion's offset: adults' intercanthal width is
// about a third of their biocular width, and more than two fifths only where the eyes are set far apart.
constexpr double kMaxEndoFraction = 0.45;
// Rule 6: the floor's height.
constexpr double kRefine = 4;            // mm either side of the line's height
constexpr double kFloorTolerance = 0.1;  // mm behind the rearmost y
// Rule 7: adult proportions (Farkas): a biocular width of about 92 mm, an intercanthal width of about 30 % of it,
// and a canthal tilt of about 4 degrees.
constexpr double kEstimatedExoOffset = 46;
constexpr double kEstimatedExoDrop = 7.5;  // mm below the nasion when no line was followed
constexpr double kEstimatedEndoFraction = 0.30;
constexpr double kCanthalDrop = 2;

// The index of the largest non-NaN value of v[lo..hi] (the first of equals), or none.
std::optional<int> largest_index(const std::vector<double>& v, int lo, int hi) {
  std::optional<int> best;
  for (int i = lo; i <= hi; ++i)
    if (!std::isnan(v[i]) && (!best || v[i] > v[*best])) best = i;
  return best;
}

// A running mean of 3, the values beyond the ends taken as 0 (numpy's "same" convolution).
std::vector<double> running_mean3(const std::vector<double>& v) {
  std::vector<double> out(v.size());
  for (size_t i = 0; i < v.size(); ++i)
    out[i] = ((i > 0 ? v[i - 1] : 0) + v[i] + (i + 1 < v.size() ? v[i + 1] : 0)) / 3;
  return out;
}

struct LinePoint {
  double offset, z, y;
};

double interpolate_z(const std::vector<LinePoint>& line, double offset) {
  if (offset <= line.front().offset) return line.front().z;
  for (size_t i = 1; i < line.size(); ++i)
    if (offset <= line[i].offset) {
      const double t = (offset - line[i - 1].offset) / (line[i].offset - line[i - 1].offset);
      return line[i - 1].z + t * (line[i].z - line[i - 1].z);
    }
  return line.back().z;
}

// One side's slit, in the head frame: side -1 the right eye (-x), +1 the left.
class Slit {
 public:
  // lean: the plane's dx/dz in the head frame. A head tilted towards a shoulder has its eye line across the plane, not
  // level: the slit's levels are heights on the line through the nasion across the plane, `offset` mm out lying
  // rise(offset) above the nasion's level.
  Slit(const FaceFront& front, double centre, double nasion_z, double lean, int side)
      : front_(front), centre_(centre), nasion_z_(nasion_z), rise_per_mm_(-lean * side), side_(side) {
    for (double z = nasion_z - kBelow; z <= nasion_z + kAbove + 1e-9; z += 1) levels_.push_back(z);
  }

  // Rules 2-7.
  std::array<std::optional<CtLandmark>, 2> corners() {
    const std::optional<int> seed = seed_level();
    std::vector<LinePoint> outer, inner;
    if (seed) {
      outer = follow(*seed, kOuter);
      inner = follow(*seed, kInner);
    }
    const bool seen = !outer.empty() && slit_seen(outer);
    std::optional<CtLandmark> exo = seen ? slit_end(outer) : std::nullopt;
    if (!exo) {
      // The line, when followed, follows the lids' folds; without them it wanders, and is held to the seed's levels.
      const double z = outer.empty()
                           ? nasion_z_ - kEstimatedExoDrop
                           : std::clamp(interpolate_z(outer, kEstimatedExoOffset), nasion_z_ - kSeedLowest, nasion_z_);
      exo = on_front(kEstimatedExoOffset, z, true);
    }
    std::optional<CtLandmark> endo = seen ? nose_side(inner) : std::nullopt;
    // An inner end further out than an adult's is where the line lost the slit on its way in (on thick slices the
    // notch's height jumps between columns), not the corner: estimated, at the slit's height where it was lost.
    std::optional<double> lost_level;
    if (endo && exo) {
      const double endo_offset = std::abs(endo->point.x() - centre_);
      if (endo_offset > kMaxEndoFraction * std::abs(exo->point.x() - centre_)) {
        lost_level = endo->point.z() - rise(endo_offset);
        endo.reset();
      }
    }
    if (!endo && exo) {
      const double exo_offset = std::abs(exo->point.x() - centre_);
      endo = on_front(kEstimatedEndoFraction * exo_offset,
                      lost_level ? *lost_level : exo->point.z() - rise(exo_offset) - kCanthalDrop, true);
    }
    return {endo, exo};
  }

 private:
  double x_at(double offset) const { return centre_ + side_ * offset; }
  double rise(double offset) const { return rise_per_mm_ * offset; }
  // The front `offset` mm out at the slit's level z.
  double front(double offset, double z) const { return front_(x_at(offset), z + rise(offset)); }

  std::optional<CtLandmark> on_front(double offset, double z, bool estimated) const {
    const double y = front(offset, z);
    if (std::isnan(y)) return std::nullopt;
    return CtLandmark{Eigen::Vector3d(x_at(offset), y, z + rise(offset)), estimated};
  }

  // The notch depth at each level of the column `offset` mm out (a whole number), averaged over the columns 1 mm
  // either side.
  const std::vector<double>& notch(int offset) {
    auto [at, fresh] = notch_.try_emplace(offset);
    if (!fresh) return at->second;
    std::vector<double>& mean = at->second;
    mean.assign(levels_.size(), 0.0);
    for (int column = offset - 1; column <= offset + 1; ++column)
      for (size_t j = 0; j < levels_.size(); ++j) {
        const double z = levels_[j];
        mean[j] += ((front(column, z + kChord) + front(column, z - kChord)) / 2 - front(column, z)) / 3;
      }
    return mean;
  }

  // The level (index into levels_) the line starts from in the column kSeedColumn out.
  std::optional<int> seed_level() {
    const int n = static_cast<int>(levels_.size());
    std::vector<double> mean(levels_.size(), kNaN);
    for (int j = 0; j < n; ++j) {
      if (levels_[j] < nasion_z_ - kSeedLowest - 1e-9 || levels_[j] > nasion_z_ + 1e-9) continue;
      double sum = 0;
      int count = 0;
      for (int offset = static_cast<int>(kSeedInner); offset <= static_cast<int>(kSeedOuter); ++offset)
        if (!std::isnan(notch(offset)[j])) {
          sum += notch(offset)[j];
          ++count;
        }
      if (count > 0) mean[j] = sum / count;
    }
    const std::optional<int> best = largest_index(mean, 0, n - 1);
    if (!best) return std::nullopt;
    const int lo = std::max(*best - 2, 1), hi = std::min(*best + 2, n - 2);
    return largest_index(notch(static_cast<int>(kSeedColumn)), lo, hi).value_or(*best);
  }

  // The deepest notch followed from kSeedColumn to `end` mm out, column by column.
  std::vector<LinePoint> follow(int level, double end) {
    const int n = static_cast<int>(levels_.size());
    const int step = end > kSeedColumn ? 1 : -1;
    std::vector<LinePoint> line;
    int j = level;
    for (int offset = static_cast<int>(kSeedColumn); (end - offset) * step >= 0; offset += step) {
      const std::vector<double>& d = notch(offset);
      const int lo = std::max(j - kReach, 1), hi = std::min(j + kReach, n - 2);
      const std::optional<int> deepest = largest_index(d, lo, hi);
      if (!deepest) break;
      j = *deepest;
      // The notch's peak between the levels, from the parabola through three.
      double dz = 0;
      if (!std::isnan(d[j - 1]) && !std::isnan(d[j + 1])) {
        const double curvature = d[j - 1] - 2 * d[j] + d[j + 1];
        if (curvature < 0) dz = std::clamp(0.5 * (d[j - 1] - d[j + 1]) / curvature, -0.5, 0.5);
      }
      const double z = levels_[j] + dz;
      line.push_back({static_cast<double>(offset), z, front(offset, z)});
    }
    return line;
  }

  bool slit_seen(const std::vector<LinePoint>& outer) const {
    std::vector<double> depth;
    for (const LinePoint& p : outer) {
      const double d =
          (front(p.offset, p.z + kNarrowChord) + front(p.offset, p.z - kNarrowChord)) / 2 - front(p.offset, p.z);
      depth.push_back(std::isnan(d) ? 0.0 : d);
    }
    const std::vector<double> mean = running_mean3(depth);
    for (size_t i = 0; i < outer.size(); ++i)
      if (outer[i].offset >= kExoInner && outer[i].offset <= kExoOuter && mean[i] >= kMinSlitDepth) return true;
    return false;
  }

  // Rule 6, at the slit's levels.
  double floor_height(double offset, double z) const {
    std::vector<double> zs, ys;
    for (double dz = -kRefine; dz <= kRefine + 1e-9; dz += 0.5) {
      zs.push_back(z + dz);
      ys.push_back(front(offset, z + dz));
      if (std::isnan(ys.back())) return z;
    }
    const int n = static_cast<int>(ys.size());
    const int rear = static_cast<int>(std::min_element(ys.begin(), ys.end()) - ys.begin());
    int a = rear, b = rear;
    while (a > 0 && ys[a - 1] <= ys[rear] + kFloorTolerance) --a;
    while (b < n - 1 && ys[b + 1] <= ys[rear] + kFloorTolerance) ++b;
    if (a == 0 || b == n - 1) return z;
    return 0.5 * (zs[a] + zs[b]);
  }

  // Rule 4.
  std::optional<CtLandmark> slit_end(const std::vector<LinePoint>& outer) const {
    std::vector<double> offsets, floor, floor_z;
    for (double offset = kExoInner; offset <= std::min(kExoOuter + kPitReach, outer.back().offset) + 1e-9;
         offset += 0.5) {
      const double z = interpolate_z(outer, offset);
      double rear = kNaN, rear_z = z;
      for (double dz = -kFloorBand; dz <= kFloorBand + 1e-9; dz += 0.25) {
        const double y = front(offset, z + dz);
        if (!std::isnan(y) && (std::isnan(rear) || y < rear)) {
          rear = y;
          rear_z = z + dz;
        }
      }
      double lids = 0;
      int count = 0;
      for (double d = kLidsNear; d <= kLidsFar + 1e-9; d += 0.5)
        for (const double y : {front(offset, z + d), front(offset, z - d)})
          if (!std::isnan(y)) lids += y, ++count;
      offsets.push_back(offset);
      floor.push_back(count > 0 ? rear - lids / count : kNaN);
      floor_z.push_back(rear_z);
    }
    const int n = static_cast<int>(offsets.size());
    if (n < 3) return std::nullopt;
    std::vector<double> smooth = running_mean3(floor);
    smooth.front() = floor.front();
    smooth.back() = floor.back();
    const int reach = static_cast<int>(std::lround(kPitReach / 0.5));
    // Whether the floor rises by kPitRise within kPitReach beyond `from`, where it is defined throughout.
    const auto rises_beyond = [&](int from) {
      double highest = -std::numeric_limits<double>::infinity();
      for (int r = from; r <= std::min(from + reach, n - 1); ++r) {
        if (std::isnan(smooth[r])) return false;
        highest = std::max(highest, smooth[r]);
      }
      return highest - smooth[from] >= kPitRise;
    };
    for (int i = 1; i < n - 1; ++i) {
      if (offsets[i] > kExoOuter) break;
      if (!(smooth[i] <= smooth[i - 1] && smooth[i] <= smooth[i + 1])) continue;
      // The pit's bottom: the deepest point within kPitReach (a slit deepening outwards by less than the front's grid
      // shows the first of its steps as a minimum of its own), moved out while the next point is as deep within the
      // front's grid.
      int bottom = i;
      for (int r = i + 1; r <= std::min(i + reach, n - 1) && offsets[r] <= kExoOuter; ++r)
        if (smooth[r] <= smooth[bottom]) bottom = r;
      while (bottom + 1 < n && offsets[bottom + 1] <= kExoOuter &&
             smooth[bottom + 1] <= smooth[bottom] + kBottomTolerance)
        ++bottom;
      // The rise is looked for beyond the bottom as well: a slit growing shallower outwards has its last minimum
      // further in than kPitReach from the step where it ends.
      if (!rises_beyond(i) && !rises_beyond(bottom)) continue;
      return on_front(offsets[bottom], floor_height(offsets[bottom], floor_z[bottom]), false);
    }
    return std::nullopt;
  }

  // Rule 5.
  std::optional<CtLandmark> nose_side(const std::vector<LinePoint>& inner) const {
    for (size_t i = 1; i < inner.size(); ++i)
      if (inner[i].y - inner[i - 1].y > kWallSlope * std::abs(inner[i].offset - inner[i - 1].offset) ||
          std::abs(inner[i].z - inner[i - 1].z) >= kReach - 1e-6)
        return on_front(inner[i - 1].offset, floor_height(inner[i - 1].offset, inner[i - 1].z), false);
    return std::nullopt;
  }

  const FaceFront& front_;
  double centre_, nasion_z_, rise_per_mm_;
  int side_;
  std::vector<double> levels_;                // mm: the levels the line moves on, 1 mm apart
  std::map<int, std::vector<double>> notch_;  // by column offset
};

}  // namespace

EyeCorners find_eye_corners(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                            const Eigen::Vector3d& nasion, const Eigen::Vector3d& pronasale) {
  const HeadTurn frame = head_turn_of(plane);
  const Eigen::Vector3d n = frame.to_head(nasion), tip = frame.to_head(pronasale);
  const MidSagittalPlane head_plane = frame.to_head(plane);
  const double centre = head_plane.x_at(n.y(), n.z());
  const double tilt = std::abs(head_plane.slope) * kFieldHalfWidth;  // the most a slit's levels rise or fall
  const FaceFront front(ct, skin_threshold, frame, centre - kFieldHalfWidth, centre + kFieldHalfWidth,
                        n.z() - kBelow - kFieldMargin - tilt, n.z() + kAbove + kFieldMargin + tilt, tip.y() + kRayFront,
                        n.y() - kRayBack);
  EyeCorners corners;
  for (const int side : {-1, 1}) {
    const auto [endo, exo] = Slit(front, centre, n.z(), head_plane.slope, side).corners();
    const int first = side < 0 ? 0 : 2;  // kEyeCornerNames: right, then left
    for (const auto& [at, corner] : {std::pair{first, endo}, std::pair{first + 1, exo}})
      if (corner) corners[at] = CtLandmark{frame.to_model(corner->point), corner->estimated};
  }
  return corners;
}

}  // namespace facehex
