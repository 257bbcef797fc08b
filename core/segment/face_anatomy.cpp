#include "core/segment/face_anatomy.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include "core/segment/symmetry_trace.h"
#include "core/segment/tragus.h"
#include "core/util/error.h"
#include "core/util/mirror_symmetry.h"

namespace facehex {
namespace {

constexpr double kShoulderWidth = 1.3;    // head sections wider than this times the head's are shoulders
constexpr double kSymmetryReach = 45.0;   // mm either side of the mid-plane compared for symmetry
constexpr double kSymmetrySearch = 30.0;  // mm either side of the head's mean x searched for the plane
constexpr double kProfileBand = 2.0;      // mm either side of the mid-plane for the skin profile
constexpr double kChinHalfWidth = 6.0;    // mm either side of the mid-plane for the chin's bone
constexpr double kApertureHeight = 6.0;   // mm: a run of levels this tall without bone near the skin is the nose's
constexpr double kChinSoftTissue = 25.0;  // mm: bone this close behind the skin is near it (chin, not nose)
constexpr double kChinGap = 8.0;          // mm of levels without such bone within the chin's run (lips apart)
constexpr double kChinDepth = 30.0;       // mm the mandible's lower border reaches back from the chin's front
constexpr double kMaxRoll = 25.0;         // degrees a head tilts towards a shoulder in a scanner, at most
constexpr double kLevelAgreement = 3.0;   // mm: a level whose mirror centre lies this close to the trace agrees
// A trace leaning more than this is measured again across the leaning plane (across_leaning_plane), within
// kLeaningRowSearch of it.
constexpr double kLeaningRowsMinRoll = 5.0;     // degrees
constexpr double kLeaningRowSearch = 10.0;      // mm
constexpr int kLeaningRowPasses = 3;            // at most, each across the trace the last one gave
constexpr double kLeaningRowSettled = 0.1;      // degrees: a pass that turns the trace less ends them
constexpr double kLeaningRowSupport = 2.0 / 3;  // of the levels agreeing with the trace across the rows
constexpr double kMaxTurn = 40.0;               // degrees a head is looked for turned about the vertical axis
constexpr double kTurnSampling = 2.0;           // mm between the head voxels compared for the turn
constexpr double kMirrorSampling = 4.0;         // mm between the head voxels compared for the 3D mirror plane
constexpr double kMirrorOffsetSearch = 6.0;     // mm either side of their centroid searched for the plane
// The auricle is thin: the opening of the body removes it. Where the body stands out of its opening sideways by at
// least kEarStandOut (more than the opening's rounding of the skin), over levels at least kEarMinHeight tall in one
// coronal row (the auricle's front edge is taller; a skin fold or a strap's edge is not), the row holds the ear.
constexpr double kEarStandOut = 3.0;           // mm
constexpr double kEarMinHeight = 10.0;         // mm
constexpr double kEarReachTolerance = 3.0;     // mm: without an auricle, rows reaching this close to the widest
constexpr double kBrowReach[2] = {3.0, 30.0};  // mm above the nasion where the brow is looked for
// A head, an infant's included, is wider and deeper than this, and its nose tip stands at least this far in front of
// its nasion or of the mean of its cheeks kCheekOffset to either side (a nose clipped by the field of view still stands
// out of one of them); a box or a small phantom is neither.
constexpr double kMinHeadSize = 80.0;   // mm
constexpr double kMinNoseRelief = 4.0;  // mm
// mm from the nose tip (pronasale) down to the chin's lowest bone (menton): adults' lie within about 60 to 100, and a
// chin that the scan's first slice cuts, or a nose its field of view clips, shortens or lengthens it by a little.
constexpr double kNoseToChin[2] = {30.0, 115.0};
constexpr double kCheekOffset = 40.0;  // mm from the mid-sagittal plane
// Rule 3b: the forehead's front is read this far either side of the mid-plane (about the inner eye corners' span
// and more, where a scan's tilted end crosses the forehead first).
constexpr double kForeheadHalfWidth = 25.0;  // mm

const double kNone = std::numeric_limits<double>::quiet_NaN();

std::string point_text(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

[[noreturn]] void not_found(const std::string& what, const std::string& options) {
  throw Error("segment", "cannot find " + what + " in the CT; check --skin, --anterior and --superior, or place the " +
                             "cuts with " + options);
}

// The options that place every cut by hand, so that no anatomy is looked for.
const char* const kAllCutOptions = "--top-cut, --bottom-cut, --posterior-cut and --mid-plane";

[[noreturn]] void not_a_head(const std::string& why) {
  throw Error("segment", "not a plausible head: " + why + "; if it is one, place the cuts with " + kAllCutOptions);
}

std::string mm(double x) {
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << x << " mm";
  return s.str();
}

}  // namespace

void check_head_size(const Mask& head) {
  const GridGeometry& g = head.geometry;
  const auto [lo, hi] = occupied_box(head);
  const double width = (hi[0] - lo[0]) * g.spacing.x(), depth = (hi[1] - lo[1]) * g.spacing.y();
  if (!(width >= kMinHeadSize && depth >= kMinHeadSize))
    throw Error("segment", "not a plausible head: the body found is " + mm(width) + " wide and " + mm(depth) +
                               " deep, a head at least " + mm(kMinHeadSize) + " both ways");
}

namespace {

// The head masks' sections, one pass: per slice the x extent, per column (i, k) the most anterior voxel's y.
struct Sections {
  const GridGeometry& g;
  std::vector<double> width;  // per slice, mm; -1 where empty
  std::vector<double> front;  // per (i, k), x fastest; NaN where the column is empty

  explicit Sections(const Mask& head) : g(head.geometry) {
    width.assign(g.dims[2], -1);
    front.assign(static_cast<size_t>(g.dims[0]) * g.dims[2], kNone);
    for (int k = 0; k < g.dims[2]; ++k) {
      int first = g.dims[0], last = -1;
      for (int j = 0; j < g.dims[1]; ++j)
        for (int i = 0; i < g.dims[0]; ++i)
          if (head(i, j, k)) {
            first = std::min(first, i), last = std::max(last, i);
            front[at(i, k)] = g.point(i, j, k).y();  // j ascends: the last one is the most anterior
          }
      if (last >= 0) width[k] = (last - first + 1) * g.spacing.x();
    }
  }
  size_t at(int i, int k) const { return static_cast<size_t>(i) + static_cast<size_t>(g.dims[0]) * k; }
};

// The slices above the highest one in the lower half that is wider than the shoulder bound, and the lowest non-empty
// slice: lowest head level, highest level, lowest level.
std::array<int, 3> head_levels(const Sections& s) {
  int top = -1, bottom = -1;
  for (int k = s.g.dims[2] - 1; k >= 0 && top < 0; --k)
    if (s.width[k] > 0) top = k;
  for (int k = 0; k < s.g.dims[2] && bottom < 0; ++k)
    if (s.width[k] > 0) bottom = k;
  if (top < 0) throw Error("segment", "the head mask is empty");
  std::vector<double> upper;
  for (int k = (top + bottom) / 2; k <= top; ++k)
    if (s.width[k] > 0) upper.push_back(s.width[k]);
  std::nth_element(upper.begin(), upper.begin() + upper.size() / 2, upper.end());
  const double bound = kShoulderWidth * upper[upper.size() / 2];
  int lowest = bottom;
  for (int k = bottom; k <= (bottom + top) / 2; ++k)
    if (s.width[k] > bound) lowest = k + 1;
  return {lowest, top, bottom};
}

// Rule 2 on one slice: its mirror centre.
std::optional<LevelCentre> slice_symmetry(const Sections& s, int k, double x0) {
  std::vector<double> front(s.g.dims[0]);
  for (int i = 0; i < s.g.dims[0]; ++i) front[i] = s.front[s.at(i, k)];
  const std::optional<double> c =
      mirror_centre(front, s.g.origin.x(), s.g.spacing.x(), x0, kSymmetrySearch, kSymmetryReach);
  if (!c) return std::nullopt;
  return LevelCentre{s.g.point(0, 0, k).z(), *c};
}

// Rule 2 on a head that leans: a horizontal level cuts its two sides at different heights, which moves the level's
// mirror centre off the plane, so each level is measured again on the row across the leaning plane through its
// centre (perpendicular to the trace in x-z; the plane's mirror image keeps such a row), the front interpolated
// between the columns and slices; the centre found there is a point of the plane. Nothing where a row leaves the
// head.
std::vector<LevelCentre> across_leaning_plane(const Sections& s, const std::vector<LevelCentre>& levels,
                                              const FaceAnatomy& anatomy) {
  const GridGeometry& g = s.g;
  const double h = g.spacing.x(), norm = std::hypot(1.0, anatomy.roll_slope);
  const Eigen::Vector2d across(1 / norm, -anatomy.roll_slope / norm);  // (x, z)
  const double reach = kLeaningRowSearch + kSymmetryReach + 2 * h;
  const int n = 2 * static_cast<int>(std::ceil(reach / h)) + 1;
  const auto front_at = [&](double x, double z) {
    const double ti = (x - g.origin.x()) / h, tk = (z - g.origin.z()) / g.spacing.z();
    const int i = static_cast<int>(std::floor(ti)), k = static_cast<int>(std::floor(tk));
    if (i < 0 || k < 0 || i + 1 >= g.dims[0] || k + 1 >= g.dims[2]) return kNone;
    const double fi = ti - i, fk = tk - k;
    return (1 - fk) * ((1 - fi) * s.front[s.at(i, k)] + fi * s.front[s.at(i + 1, k)]) +
           fk * ((1 - fi) * s.front[s.at(i, k + 1)] + fi * s.front[s.at(i + 1, k + 1)]);  // NaN if one is
  };
  std::vector<LevelCentre> out;
  std::vector<double> row(static_cast<size_t>(n));
  for (const LevelCentre& level : levels) {
    const Eigen::Vector2d centre(anatomy.centre_at(level.z), level.z);
    const double first = -(n / 2) * h;
    for (int m = 0; m < n; ++m) {
      const Eigen::Vector2d p = centre + (first + m * h) * across;
      row[static_cast<size_t>(m)] = front_at(p.x(), p.y());
    }
    if (const auto t = mirror_centre(row, first, h, 0.0, kLeaningRowSearch, kSymmetryReach)) {
      const Eigen::Vector2d p = centre + *t * across;
      out.push_back(LevelCentre{p.y(), p.x()});
    }
  }
  return out;
}

// Rule 2's trace through the levels' centres (symmetry_trace.h).
void fit_plane(const std::vector<LevelCentre>& levels, FaceAnatomy& anatomy) {
  const SymmetryTrace trace = consensus_trace(levels, kLevelAgreement, std::tan(kMaxRoll * M_PI / 180));
  anatomy.roll_z = trace.z0, anatomy.centre_x = trace.c0, anatomy.roll_slope = trace.slope;
  anatomy.roll_degrees = std::atan(anatomy.roll_slope) * 180 / M_PI;
  anatomy.roll_support = static_cast<double>(trace.agreeing.size()) / static_cast<double>(levels.size());
}

// Rule 3: the mid-sagittal skin profile, one point per head level (NaN y where the band is empty).
struct Profile {
  std::vector<Eigen::Vector3d> points;  // per slice index

  Profile(const Mask& head, const FaceAnatomy& anatomy, int lowest, int top) {
    const GridGeometry& g = head.geometry;
    points.assign(g.dims[2], Eigen::Vector3d::Constant(kNone));
    for (int k = lowest; k <= top; ++k) {
      const double z = g.point(0, 0, k).z(), c = anatomy.centre_at(z);
      for (int j = g.dims[1] - 1; j >= 0 && std::isnan(points[k].y()); --j)
        for (int i = 0; i < g.dims[0]; ++i)
          if (head(i, j, k) && std::abs(g.point(i, j, k).x() - c) <= kProfileBand) {
            points[k] = Eigen::Vector3d(c, g.point(i, j, k).y(), z);
            break;
          }
    }
  }
  // The most (max) or least anterior point with z in [lo, hi]; among ties within `tie` mm, the middle one.
  std::optional<Eigen::Vector3d> extreme(double lo, double hi, bool max, double tie) const {
    std::optional<double> best;
    for (const auto& p : points)
      if (!std::isnan(p.y()) && p.z() >= lo && p.z() <= hi && (!best || (max ? p.y() > *best : p.y() < *best)))
        best = p.y();
    if (!best) return std::nullopt;
    std::vector<const Eigen::Vector3d*> ties;
    for (const auto& p : points)
      if (!std::isnan(p.y()) && p.z() >= lo && p.z() <= hi && std::abs(p.y() - *best) <= tie) ties.push_back(&p);
    return *ties[ties.size() / 2];
  }
  // The least anterior point with z in [lo, hi] that has a point at least as anterior `reach` mm above it (a hollow
  // below a brow, not the head's top receding); among ties within `tie` mm, the middle one.
  std::optional<Eigen::Vector3d> hollow(double lo, double hi, const double (&reach)[2], double tie) const {
    std::vector<const Eigen::Vector3d*> candidates;
    for (const auto& p : points) {
      if (std::isnan(p.y()) || p.z() < lo || p.z() > hi) continue;
      const auto above = extreme(p.z() + reach[0], p.z() + reach[1], true, 0.0);
      if (above && above->y() >= p.y()) candidates.push_back(&p);
    }
    if (candidates.empty()) return std::nullopt;
    double best = candidates.front()->y();
    for (const auto* p : candidates) best = std::min(best, p->y());
    std::vector<const Eigen::Vector3d*> ties;
    for (const auto* p : candidates)
      if (p->y() - best <= tie) ties.push_back(p);
    return *ties[ties.size() / 2];
  }
};

// Rule 4: the bony chin below the pronasale.
void find_chin(const Mask& bone, const Profile& profile, int lowest, FaceAnatomy& anatomy) {
  const GridGeometry& g = bone.geometry;
  // Most anterior bone voxel near the mid-plane in slice k, as a voxel index.
  auto bone_front = [&](int k) -> std::optional<std::array<int, 3>> {
    const double c = anatomy.centre_at(g.point(0, 0, k).z());
    for (int j = g.dims[1] - 1; j >= 0; --j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (bone(i, j, k) && std::abs(g.point(i, j, k).x() - c) <= kChinHalfWidth) return std::array<int, 3>{i, j, k};
    return std::nullopt;
  };
  auto near_skin = [&](int k) -> std::optional<std::array<int, 3>> {
    const auto b = bone_front(k);
    if (!b || std::isnan(profile.points[k].y())) return std::nullopt;
    if (profile.points[k].y() - g.point(b->at(0), b->at(1), k).y() > kChinSoftTissue) return std::nullopt;
    return b;
  };
  const double start_z = anatomy.pronasale.z() - 30;
  int k = static_cast<int>(std::floor((start_z - g.origin.z()) / g.spacing.z()));
  k = std::min(k, g.dims[2] - 1);
  // Runs of levels with bone near the skin, joined over gaps of at most kChinGap; the chin's is the tallest (the
  // upper teeth and the maxilla's alveolar bone, near the lips, make a shorter run above it when the lips are apart
  // further than the gap).
  const int gap = static_cast<int>(std::ceil(kChinGap / g.spacing.z()));
  std::optional<std::array<int, 3>> chin;  // the bone at the tallest run's lowest level
  int chin_height = -1, run_top = -1;
  std::array<int, 3> run_last{};
  auto close_run = [&] {
    if (run_top >= 0 && run_top - run_last[2] >= chin_height) {
      chin_height = run_top - run_last[2];
      chin = run_last;
    }
    run_top = -1;
  };
  for (; k >= lowest; --k) {
    const auto b = near_skin(k);
    if (!b) continue;
    if (run_top >= 0 && run_last[2] - k > gap) close_run();
    if (run_top < 0) run_top = k;
    run_last = *b;
  }
  close_run();
  if (!chin) not_found("the chin's bone below the nose", "--bottom-cut");
  const std::array<int, 3> last = *chin;
  // Flood down and back from the run's lowest bone within the mid-plane band.
  const double y_min = g.point(0, last[1], 0).y() - kChinDepth;
  std::vector<std::uint8_t> seen(g.size(), 0);
  std::vector<std::array<int, 3>> stack = {last};
  seen[g.index(last[0], last[1], last[2])] = 1;
  // The lowest level's voxel nearest the mid-plane (then the most anterior): a chin whose lowest level is broad, or
  // that the scan's first slice cuts, has many voxels there, and the menton is the midline's.
  std::array<int, 3> lowest_bone = last;
  const auto off_plane = [&](const std::array<int, 3>& v) {
    const Eigen::Vector3d p = g.point(v[0], v[1], v[2]);
    return std::abs(p.x() - anatomy.centre_at(p.z()));
  };
  const auto lower = [&](const std::array<int, 3>& a, const std::array<int, 3>& b) {
    if (a[2] != b[2]) return a[2] < b[2];
    if (off_plane(a) != off_plane(b)) return off_plane(a) < off_plane(b);
    return a[1] != b[1] ? a[1] > b[1] : a[0] < b[0];
  };
  while (!stack.empty()) {
    const std::array<int, 3> v = stack.back();
    stack.pop_back();
    if (lower(v, lowest_bone)) lowest_bone = v;
    for (int axis = 0; axis < 3; ++axis)
      for (int d : {-1, 1}) {
        std::array<int, 3> n = v;
        n[axis] += d;
        if (!g.contains(n[0], n[1], n[2]) || n[2] > last[2] || seen[g.index(n[0], n[1], n[2])] ||
            !bone(n[0], n[1], n[2]))
          continue;
        const Eigen::Vector3d p = g.point(n[0], n[1], n[2]);
        if (p.y() < y_min || std::abs(p.x() - anatomy.centre_at(p.z())) > kChinHalfWidth) continue;
        seen[g.index(n[0], n[1], n[2])] = 1;
        stack.push_back(n);
      }
  }
  anatomy.menton = g.point(lowest_bone[0], lowest_bone[1], lowest_bone[2]);
}

// Rule 5: the front of the ears.
void find_ear_front(const Mask& head, const Mask& without_ears, FaceAnatomy& anatomy) {
  const GridGeometry& g = head.geometry;
  const double z_lo = anatomy.pronasale.z() - 25, z_hi = anatomy.glabella.z();
  double y_front = -std::numeric_limits<double>::infinity(), y_back = -y_front;
  for (int k = 0; k < g.dims[2]; ++k) {
    const double z = g.point(0, 0, k).z();
    if (z < z_lo || z > z_hi) continue;
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (head(i, j, k))
          y_front = std::max(y_front, g.point(i, j, k).y()), y_back = std::min(y_back, g.point(i, j, k).y());
  }
  if (!(y_front > y_back)) not_found("the ears", "--posterior-cut");
  const double depth = y_front - y_back;
  // Per side and coronal row: the height of the levels over which the head stands out of the head without its ears
  // (a head turned about the vertical axis has one ear further forward than the other), and how far the head reaches
  // from the mid-sagittal plane.
  std::array<std::vector<double>, 2> ear_height, reach;
  ear_height.fill(std::vector<double>(g.dims[1], 0.0));
  reach.fill(std::vector<double>(g.dims[1], -1.0));
  const auto ends = [&](const Mask& m, int j, int k) {
    std::pair<int, int> e(-1, -1);
    for (int i = 0; i < g.dims[0]; ++i)
      if (m(i, j, k)) {
        if (e.first < 0) e.first = i;
        e.second = i;
      }
    return e;
  };
  for (int j = 0; j < g.dims[1]; ++j) {
    const double y = g.point(0, j, 0).y();
    if (y < y_back + 0.25 * depth || y > y_front - 0.25 * depth) continue;
    for (int k = 0; k < g.dims[2]; ++k) {
      const double z = g.point(0, 0, k).z();
      if (z < z_lo || z > z_hi) continue;
      const auto [first, last] = ends(head, j, k);
      if (first < 0) continue;
      const double centre = anatomy.centre_at(z);
      reach[0][j] = std::max(reach[0][j], centre - g.point(first, 0, 0).x());
      reach[1][j] = std::max(reach[1][j], g.point(last, 0, 0).x() - centre);
      const auto [inner_first, inner_last] = ends(without_ears, j, k);
      if (inner_first < 0) continue;
      if ((inner_first - first) * g.spacing.x() >= kEarStandOut) ear_height[0][j] += g.spacing.z();
      if ((last - inner_last) * g.spacing.x() >= kEarStandOut) ear_height[1][j] += g.spacing.z();
    }
  }
  // Each ear's front, and the more anterior of the two: the posterior cut goes in front of both.
  for (int s = 0; s < 2; ++s)
    for (int j = 0; j < g.dims[1]; ++j)
      if (ear_height[s][j] >= kEarMinHeight - 1e-9)
        anatomy.ear_fronts_y[s] = std::max(anatomy.ear_fronts_y[s], g.point(0, j, 0).y());
  anatomy.ear_front_y = std::max(anatomy.ear_fronts_y[0], anatomy.ear_fronts_y[1]);
  if (std::isfinite(anatomy.ear_front_y)) return;
  // No auricle stands out (outside the field of view, or pressed flat by a support): each side's front of the rows
  // that reach within kEarReachTolerance of its widest, where the ears would be.
  anatomy.ears_estimated = true;
  for (int s = 0; s < 2; ++s) {
    const double widest = *std::max_element(reach[s].begin(), reach[s].end());
    if (!(widest > 0)) continue;
    for (int j = 0; j < g.dims[1]; ++j)
      if (reach[s][j] >= widest - kEarReachTolerance)
        anatomy.ear_fronts_y[s] = std::max(anatomy.ear_fronts_y[s], g.point(0, j, 0).y());
  }
  anatomy.ear_front_y = std::max(anatomy.ear_fronts_y[0], anatomy.ear_fronts_y[1]);
  if (!std::isfinite(anatomy.ear_front_y)) not_found("the ears", "--posterior-cut");
}

// Rule 3b: the forehead's end, looked for from height `from` up to slice `top`. The front is compared across a rise of
// kScanEndRise (two slices at least), since a slice's front moves by whole voxels.
double forehead_end(const Sections& s, const FaceAnatomy& anatomy, double from, int top) {
  const GridGeometry& g = s.g;
  const int first = std::max(0, static_cast<int>(std::ceil((from - g.origin.z()) / g.spacing.z())));
  const int rise = std::max(2, static_cast<int>(std::ceil(kScanEndRise / g.spacing.z())));
  const double recession = kScanEndSlope * rise * g.spacing.z();
  std::vector<double> ends;  // per column
  for (int i = 0; i < g.dims[0]; ++i) {
    if (std::abs(g.point(i, 0, 0).x() - anatomy.centre_at(from)) > kForeheadHalfWidth) continue;
    const auto front = [&](int k) { return s.front[s.at(i, k)]; };
    if (std::isnan(front(first))) continue;
    ends.push_back(std::numeric_limits<double>::infinity());
    for (int k = first + 1; k <= top; ++k) {
      const int base = std::max(first, k - rise);
      if (!std::isnan(front(k)) && !(front(base) - front(k) >= recession)) continue;
      // The front is whole up to the last level within a voxel of the base's.
      int whole = k - 1;
      while (whole > base && !(front(whole) >= front(base) - g.spacing.y())) --whole;
      ends.back() = g.point(0, 0, whole).z();
      break;
    }
  }
  if (ends.empty()) return std::numeric_limits<double>::infinity();
  const auto quarter = ends.begin() + static_cast<long>(ends.size() / 4);
  std::nth_element(ends.begin(), quarter, ends.end());
  return *quarter;
}

// The head's mirror plane in 3D (rules 0 and 2): the turn about the vertical axis and the roll towards a shoulder
// (degrees, as FaceAnatomy::roll_degrees) at which the most head voxels of the levels [lowest, top], sampled every
// kMirrorSampling mm, have their mirror image in the head too; the plane passes within kMirrorOffsetSearch of their
// centroid. Searched every 2 degrees over the turn's and the roll's ranges, then every 0.5 and 0.1 degree around the
// best.
struct MirrorPlane {
  double turn = 0, roll = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // mm, on the plane
};

MirrorPlane find_mirror_plane(const Mask& head, int lowest, int top) {
  const GridGeometry& g = head.geometry;
  const auto every = [&](int axis) {
    return std::max(1, static_cast<int>(std::lround(kMirrorSampling / g.spacing(axis))));
  };
  // The samples as voxel indices, the centroid in mm.
  std::vector<Eigen::Vector3d> samples;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int k = lowest; k <= top; k += every(2))
    for (int j = 0; j < g.dims[1]; j += every(1))
      for (int i = 0; i < g.dims[0]; i += every(0))
        if (head(i, j, k)) samples.emplace_back(i, j, k), centroid += g.point(i, j, k);
  centroid /= static_cast<double>(samples.size());
  // The face looks to (sin t, cos t, 0); the plane's normal is (cos t, -sin t, 0) rolled about that direction, so
  // that the plane's trace on a coronal plane leans towards +x going up for a positive roll.
  const auto normal = [](const MirrorPlane& plane) {
    const double t = plane.turn * M_PI / 180, r = plane.roll * M_PI / 180;
    return Eigen::Vector3d(std::cos(r) * std::cos(t), -std::cos(r) * std::sin(t), -std::sin(r));
  };
  // The mirror image of a voxel, in voxel indices, is an affine map of its indices: the reflection through the plane
  // conjugated by the grid's scaling, so that each sample costs a matrix-vector product and a lookup.
  const Eigen::Vector3d upper(g.dims[0] - 0.5, g.dims[1] - 0.5, g.dims[2] - 0.5);
  // The head as one bit per voxel: the lookups, scattered over the head, then mostly hit the cache.
  std::vector<std::uint64_t> bits((g.size() + 63) / 64, 0);
  for (size_t v = 0; v < g.size(); ++v)
    if (head.data[v]) bits[v / 64] |= std::uint64_t{1} << (v % 64);
  const auto in_head = [&](int i, int j, int k) {
    const size_t v = g.index(i, j, k);
    return static_cast<std::ptrdiff_t>((bits[v / 64] >> (v % 64)) & 1);
  };
  const auto symmetry = [&](const MirrorPlane& plane, double offset) {
    const Eigen::Vector3d n = normal(plane);
    const Eigen::Vector3d c = centroid + offset * n;
    const Eigen::Matrix3d reflect = Eigen::Matrix3d::Identity() - 2 * n * n.transpose();
    const Eigen::Matrix3d a = g.spacing.cwiseInverse().asDiagonal() * reflect * g.spacing.asDiagonal();
    const Eigen::Vector3d b = (reflect * g.origin + 2 * c.dot(n) * n - g.origin).cwiseQuotient(g.spacing);
    std::ptrdiff_t hits = 0;
    for (const Eigen::Vector3d& s : samples) {
      const Eigen::Vector3d ijk = a * s + b;
      // Rounded to the nearest voxel (halves away from zero) once known to be inside the grid.
      if (!(ijk.x() > -0.5 && ijk.y() > -0.5 && ijk.z() > -0.5 && ijk.x() < upper.x() && ijk.y() < upper.y() &&
            ijk.z() < upper.z()))
        continue;
      hits +=
          in_head(static_cast<int>(ijk.x() + 0.5), static_cast<int>(ijk.y() + 0.5), static_cast<int>(ijk.z() + 0.5));
    }
    return hits;
  };
  // The candidates of one search are scored in one parallel loop (a parallel region per candidate would cost more
  // in waking threads than it saves); the first of the best, in the order listed, is taken.
  const auto best_of = [&](const std::vector<MirrorPlane>& planes, const std::vector<double>& offsets) {
    std::vector<std::ptrdiff_t> hits(planes.size());
    const auto count = static_cast<std::ptrdiff_t>(planes.size());
#pragma omp parallel for schedule(dynamic)
    for (std::ptrdiff_t c = 0; c < count; ++c)
      hits[static_cast<size_t>(c)] = symmetry(planes[static_cast<size_t>(c)], offsets[static_cast<size_t>(c)]);
    return static_cast<size_t>(std::max_element(hits.begin(), hits.end()) - hits.begin());
  };
  double offset = 0;
  const auto search = [&](double turn_from, double turn_to, double roll_from, double roll_to, double step) {
    std::vector<MirrorPlane> planes;
    for (double t = turn_from; t <= turn_to + 1e-9; t += step)
      for (double r = roll_from; r <= roll_to + 1e-9; r += step) planes.push_back({t, r});
    return planes[best_of(planes, std::vector<double>(planes.size(), offset))];
  };
  MirrorPlane best = search(-kMaxTurn, kMaxTurn, -kMaxRoll, kMaxRoll, 2.0);
  std::vector<double> offsets;
  for (double d = -kMirrorOffsetSearch; d <= kMirrorOffsetSearch + 1e-9; d += 1.0) offsets.push_back(d);
  offset = offsets[best_of(std::vector<MirrorPlane>(offsets.size(), best), offsets)];
  for (const double step : {0.5, 0.1}) {
    const MirrorPlane around = best;
    best = search(around.turn - 4 * step, around.turn + 4 * step, around.roll - 4 * step, around.roll + 4 * step, step);
  }
  best.point = centroid + offset * normal(best);
  return best;
}

}  // namespace

HeadTurn find_head_turn(const Mask& head) {
  const GridGeometry& g = head.geometry;
  const Sections sections(head);
  const auto [lowest, top, bottom] = head_levels(sections);
  // Head voxels every kTurnSampling mm of each level, with the level's centroid.
  struct Level {
    int k = 0;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    std::vector<Eigen::Vector2d> points;
  };
  const auto every = [&](int axis) {
    return std::max(1, static_cast<int>(std::lround(kTurnSampling / g.spacing(axis))));
  };
  std::vector<Level> levels;
  Eigen::Vector2d axis = Eigen::Vector2d::Zero();
  size_t count = 0;
  for (int k = lowest; k <= top; k += every(2)) {
    Level level;
    level.k = k;
    for (int j = 0; j < g.dims[1]; j += every(1))
      for (int i = 0; i < g.dims[0]; i += every(0))
        if (head(i, j, k)) level.points.push_back(g.point(i, j, k).head<2>());
    if (level.points.empty()) continue;
    for (const auto& p : level.points) level.centroid += p;
    axis += level.centroid;
    count += level.points.size();
    level.centroid /= static_cast<double>(level.points.size());
    levels.push_back(std::move(level));
  }
  HeadTurn turn;
  turn.axis = axis / static_cast<double>(count);
  // The fraction of the samples whose mirror image about the line through their level's centroid along
  // (sin t, cos t) is in the head too.
  const auto symmetry = [&](double degrees) {
    const double a = degrees * M_PI / 180;
    const Eigen::Vector2d normal(std::cos(a), -std::sin(a));
    const double upper_i = g.dims[0] - 0.5, upper_j = g.dims[1] - 0.5;
    size_t hits = 0;
    for (const Level& level : levels)
      for (const auto& p : level.points) {
        const Eigen::Vector2d q = p - 2 * (p - level.centroid).dot(normal) * normal;
        const double i = (q.x() - g.origin.x()) / g.spacing.x(), j = (q.y() - g.origin.y()) / g.spacing.y();
        // Rounded to the nearest voxel (halves away from zero) once known to be inside the grid.
        if (i > -0.5 && j > -0.5 && i < upper_i && j < upper_j)
          hits += head(static_cast<int>(i + 0.5), static_cast<int>(j + 0.5), level.k) != 0;
      }
    return static_cast<double>(hits) / static_cast<double>(count);
  };
  const auto best_of = [&](double from, double to, double step) {
    double best = from, best_score = -1;
    for (double t = from; t <= to + 1e-9; t += step)
      if (const double score = symmetry(t); score > best_score + 1e-12) best = t, best_score = score;
    return best;
  };
  const double coarse = best_of(-kMaxTurn, kMaxTurn, 1.0);
  turn.degrees = best_of(coarse - 1.0, coarse + 1.0, 0.1);
  // A head tilted towards a shoulder cuts each horizontal section's two sides at different heights, which turns its
  // sections' mirror lines with the tilt: its turn is the 3D mirror plane's.
  if (const MirrorPlane plane = find_mirror_plane(head, lowest, top); std::abs(plane.roll) > kLeaningRowsMinRoll)
    turn.degrees = plane.turn;
  return turn;
}

double FaceAnatomy::centre_at(double z) const { return centre_x + roll_slope * (z - roll_z); }

FaceAnatomy find_face_anatomy(const Mask& head, const Mask& without_ears, const Mask& bone) {
  const GridGeometry& g = head.geometry;
  const Sections sections(head);
  const auto [lowest, top, bottom] = head_levels(sections);
  FaceAnatomy anatomy;
  anatomy.lowest_head_z = g.point(0, 0, lowest).z();

  double x_sum = 0, count = 0;
  for (int k = lowest; k <= top; ++k)
    for (int i = 0; i < g.dims[0]; ++i)
      if (!std::isnan(sections.front[sections.at(i, k)])) x_sum += g.point(i, 0, 0).x(), count += 1;
  const double x0 = x_sum / count;
  std::vector<LevelCentre> slices;
  const int stride = std::max(1, static_cast<int>(std::lround(2.0 / g.spacing.z())));  // every 2 mm is plenty
  for (int k = lowest; k <= top; k += stride)
    if (const auto s = slice_symmetry(sections, k, x0)) slices.push_back(*s);
  if (slices.size() < 3) not_found("the face's mirror symmetry", "--mid-plane");
  fit_plane(slices, anatomy);
  // Rows across a leaning plane are measured again across the trace they give, until its lean settles. The passes
  // start from the level trace when it leans, and from the head's 3D mirror plane when that leans (the levels of a
  // tilted head whose front the field of view cuts can agree on a wrong trace). The trace the most levels agree with
  // is taken when that is most of them (a lean few levels agree with is a misreading, as on a scan that holds only the
  // front half of the head); else the best of the passes from the 3D plane, the head's symmetry as a whole deciding
  // its lean where its levels do not.
  const auto leans = [](double roll) { return std::abs(roll) > kLeaningRowsMinRoll && std::abs(roll) <= kMaxRoll; };
  const auto best_pass = [&](FaceAnatomy pass) {
    FaceAnatomy best = pass;
    best.roll_support = 0;
    for (int k = 0; k < kLeaningRowPasses; ++k) {
      const double before = pass.roll_degrees;
      const std::vector<LevelCentre> across = across_leaning_plane(sections, slices, pass);
      if (across.size() < 3) break;
      fit_plane(across, pass);
      if (pass.roll_support > best.roll_support) best = pass;
      if (std::abs(pass.roll_degrees - before) < kLeaningRowSettled) break;
    }
    return best;
  };
  std::optional<FaceAnatomy> from_levels, from_mirror;
  if (leans(anatomy.roll_degrees)) from_levels = best_pass(anatomy);
  const MirrorPlane mirror = find_mirror_plane(head, lowest, top);
  if (leans(mirror.roll)) {
    FaceAnatomy start = anatomy;
    start.roll_degrees = mirror.roll;
    start.roll_slope = std::tan(mirror.roll * M_PI / 180);
    start.roll_z = mirror.point.z(), start.centre_x = mirror.point.x();
    from_mirror = best_pass(start);
  }
  const auto support = [](const std::optional<FaceAnatomy>& a) { return a ? a->roll_support : 0.0; };
  const std::optional<FaceAnatomy>& best = support(from_mirror) > support(from_levels) ? from_mirror : from_levels;
  if (support(best) >= kLeaningRowSupport)
    anatomy = *best;
  else if (support(from_mirror) > 0)
    anatomy = *from_mirror;
  if (leans(mirror.roll)) anatomy.mirror_roll_degrees = mirror.roll;
  if (std::abs(anatomy.roll_degrees) > kMaxRoll) {
    std::ostringstream why;
    why.precision(1);
    why << std::fixed << "the face's mirror symmetry gives a mid-sagittal plane leaning "
        << std::abs(anatomy.roll_degrees) << " degrees, beyond the " << kMaxRoll
        << " a head tilts in a scanner (a head turned far about the vertical axis misleads it)";
    throw Error("segment", why.str() + "; place the cuts with " + kAllCutOptions);
  }

  const Profile profile(head, anatomy, bottom, top);
  const double z_lo = g.point(0, 0, lowest).z(), z_hi = g.point(0, 0, top).z(), tie = 0.5 * g.spacing.y();
  // The nose stands in front of the nasal aperture: the highest run of head levels where the mid-plane's bone lies
  // far behind the skin. A field of view that cuts the face flat can leave the forehead as far forward as the nose.
  const Profile bone_profile(bone, anatomy, bottom, top);
  std::optional<std::pair<double, double>> aperture;
  // A run must have bone near the skin right above it (the nasal bones) and right below it (the maxilla): the scalp
  // above the skull's vertex and the neck below the chin have none on one side.
  bool bone_above = false;
  for (int k = top, run_top = -1; k >= lowest && !aperture; --k) {
    const double skin = profile.points[k].y(), behind = skin - bone_profile.points[k].y();
    const bool open = !std::isnan(skin) && !(behind <= kChinSoftTissue), bone = !std::isnan(skin) && !open;
    if (open && run_top == -1) run_top = bone_above ? k : -2;
    if (!open) {
      if (bone && run_top >= 0 && (run_top - k - 1) * g.spacing.z() >= kApertureHeight)
        aperture = {g.point(0, 0, k + 1).z(), g.point(0, 0, run_top).z()};
      run_top = -1;
    }
    bone_above = bone;
  }
  const auto prn =
      aperture ? profile.extreme(aperture->first, aperture->second, true, tie) : profile.extreme(z_lo, z_hi, true, tie);
  if (!prn) not_found("the face's profile", "--top-cut, --bottom-cut and --posterior-cut");
  anatomy.pronasale = *prn;
  // A front plateau longer than a nose's tip: the field of view cut it.
  const auto front_run = [&] {
    double lo = prn->z(), hi = prn->z();
    for (const auto& p : profile.points)
      if (!std::isnan(p.y()) && p.y() >= prn->y() - tie) lo = std::min(lo, p.z()), hi = std::max(hi, p.z());
    return hi - lo;
  }();
  anatomy.nose_clipped = front_run > 10.0;
  const auto hollow = profile.hollow(prn->z() + 15, prn->z() + 50, kBrowReach, tie);
  anatomy.brow_unseen = !hollow;
  const Eigen::Vector3d* n = hollow ? &*hollow : &*prn;
  anatomy.nasion = *n;
  // The front of the head at the cheeks, level with the nose: the mean of the two sides, since a head turned about
  // the vertical axis brings one cheek as far forward as the other goes back (an empty column is no obstacle).
  double cheeks_sum = 0;
  int cheeks_found = 0;
  const int k = static_cast<int>(std::lround((prn->z() - g.origin.z()) / g.spacing.z()));
  for (const double side : {-1.0, 1.0}) {
    const int i = static_cast<int>(
        std::lround((anatomy.centre_at(prn->z()) + side * kCheekOffset - g.origin.x()) / g.spacing.x()));
    if (i >= 0 && i < g.dims[0] && !std::isnan(sections.front[sections.at(i, k)]))
      cheeks_sum += sections.front[sections.at(i, k)], ++cheeks_found;
  }
  const double cheeks = cheeks_found > 0 ? cheeks_sum / cheeks_found : -std::numeric_limits<double>::infinity();
  const double relief = std::max(hollow ? prn->y() - n->y() : 0.0, prn->y() - cheeks);
  if (!(relief >= kMinNoseRelief))
    not_a_head("no nose stands out of the profile (its most anterior point is " + mm(relief) +
               " in front of the nasion and the cheeks, a face's at least " + mm(kMinNoseRelief) + ")");
  anatomy.glabella = hollow ? *profile.extreme(n->z() + kBrowReach[0], n->z() + kBrowReach[1], true, tie)
                            : *profile.extreme(prn->z(), z_hi, true, tie);
  anatomy.highest_head_z = z_hi;
  anatomy.forehead_end_z = forehead_end(sections, anatomy, anatomy.brow_unseen ? prn->z() + 15 : n->z(), top);
  find_chin(bone, profile, bottom, anatomy);
  // A profile read off the face (a head frame turned far from the head's, a misread plane) can show a "nose" and a
  // "chin" that stand out enough but lie at no face's distance apart.
  const double nose_to_chin = anatomy.pronasale.z() - anatomy.menton.z();
  if (!(nose_to_chin >= kNoseToChin[0] && nose_to_chin <= kNoseToChin[1]))
    not_a_head("the nose tip found (z " + mm(anatomy.pronasale.z()) + ") lies " + mm(nose_to_chin) +
               " above the chin's lowest bone (z " + mm(anatomy.menton.z()) + "), a face's " + mm(kNoseToChin[0]) +
               " to " + mm(kNoseToChin[1]));
  find_ear_front(head, without_ears, anatomy);
  anatomy.tragi = find_tragi(head, anatomy);
  return anatomy;
}

std::string face_anatomy_text(const FaceAnatomy& a) {
  const auto ear = [&](int side) {
    std::ostringstream y;
    y.precision(1);
    y << std::fixed << a.ear_fronts_y[side];
    return std::isfinite(a.ear_fronts_y[side]) ? y.str() : std::string("unseen");
  };
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << "mid-sagittal plane x " << a.centre_x << " (roll " << a.roll_degrees << " deg); pronasale "
    << point_text(a.pronasale) << (a.nose_clipped ? " (nose clipped)" : "")
    << (a.brow_unseen ? "" : ", nasion " + point_text(a.nasion)) << ", glabella " << point_text(a.glabella)
    << (a.glabella_under_object ? " (on the skin under the object lying on it)" : "")
    << (a.brow_unseen ? " (estimated: the profile shows no nasion below a brow, the top cut is the head's top)" : "")
    << ", menton " << point_text(a.menton) << ", front of the ears y " << a.ear_front_y << " (-x ear " << ear(0)
    << ", +x ear " << ear(1)
    << (a.ears_estimated ? "; estimated: no auricle stands out, the front of the widest rows" : "") << ")";
  for (int side = 0; side < 2; ++side)
    s << ", " << kTragusNames[side] << " "
      << (a.tragi[side] ? point_text(a.tragi[side]->point) + (a.tragi[side]->estimated ? " (estimated)" : "")
                        : std::string("unseen"));
  if (a.lowest_head_z > -std::numeric_limits<double>::infinity()) s << ", head sections above z " << a.lowest_head_z;
  if (std::isfinite(a.forehead_end_z)) s << ", the forehead's front whole up to z " << a.forehead_end_z;
  return s.str();
}

}  // namespace facehex
