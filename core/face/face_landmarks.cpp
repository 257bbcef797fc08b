#include "core/face/face_landmarks.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

#include "core/face/millimetre_bins.h"
#include "core/face/mouth_corners.h"
#include "core/mesh/head_turn.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/mesh/sides.h"
#include "core/mesh/skin_points.h"
#include "core/util/error.h"
#include "core/util/mirror_symmetry.h"

namespace facehex {
namespace {

// Most anterior skin point per 1 mm bin of z near the mid-sagittal plane.
struct Profile {
  double z0 = 0;
  std::vector<std::optional<Eigen::Vector3d>> bins;

  // The most (max = true) or least anterior point with z in [lo, hi].
  std::optional<Eigen::Vector3d> extreme(double lo, double hi, bool max) const {
    std::optional<Eigen::Vector3d> best;
    for (size_t b = 0; b < bins.size(); ++b) {
      const double z = z0 + static_cast<double>(b) + 0.5;
      if (z < lo || z > hi || !bins[b]) continue;
      if (!best || (max ? bins[b]->y() > best->y() : bins[b]->y() < best->y())) best = bins[b];
    }
    return best;
  }

  // The middle (in z) of the bins with z in [lo, hi] within `tie` mm of the most (max) or least anterior one: a flat
  // brow's centre, a flat nasion's.
  std::optional<Eigen::Vector3d> middle_of_extreme(double lo, double hi, bool max, double tie) const {
    const std::optional<Eigen::Vector3d> best = extreme(lo, hi, max);
    if (!best) return best;
    double first = best->z(), last = best->z();
    for (const auto& bin : bins)
      if (bin && bin->z() >= lo && bin->z() <= hi && std::abs(bin->y() - best->y()) <= tie)
        first = std::min(first, bin->z()), last = std::max(last, bin->z());
    const double mid = 0.5 * (first + last);
    for (double reach = 0.5; reach <= 0.5 * (last - first) + 0.5; reach += 1)  // the nearest bin holding a point
      if (const auto p = extreme(mid - reach, mid + reach, max)) return p;
    return best;
  }

  // Going up from lo, the height of the first bin at least `rise` mm in front of the deepest bin between lo and it:
  // where the profile comes forward again (the brow above the nasion), or none up to hi.
  std::optional<double> first_rise_above(double lo, double hi, double rise) const {
    std::optional<double> deepest;
    for (size_t b = 0; b < bins.size(); ++b) {
      const double z = z0 + static_cast<double>(b) + 0.5;
      if (z < lo || z > hi || !bins[b]) continue;
      if (deepest && bins[b]->y() >= *deepest + rise) return z;
      if (!deepest || bins[b]->y() < *deepest) deepest = bins[b]->y();
    }
    return std::nullopt;
  }

  // Going down from z, the first bin that is the least anterior within 2 mm either side (a local minimum), within
  // `reach` mm.
  std::optional<Eigen::Vector3d> next_minimum_below(double z, double reach) const {
    for (double at = z - 1; at >= z - reach; at -= 1) {
      const std::optional<Eigen::Vector3d> here = extreme(at - 0.5, at + 0.5, false);
      const std::optional<Eigen::Vector3d> around = extreme(at - 2.5, at + 2.5, false);
      if (here && around && here->y() <= around->y()) return here;
    }
    return std::nullopt;
  }

  // Going down from z (within `reach` mm), the profile's turns, alternately hollows and prominences: the bins that
  // the Douglas-Peucker simplification of the profile keeps at `tolerance` mm, each a hollow if it lies behind the
  // chord of its kept neighbours, else a prominence; consecutive turns of one kind keep the deepest (most anterior).
  // Measured against chords rather than as extremes of the depth, they stay where they are on a head that is pitched
  // and on a face whose proportions differ from the usual.
  struct Turn {
    Eigen::Vector3d point;
    bool hollow;
  };
  std::vector<Turn> turns_below(double z, double reach, double tolerance) const {
    std::vector<Eigen::Vector3d> points;
    for (int b = static_cast<int>(std::floor(z - z0)); b >= 0 && z0 + b + 0.5 >= z - reach; --b)
      if (b < static_cast<int>(bins.size()) && bins[b] && bins[b]->z() <= z) points.push_back(*bins[b]);
    std::vector<int> kept = {0};
    if (points.size() >= 2) {
      simplify(points, 0, static_cast<int>(points.size()) - 1, tolerance, kept);
      kept.push_back(static_cast<int>(points.size()) - 1);
    }
    std::vector<Turn> turns;
    for (size_t i = 1; i + 1 < kept.size(); ++i) {
      const Eigen::Vector3d &p = points[kept[i]], &a = points[kept[i - 1]], &c = points[kept[i + 1]];
      const double chord_y = a.y() + (p.z() - a.z()) / (c.z() - a.z()) * (c.y() - a.y());
      const Turn turn{p, p.y() < chord_y};
      if (!turns.empty() && turns.back().hollow == turn.hollow) {
        if (turn.hollow ? p.y() < turns.back().point.y() : p.y() > turns.back().point.y()) turns.back() = turn;
      } else {
        turns.push_back(turn);
      }
    }
    return turns;
  }

  // Douglas-Peucker in the (z, y) plane: the indices strictly between first and last that are further than
  // tolerance from the chord, and recursively so, in order.
  static void simplify(const std::vector<Eigen::Vector3d>& points, int first, int last, double tolerance,
                       std::vector<int>& kept) {
    const Eigen::Vector2d a = points[first].tail<2>(), chord = (points[last].tail<2>() - a).normalized();
    int farthest = -1;
    double distance = tolerance;
    for (int i = first + 1; i < last; ++i) {
      const Eigen::Vector2d d = points[i].tail<2>() - a;
      const double off = std::abs(chord.x() * d.y() - chord.y() * d.x());
      if (off > distance) distance = off, farthest = i;
    }
    if (farthest < 0) return;
    simplify(points, first, farthest, tolerance, kept);
    kept.push_back(farthest);
    simplify(points, farthest, last, tolerance, kept);
  }

  // A field-of-view cut's front as the profile shows it: the line through (z, y) rising `slope` mm in y per mm in z,
  // upright where the scan's edge is level with the head frame, leaning where a pitch (or a warp) leans it.
  struct FrontLine {
    double z = 0, y = 0, slope = 0;
    double y_at(double at) const { return y + slope * (at - z); }
  };

  // The longest run of bins at most `depth` mm behind `line` (one bin behind it allowed), as (lowest z, highest z),
  // if it is at least `min_length` mm long: a flat plateau where the scan's field of view cut the face. Empty bins
  // neither end nor extend a run: they lie between the mesh's vertices, several in a row where its edges are long.
  std::optional<std::pair<double, double>> run_behind(const FrontLine& line, double depth, double min_length) const {
    std::optional<std::pair<double, double>> best;
    bool in_run = false;
    std::pair<double, double> run{0.0, 0.0};
    int gap = 0;
    for (size_t b = 0; b < bins.size(); ++b) {
      if (!bins[b]) continue;
      const double z = z0 + static_cast<double>(b) + 0.5;
      if (bins[b]->y() >= line.y_at(bins[b]->z()) - depth) {
        run = in_run ? std::pair{run.first, z} : std::pair{z, z};
        in_run = true;
        gap = 0;
      } else if (in_run && ++gap > 1) {
        in_run = false;  // a second bin behind the plateau
      }
      if (in_run && (!best || run.second - run.first > best->second - best->first)) best = run;
    }
    if (best && best->second - best->first >= min_length) return best;
    return std::nullopt;
  }

  // The least-squares line through the bins with z in [lo, hi], moved forward onto the most anterior of them; none
  // for fewer than two bins.
  std::optional<FrontLine> fitted_front(double lo, double hi) const {
    double n = 0, sz = 0, sy = 0, szz = 0, szy = 0;
    for (const auto& bin : bins)
      if (bin && bin->z() >= lo && bin->z() <= hi)
        n += 1, sz += bin->z(), sy += bin->y(), szz += bin->z() * bin->z(), szy += bin->z() * bin->y();
    const double spread = n * szz - sz * sz;
    if (n < 2 || spread <= 0) return std::nullopt;
    FrontLine line{sz / n, sy / n, (n * szy - sz * sy) / spread};
    double ahead = -std::numeric_limits<double>::infinity();
    for (const auto& bin : bins)
      if (bin && bin->z() >= lo && bin->z() <= hi) ahead = std::max(ahead, bin->y() - line.y_at(bin->z()));
    line.y += ahead;
    return line;
  }

  // True if, going down from z_top to z_bottom, the profile comes forward again by more than `rise` mm after
  // receding: a hollow and a bump (the subnasale and an upper lip), not a nose's underside, which only recedes.
  bool comes_forward_below(double z_top, double z_bottom, double rise) const {
    double deepest = std::numeric_limits<double>::infinity();
    for (size_t b = bins.size(); b-- > 0;) {
      const double z = z0 + static_cast<double>(b) + 0.5;
      if (z > z_top || z < z_bottom || !bins[b]) continue;
      deepest = std::min(deepest, bins[b]->y());
      if (bins[b]->y() > deepest + rise) return true;
    }
    return false;
  }
};

Profile skin_profile(const Eigen::MatrixXd& V, const std::vector<int>& skin, const MidSagittalPlane& plane,
                     double band) {
  Profile p;
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (int v : skin) {
    zmin = std::min(zmin, V(v, 2));
    zmax = std::max(zmax, V(v, 2));
  }
  p.z0 = std::floor(zmin);
  p.bins.resize(static_cast<size_t>(std::ceil(zmax) - p.z0) + 1);
  for (int v : skin) {
    const double x = plane.x_at(V(v, 1), V(v, 2));
    if (std::abs(V(v, 0) - x) > band) continue;
    auto& bin = p.bins[static_cast<size_t>(millimetre_bin(V(v, 2) - p.z0))];
    if (!bin || V(v, 1) > bin->y()) bin = Eigen::Vector3d(x, V(v, 1), V(v, 2));  // on the plane
  }
  return p;
}

// The profile under objects lying on the skin (core/mesh/ct_landmarks.h, SkinObject): over the z range of the skin
// the CT shows under each, that skin, moved by the offset between it and the skin read at the range's ends (linear
// between them; the skin read is the segmentation's smoothed surface, a little off the CT's own). The ranges.
std::vector<std::pair<double, double>> read_under(const std::vector<SkinObject>& objects, Profile& p) {
  std::vector<std::pair<double, double>> covered;
  for (const SkinObject& o : objects) {
    const double lo = o.skin.front().x(), hi = o.skin.back().x();
    const auto under = [&](double z) {  // the CT's skin at z, linear between its points
      const auto after = std::lower_bound(o.skin.begin(), o.skin.end(), z,
                                          [](const Eigen::Vector2d& s, double at) { return s.x() < at; });
      if (after == o.skin.begin()) return after->y();
      if (after == o.skin.end()) return o.skin.back().y();
      const Eigen::Vector2d& before = *(after - 1);
      return before.y() + (after->y() - before.y()) * (z - before.x()) / (after->x() - before.x());
    };
    std::optional<Eigen::Vector3d> below, above;
    for (const auto& bin : p.bins) {
      if (bin && bin->z() < lo) below = bin;
      if (bin && bin->z() > hi && !above) above = bin;
    }
    const double offset_lo = below ? below->y() - under(lo) : 0;
    const double offset_hi = above ? above->y() - under(hi) : offset_lo;
    for (auto& bin : p.bins)
      if (bin && bin->z() >= lo && bin->z() <= hi)
        bin->y() = under(bin->z()) + offset_lo + (offset_hi - offset_lo) * (bin->z() - lo) / (hi - lo);
    covered.emplace_back(lo, hi);
  }
  return covered;
}

// The skin's mirror plane: per 2 mm row of z in [zlo, zhi], the plane x = c that best mirrors the front (the most
// anterior skin point of each 1 mm column; core/util/mirror_symmetry.h) within `reach` of it; the median of the rows'
// c. Searched within `search` of x_start, which it is when no row is wide enough.
double mirror_plane(const Eigen::MatrixXd& V, const std::vector<int>& skin, double x_start, double zlo, double zhi,
                    double reach, double search) {
  constexpr double kColumn = 1.0, kRow = 2.0, kMaxGap = 8.0;
  const double x0 = x_start - search - reach - 1;
  const int columns = static_cast<int>(2 * (search + reach + 1) / kColumn) + 1;
  const int rows = static_cast<int>((zhi - zlo) / kRow) + 1;
  std::vector<std::vector<double>> front(rows, std::vector<double>(columns, std::numeric_limits<double>::quiet_NaN()));
  for (int v : skin) {
    const int i = static_cast<int>(std::lround((V(v, 0) - x0) / kColumn)), r = static_cast<int>((V(v, 2) - zlo) / kRow);
    if (i < 0 || i >= columns || r < 0 || r >= rows || V(v, 2) < zlo) continue;
    double& d = front[r][i];
    if (std::isnan(d) || V(v, 1) > d) d = V(v, 1);
  }
  std::vector<double> centres;
  for (auto& row : front) {
    // Columns between the mesh's vertices (a few mm apart on a hex standard) are interpolated from the nearest
    // filled ones either side, so the front has no holes.
    int last = -1;
    for (int i = 0; i < columns; ++i) {
      if (std::isnan(row[i])) continue;
      if (last >= 0 && i - last > 1 && (i - last) * kColumn <= kMaxGap)
        for (int k = last + 1; k < i; ++k) row[k] = row[last] + (row[i] - row[last]) * (k - last) / (i - last);
      last = i;
    }
    if (const auto c = mirror_centre(row, x0, kColumn, x_start, search, reach)) centres.push_back(*c);
  }
  if (centres.empty()) return x_start;
  std::nth_element(centres.begin(), centres.begin() + centres.size() / 2, centres.end());
  return centres[centres.size() / 2];
}

Eigen::Vector3d require(const std::optional<Eigen::Vector3d>& p, const std::string& name) {
  if (!p)
    throw Error("landmarks", "cannot find the " + name +
                                 " on the mid-sagittal skin profile (is the face looking to +y with +z up? a CT's "
                                 "axes are set with --anterior and --superior; or give the landmarks with "
                                 "--landmarks FILE)");
  return *p;
}

// mm, the Douglas-Peucker tolerances tried for the lips, coarsest first (Profile::turns_below)
constexpr double kTurnTolerances[] = {1.5, 1.0, 0.5};
// mm below the nose within which the lips are looked for; the second reach only when the first does not show all four
// (a slanted field-of-view cut's lowest point, taken for the nose, can be well above the tip).
constexpr double kLipsReaches[] = {50.0, 65.0};
// dy/dz: a field-of-view cut leaning more than this (15 degrees) in the head frame is not followed along its lean
constexpr double kMaxCutSlope = 0.27;
// mm: a plateau followed along its lean that is not this much longer than the upright one is the same plateau, read
// again on a rough profile (a flat nose's, a coarse model's)
constexpr double kMinCutGain = 5.0;
// mm: a profile that comes this far forward again below a field-of-view cut's flat front shows the lips there
constexpr double kLipRise = 1.0;
// The share of the skin's height from its bottom where a face's nose tip never lies (a face's bottom cut below the
// chin, its top above the brow or at the crown: the tip is at a third or more of the height): only the chin or the
// lips can be the most anterior point there.
constexpr double kBelowTheNose = 0.3;
// mm from the subnasale's hollow down to the stomion's, at least (an adult's upper lip is 15-25 mm tall).
constexpr double kMinUpperLipHeight = 10.0;
// mm: an adult's nasion lies this far from the subnasale (check_plausible); the lower bound is about three standard
// deviations below adult women's mean nose height in anthropometric surveys, so that a profile read a nose too short
// (its landmarks shifted up by a field-of-view cut not recognised) is refused rather than taken.
constexpr double kNasionSubnasale[2] = {38.0, 70.0};
// mm above the nose tip: the nasion is looked for from kNasionLowest up to where the profile comes kBrowRise forward
// again above it (the brow) within kBrowReach (adults' nasion lies 30-60 mm above the tip), else up to
// kNasionHighestWithoutBrow (a model cut off below its brow, where the deepest point further up could be the cut's
// edge).
constexpr double kNasionLowest = 10.0, kBrowReach = 70.0, kNasionHighestWithoutBrow = 45.0;
// mm: more than a dorsal hump brings the profile forward going up (the dorsum slopes back towards the nasion, a hump
// only less steeply), less than a brow stands in front of the nasion.
constexpr double kBrowRise = 2.0;

// mm: profile points this close to the most or least anterior one are one flat stretch, whose middle is taken (a flat
// nasion or brow, or a field-of-view cut above the nose).
constexpr double kFlatTie = 0.5;

// mm: the face's mirror plane mirrors each row's front within this reach, searched this far either side of the nose
// tip; the mouth's own midline, within the mouth's half-width, searched this far either side of the plane.
constexpr double kFaceMirrorReach = 45.0, kFaceMirrorSearch = 30.0;
constexpr double kMouthMirrorReach = 20.0, kMouthMirrorSearch = 10.0;

// The lips' four turns on `profile` going down from the nose (the subnasale's hollow, the upper lip, the stomion and
// the lower lip; Profile::turns_below), or fewer when the profile does not show them all. Read in that order rather
// than in windows of fixed height, they follow a face whose nose or lips are longer or shorter than the usual. The
// coarsest simplification that shows the four: the lips' own turns rather than the skin's ripples, on lips as
// pronounced as the standard's and on a flat profile alike.
std::vector<Profile::Turn> lip_turns(const Profile& profile, double nose_z) {
  std::vector<Profile::Turn> turns;
  for (const double reach : kLipsReaches) {
    for (const double tolerance : kTurnTolerances) {
      turns = profile.turns_below(nose_z, reach, tolerance);
      while (!turns.empty() && !turns.front().hollow) turns.erase(turns.begin());  // on the nose's own underside
      // A ripple under the nose (a coarse scan's, or where a field-of-view cut ends) reads as a hollow and a bump
      // closer together than any upper lip is tall: the lips lie below it.
      while (turns.size() >= 4 && turns[0].point.z() - turns[2].point.z() < kMinUpperLipHeight)
        turns.erase(turns.begin(), turns.begin() + 2);
      if (turns.size() >= 4) return turns;
    }
  }
  return turns;
}

// The subnasale: the profile point between the upper lip and the nose (`nose`: its tip, or the lowest point of a
// field-of-view cut) deepest behind the chord joining them, moved up to where the columella meets the lip: the lip
// below the columella is often nearly vertical, and its top is the highest point from the deepest one up whose depth,
// averaged with its neighbours' (the profile of a 2-3 mm mesh is rough by half a millimetre), stays within
// kColumellaTie of the deepest's.
Eigen::Vector3d subnasale(const Profile& profile, const Eigen::Vector3d& ls, const Eigen::Vector3d& nose) {
  constexpr double kColumellaTie = 0.75;  // mm
  std::vector<Eigen::Vector3d> lip;       // the profile from the upper lip up to the nose
  for (const auto& bin : profile.bins)
    if (bin && bin->z() >= ls.z() && bin->z() <= nose.z()) lip.push_back(*bin);
  if (lip.empty()) require(std::nullopt, "subnasale");
  std::size_t deepest = 0;
  double depth = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < lip.size(); ++i) {
    const double t = (lip[i].z() - ls.z()) / (nose.z() - ls.z());
    const double d = ls.y() + t * (nose.y() - ls.y()) - lip[i].y();
    if (d > depth) depth = d, deepest = i;
  }
  const auto smoothed_y = [&](std::size_t i) {
    const std::size_t first = i > 0 ? i - 1 : i, last = std::min(i + 1, lip.size() - 1);
    double sum = 0;
    for (std::size_t j = first; j <= last; ++j) sum += lip[j].y();
    return sum / static_cast<double>(last - first + 1);
  };
  std::size_t top = deepest;
  while (top + 1 < lip.size() && smoothed_y(top + 1) <= smoothed_y(deepest) + kColumellaTie) ++top;
  return lip[top];
}

// mm either side of the bony menton's depth within which the skin under it is looked for (a working grid's voxel and a
// half), and the most soft tissue under an adult's chin.
constexpr double kUnderBoneColumn = 1.5;
constexpr double kMostChinTissue = 25;
// mm below the column's highest skin point within which its points belong to the same crossing of the skin.
constexpr double kCrossingBand = 3;

// The soft-tissue pogonion and menton under the lower lip (face_landmarks.h); none when the model ends above them.
// bony_menton: the chin's lowest bone, when the model's CT gave it.
void add_chin(const Profile& profile, const std::vector<int>& skin, const Eigen::MatrixXd& V,
              const std::optional<Eigen::Vector3d>& bony_menton, FaceLandmarks& l) {
  const Eigen::Vector3d li = l.points.at("labrale inferius");
  const std::optional<Eigen::Vector3d> fold = profile.next_minimum_below(li.z(), 25);
  if (!fold) return;
  const std::optional<Eigen::Vector3d> pog = profile.extreme(fold->z() - 30, fold->z() - 1, true);
  if (!pog || pog->y() <= fold->y() + 1) return;  // no chin in front of the fold: the model ends above it
  l.points["pogonion"] = *pog;
  std::optional<Eigen::Vector3d> menton;
  const auto near_plane = [&](const Eigen::Vector3d& p) { return std::abs(p.x() - l.plane.x_at(p.y(), p.z())) <= 3.0; };
  if (bony_menton) {
    // The skin where the vertical under the bony menton leaves the chin: the chin's underside is nearly level, and its
    // lowest point moves along it with any change of its slope; the bone's curve does not.
    std::vector<Eigen::Vector3d> column;
    double top = -std::numeric_limits<double>::infinity();
    for (int v : skin) {
      const Eigen::Vector3d p = V.row(v).transpose();
      if (near_plane(p) && std::abs(p.y() - bony_menton->y()) <= kUnderBoneColumn && p.z() < bony_menton->z() &&
          p.z() > bony_menton->z() - kMostChinTissue) {
        column.push_back(p);
        top = std::max(top, p.z());
      }
    }
    // Of the column's points at its first crossing of the skin, the one nearest the vertical.
    for (const Eigen::Vector3d& p : column)
      if (p.z() >= top - kCrossingBand &&
          (!menton || std::abs(p.y() - bony_menton->y()) < std::abs(menton->y() - bony_menton->y())))
        menton = p;
  }
  if (!menton)
    for (int v : skin) {
      const Eigen::Vector3d p = V.row(v).transpose();
      if (near_plane(p) && p.y() >= pog->y() - 20 && p.z() < pog->z() && (!menton || p.z() < menton->z())) menton = p;
    }
  // The chin's underside turns back towards the neck: a lowest point on the model's bottom edge is a cut, not a menton.
  double zmin = std::numeric_limits<double>::infinity();
  for (int v : skin) zmin = std::min(zmin, V(v, 2));
  if (menton && menton->z() > zmin + 2.0)
    l.points["menton"] = Eigen::Vector3d(l.plane.x_at(menton->y(), menton->z()), menton->y(), menton->z());
}

}  // namespace

LandmarkOptions landmark_options_for(const VolumeMesh& model, const std::string& source) {
  LandmarkOptions options;
  options.mid_sagittal_plane = mid_sagittal_plane(model, source);
  options.skin_points = skin_points(model, source);
  options.ct_landmarks = ct_landmarks(model, source);
  options.scan_frame = scan_frame(model, source);
  return options;
}

namespace {

// Places landmark `name` at `point`, found or estimated, in place of any placed before.
void place(FaceLandmarks& l, const std::string& name, const Eigen::Vector3d& point, bool estimated) {
  l.points[name] = point;
  l.estimated.erase(std::remove(l.estimated.begin(), l.estimated.end(), name), l.estimated.end());
  if (estimated) l.estimated.push_back(name);
}

// True when a rim named `name` (opening_name) has the width and place of an open eye or mouth: an eye 15-50 mm wide
// with its centre 10-60 mm beside the mid-sagittal plane, a mouth 25-90 mm wide centred within 10 mm of it, either
// less than 50 mm behind the pronasale. Other walls on no side (patches where a model's sides meet at its cuts) are
// not openings of the face.
bool is_face_opening(const std::string& name, const Eigen::MatrixXd& rim, const FaceLandmarks& l) {
  const Eigen::Vector3d centre = rim.colwise().mean().transpose();
  const double width = rim.col(0).maxCoeff() - rim.col(0).minCoeff(), off_plane = std::abs(centre.x() - l.plane.x);
  if (!l.points.count("pronasale") || centre.y() < l.points.at("pronasale").y() - 50) return false;
  if (name == "mouth") return width >= 25 && width <= 90 && off_plane <= 10;
  if (name == "eye at -x" || name == "eye at +x")
    return width >= 15 && width <= 50 && off_plane >= 10 && off_plane <= 60;
  return false;
}

// The corners of the open mouth and eyes among the openings (LandmarkOptions::opening_rims): of the largest rim of
// each name that is_face_opening, its skin vertices furthest towards -x and +x.
void take_opening_corners(const std::vector<Eigen::MatrixXd>& rims, FaceLandmarks& l) {
  std::map<std::string, const Eigen::MatrixXd*> largest;
  for (size_t i = 0; i < rims.size(); ++i) {
    if (rims[i].rows() == 0) continue;
    const std::string name = opening_name(rims[i].colwise().mean().transpose(), l, static_cast<int>(i));
    if (!is_face_opening(name, rims[i], l)) continue;
    if (!largest.count(name) || rims[i].rows() > largest[name]->rows()) largest[name] = &rims[i];
  }
  const auto corners = [&](const char* opening, const char* at_minus_x, const char* at_plus_x) {
    const auto rim = largest.find(opening);
    if (rim == largest.end()) return;
    Eigen::Index lo = 0, hi = 0;
    rim->second->col(0).minCoeff(&lo);
    rim->second->col(0).maxCoeff(&hi);
    place(l, at_minus_x, rim->second->row(lo).transpose(), false);
    place(l, at_plus_x, rim->second->row(hi).transpose(), false);
  };
  corners("eye at -x", "exocanthion right", "endocanthion right");
  corners("eye at +x", "endocanthion left", "exocanthion left");
  corners("mouth", "cheilion right", "cheilion left");
}

// The mouth corners (mouth_corners.h, which follows the mouth line along x) of a face whose mid-sagittal plane leans
// (a head tilted towards a shoulder tilts its mouth line with it): read on the skin turned about the front-to-back
// axis through the stomion until the plane stands upright, and turned back.
std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> mouth_corners_upright(
    const Eigen::MatrixXd& V, const std::vector<int>& skin, const MidSagittalPlane& plane,
    const Eigen::Vector3d& stomion, const Eigen::Vector3d& labrale_superius) {
  if (plane.slope == 0) return mouth_corners(V, skin, stomion.x(), stomion, labrale_superius);
  const Eigen::Matrix3d upright =
      Eigen::AngleAxisd(-std::atan(plane.slope), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const auto turned = [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return stomion + upright * (p - stomion); };
  Eigen::MatrixXd U = V;
  for (const int v : skin) U.row(v) = turned(V.row(v).transpose()).transpose();
  auto corners = mouth_corners(U, skin, stomion.x(), stomion, turned(labrale_superius));
  if (corners)
    for (Eigen::Vector3d* c : {&corners->first, &corners->second}) *c = stomion + upright.transpose() * (*c - stomion);
  return corners;
}

// The nasion over the nose tip prn: the deepest point of the profile from `lo` up to the brow (kBrowReach, kBrowRise),
// a flat hollow's middle; none where the profile has no point there.
std::optional<Eigen::Vector3d> nasion_above(const Profile& profile, double lo, const Eigen::Vector3d& prn) {
  const std::optional<double> brow = profile.first_rise_above(lo, prn.z() + kBrowReach, kBrowRise);
  return profile.middle_of_extreme(lo, brow ? *brow : prn.z() + kNasionHighestWithoutBrow, false, kFlatTie);
}

// The nose tip's first reading on a profile of skin from zmin to zmax: its most anterior point between a tenth of the
// height from either end, or above the lowest kBelowTheNose of the height when that point lies lower (a chin as far
// forward as a nose the scan's field of view clipped, or a head pitched chin-up).
std::optional<Eigen::Vector3d> nose_front(const Profile& profile, double zmin, double zmax) {
  const double height = zmax - zmin;
  const std::optional<Eigen::Vector3d> front = profile.extreme(zmin + 0.1 * height, zmax - 0.1 * height, true);
  if (front && front->z() < zmin + kBelowTheNose * height)
    return profile.extreme(zmin + kBelowTheNose * height, zmax - 0.1 * height, true);
  return front;
}

// find_face_landmarks on a model whose given plane, if any, is not turned.
FaceLandmarks find_in_head_frame(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                 const LandmarkOptions& options) {
  if (side_mask.size() != V.rows()) throw Error("landmarks", "the model has no side labels (side_mask)");
  std::vector<int> skin;
  for (int v = 0; v < V.rows(); ++v)
    if (side_mask(v) & side_bit(W1)) skin.push_back(v);
  if (skin.empty()) throw Error("landmarks", "the model has no skin side (w1)");
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, zmin = xmin, zmax = -xmin;
  for (int v : skin) {
    xmin = std::min(xmin, V(v, 0));
    xmax = std::max(xmax, V(v, 0));
    zmin = std::min(zmin, V(v, 2));
    zmax = std::max(zmax, V(v, 2));
  }
  FaceLandmarks l;
  const double height = zmax - zmin;
  if (options.mid_sagittal_plane) {
    l.plane = *options.mid_sagittal_plane;
    l.plane_source = "model";
  } else {
    // The nose tip near the middle of the skin's x range, then the skin's mirror plane searched near it.
    const auto first = nose_front(skin_profile(V, skin, {0.5 * (xmin + xmax), 0, 0}, 20.0), zmin, zmax);
    l.plane.x = mirror_plane(V, skin, require(first, "nose tip").x(), zmin + 0.1 * height, zmax - 0.1 * height,
                             kFaceMirrorReach, kFaceMirrorSearch);
    l.plane_source = "skin";
  }
  Profile profile = skin_profile(V, skin, l.plane, options.profile_band);
  const std::vector<std::pair<double, double>> under_objects =
      options.ct_landmarks ? read_under(options.ct_landmarks->skin_objects, profile)
                           : std::vector<std::pair<double, double>>{};
  const Eigen::Vector3d front = require(nose_front(profile, zmin, zmax), "nose tip");
  Profile::FrontLine cut_front{front.z(), front.y(), 0.0};
  std::optional<std::pair<double, double>> cut =
      profile.run_behind(cut_front, options.clipped_depth, options.clipped_length);
  // A cut that leans in the head frame (a pitched head's, whose scan's edge is level with the scanner; a warp's) ends
  // early behind an upright front: the line through the plateau's own points follows it to where it ends, when that
  // is well beyond the upright plateau and the profile only recedes below it (a plane's trace does; a flat nose's
  // profile comes forward again at the upper lip).
  if (cut) {
    const auto leaning = profile.fitted_front(cut->first, cut->second);
    const auto along = leaning && std::abs(leaning->slope) <= kMaxCutSlope
                           ? profile.run_behind(*leaning, options.clipped_depth, options.clipped_length)
                           : std::nullopt;
    if (along && along->second - along->first > cut->second - cut->first + kMinCutGain &&
        !profile.comes_forward_below(cut->first, along->first, kLipRise))
      cut = along, cut_front = *leaning;
  }
  // A cut that clipped the nose back to the lips' level holds the subnasale's hollow and the upper lip in a plateau as
  // deep as a coarse model's roughness needs: the cut is then its flat front, above them.
  if (cut) {
    const auto flat = profile.run_behind(cut_front, options.clipped_flat_depth, options.clipped_length);
    if (flat && flat->first > cut->first && profile.comes_forward_below(flat->first, cut->first, kLipRise)) cut = flat;
    l.clipped_from = cut->first, l.clipped_to = cut->second;
  }
  // The nose as the profile shows it: its tip, or the lowest point of the cut.
  const Eigen::Vector3d nose = cut ? require(profile.extreme(cut->first - 1, cut->first + 1, true), "nose") : front;
  // The lips: going down from the nose, the profile's turns.
  std::vector<Profile::Turn> turns = lip_turns(profile, nose.z());
  const char* lips[] = {"subnasale", "upper lip", "stomion", "lower lip"};
  if (turns.size() < 4) {
    if (!cut) require(std::nullopt, lips[turns.size()]);
    std::ostringstream message;
    message << std::fixed << std::setprecision(1) << "cannot find the " << lips[turns.size()]
            << " on the mid-sagittal skin profile below where the scan's field of view cuts the face flat (z "
            << cut->first << " to " << cut->second
            << " mm): the cut may reach the lips; give the landmarks with --landmarks FILE";
    throw Error("landmarks", message.str());
  }
  // The upper lip's front can be flat, and its turn then a corner of the lip's rise: labrale superius is the most
  // anterior point between the hollows either side of it.
  const auto lip_points = [&](const Profile& on, const std::vector<Profile::Turn>& t) {
    const Eigen::Vector3d upper = require(on.extreme(t[2].point.z(), t[0].point.z(), true), "upper lip");
    return std::array<Eigen::Vector3d, 4>{subnasale(on, upper, nose), upper, t[2].point, t[3].point};
  };
  std::array<Eigen::Vector3d, 4> mouth = lip_points(profile, turns);  // sn, ls, st, li
  // The mouth's own midline: where a face is not symmetric about one plane (a bent midline, a swelling on one side)
  // the skin's mirror plane can pass beside the mouth, and the lips read on it lie beside their midline. The lips'
  // rows' own mirror plane, when it lies further from it than the profile's band, is where they are read. Not on a
  // model that carries its plane (a CT's, from the whole head's symmetry): on a scan a few mm coarse the lips' rows
  // alone place their mirror plane millimetres apart from one scan to a warp of it (docs/results.md).
  const double plane_at_mouth = l.plane.x_at(mouth[2].y(), mouth[2].z());
  const double mouth_x = l.plane_source == "skin" ? mirror_plane(V, skin, plane_at_mouth, mouth[3].z(), mouth[0].z(),
                                                                 kMouthMirrorReach, kMouthMirrorSearch)
                                                  : plane_at_mouth;
  if (std::abs(mouth_x - plane_at_mouth) > options.profile_band) {
    MidSagittalPlane through_mouth = l.plane;
    through_mouth.x += mouth_x - plane_at_mouth;
    const Profile mouth_profile = skin_profile(V, skin, through_mouth, options.profile_band);
    const std::vector<Profile::Turn> mouth_turns = lip_turns(mouth_profile, nose.z());
    if (mouth_turns.size() >= 4) mouth = lip_points(mouth_profile, mouth_turns);
  }
  const Eigen::Vector3d &sn = mouth[0], &ls = mouth[1], &st = mouth[2], &li = mouth[3];
  // Above the nose: found above a cut that ends below the top of the skin, else placed by typical adult proportions
  // on the cut (nose tip 15 mm above the subnasale, nasion 40 mm above the tip, glabella 12 mm above the nasion).
  // The profile's front at height z, on the plane: where typical proportions place a landmark the scan does not show.
  auto on_profile = [&](double z) {
    const std::optional<Eigen::Vector3d> p = profile.extreme(z - 1, z + 1, true);
    const double y = p ? p->y() : front.y();
    return Eigen::Vector3d(l.plane.x_at(y, z), y, z);
  };
  Eigen::Vector3d prn = front, n, g;
  bool above_cut = cut && cut->second < zmax - 15;
  if (above_cut) {
    prn = require(profile.extreme(0.5 * (cut->first + cut->second) - 1, 0.5 * (cut->first + cut->second) + 1, true),
                  "nose tip");
    n = require(nasion_above(profile, cut->second, prn), "nasion");
    // A hollow above the cut further from the subnasale than any adult nasion: the cut reached past the nasion (the
    // forehead's own front ends it), and the proportions place it.
    above_cut = (n - sn).norm() <= kNasionSubnasale[1];
  }
  if (!cut || above_cut) {
    if (!cut) n = require(nasion_above(profile, prn.z() + kNasionLowest, prn), "nasion");
    // Not within a few mm of the model's top: where a model is cut just above the brow (a standard), the cut's edge
    // is the most anterior point above the nasion, and it is no anatomy. A scan that ends that close above the nasion
    // shows no brow: the glabella is estimated as on a cut face.
    constexpr double kTopCutMargin = 5;
    const std::optional<Eigen::Vector3d> brow =
        profile.middle_of_extreme(n.z() + 3, std::min(n.z() + 30, zmax - kTopCutMargin), true, kFlatTie);
    g = brow ? *brow : on_profile(std::min(n.z() + 12, zmax - 1));
    if (cut) l.estimated = {"pronasale"};
    if (!brow) l.estimated.push_back("glabella");
  } else {
    prn = on_profile(std::min(sn.z() + 15, zmax - 20));
    n = on_profile(std::min(prn.z() + 40, zmax - 13));
    g = on_profile(std::min(n.z() + 12, zmax - 1));
    l.estimated = {"pronasale", "nasion", "glabella"};
  }
  l.points = {{"pronasale", prn},       {"subnasale", sn},        {"nasion", n},  {"glabella", g},
              {"labrale superius", ls}, {"labrale inferius", li}, {"stomion", st}};
  add_chin(profile, skin, V,
           options.ct_landmarks && options.ct_landmarks->bony_menton
               ? std::optional<Eigen::Vector3d>(options.ct_landmarks->bony_menton->point)
               : std::nullopt,
           l);
  // The skin is not seen under an object: what the profile shows there is the object's front less its thickness.
  for (const auto& [name, p] : l.points)
    for (const auto& [lo, hi] : under_objects)
      if (p.z() >= lo && p.z() <= hi && std::find(l.estimated.begin(), l.estimated.end(), name) == l.estimated.end())
        l.estimated.push_back(name);
  if (options.ct_landmarks) l.skin_objects = options.ct_landmarks->skin_objects;
  if (const auto corners = mouth_corners_upright(V, skin, l.plane, st, ls)) {
    l.points["cheilion right"] = corners->first;
    l.points["cheilion left"] = corners->second;
  }
  take_opening_corners(options.opening_rims, l);
  return l;
}

}  // namespace

namespace {

// find_face_landmarks without the tragi.
FaceLandmarks find_on_skin(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask, const LandmarkOptions& options) {
  if (options.skin_points) {
    LandmarkOptions on_points = options;
    on_points.skin_points.reset();
    return find_on_skin(*options.skin_points, Eigen::VectorXi::Constant(options.skin_points->rows(), side_bit(W1)),
                        on_points);
  }
  if (!options.mid_sagittal_plane) return find_in_head_frame(V, side_mask, options);
  // A turned or pitched head's profile is read in its head frame, where the face looks to +y, upright.
  const HeadTurn turn = head_turn_of(*options.mid_sagittal_plane);
  if (!turn.turned()) return find_in_head_frame(V, side_mask, options);
  Eigen::MatrixXd head(V.rows(), 3);
  for (int v = 0; v < V.rows(); ++v) head.row(v) = turn.to_head(V.row(v).transpose()).transpose();
  LandmarkOptions in_head = options;
  in_head.mid_sagittal_plane = turn.to_head(*options.mid_sagittal_plane);
  for (Eigen::MatrixXd& rim : in_head.opening_rims)
    for (Eigen::Index r = 0; r < rim.rows(); ++r) rim.row(r) = turn.to_head(rim.row(r).transpose()).transpose();
  if (in_head.ct_landmarks && in_head.ct_landmarks->bony_menton)
    in_head.ct_landmarks->bony_menton->point = turn.to_head(in_head.ct_landmarks->bony_menton->point);
  FaceLandmarks l = find_in_head_frame(head, side_mask, in_head);
  for (auto& [name, p] : l.points) p = turn.to_model(p);
  l.plane = *options.mid_sagittal_plane;
  return l;
}

}  // namespace

std::string opening_name(const Eigen::Vector3d& centroid, const FaceLandmarks& landmarks, int index) {
  const auto at = [&](const char* name) { return landmarks.points.at(name); };
  const std::string end = centroid.x() < landmarks.plane.x ? "at -x" : "at +x";
  if (landmarks.points.count("pronasale") && centroid.z() > at("pronasale").z() + 5) return "eye " + end;
  if (landmarks.points.count("subnasale") && centroid.z() > at("subnasale").z() - 4) return "nostril " + end;
  if (landmarks.points.count("stomion") && std::abs(centroid.z() - at("stomion").z()) < 12) return "mouth";
  return "opening " + std::to_string(index + 1);
}

FaceLandmarks find_face_landmarks(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                  const LandmarkOptions& options) {
  FaceLandmarks l = find_on_skin(V, side_mask, options);
  l.scan_frame = options.scan_frame;
  if (!options.ct_landmarks) return l;
  const auto add = [&l](const char* name, const std::optional<CtLandmark>& landmark) {
    if (landmark) place(l, name, landmark->point, landmark->estimated);
  };
  for (size_t side = 0; side < kTragusNames.size(); ++side) add(kTragusNames[side], options.ct_landmarks->tragi[side]);
  for (size_t c = 0; c < kEyeCornerNames.size(); ++c) add(kEyeCornerNames[c], options.ct_landmarks->eye_corners[c]);
  add(kStomionName, options.ct_landmarks->stomion);
  for (size_t c = 0; c < kMouthCornerNames.size(); ++c)
    add(kMouthCornerNames[c], options.ct_landmarks->mouth_corners[c]);
  return l;
}

void check_plausible(const FaceLandmarks& l, const std::string& remedy) {
  const auto has = [&](const char* name) { return l.points.count(name) > 0; };
  const auto at = [&](const char* name) { return l.points.at(name); };
  const auto named = [&](const std::string& name) { return patient_side_name(name, l.scan_frame); };
  const auto fail = [&](const std::string& landmark, const std::string& problem) {
    throw Error("landmarks", "implausible " + named(landmark) + ": " + problem + "; " + remedy);
  };
  const auto number = [](double v) {
    std::ostringstream s;
    s.precision(1);
    s << std::fixed << v << " mm";
    return s.str();
  };
  for (const auto& [name, p] : l.points)
    if (!p.allFinite()) fail(name, "its position is not a number");
  for (const auto& [name, p] : l.points) {
    const int side = named_side(name);
    const double beyond = p.x() - l.plane.x_at(p.y(), p.z());  // mm towards the model's +x, its left ones' side
    if (side != 0 && side * beyond <= 0)
      fail(name, "it lies " + number(std::abs(beyond)) + " across the mid-sagittal plane, on the " +
                     named(other_side_name(name)) + "'s side (left and right are the patient's: swapped?)");
  }
  const char* order[] = {"glabella", "nasion",           "pronasale", "subnasale", "labrale superius",
                         "stomion",  "labrale inferius", "pogonion",  "menton"};
  const char* above = nullptr;
  for (const char* name : order) {
    if (!has(name)) continue;
    if (above && at(name).z() >= at(above).z())
      fail(name, std::string("it lies at or above the ") + above + " (z " + number(at(name).z()) + " vs " +
                     number(at(above).z()) + ")");
    above = name;
  }
  const auto range = [&](const char* a, const char* b, double lo, double hi, const char* blame,
                         const std::string& why = "") {
    if (!has(a) || !has(b)) return;
    const double d = (at(a) - at(b)).norm();
    if (d < lo || d > hi)
      fail(blame, "the distance " + named(a) + " - " + named(b) + " is " + number(d) + ", outside the adult range " +
                      number(lo) + " to " + number(hi) + why);
  };
  range("nasion", "subnasale", kNasionSubnasale[0], kNasionSubnasale[1], "subnasale");
  range("subnasale", "menton", 45, 95, "menton");
  range("glabella", "nasion", 3, 35, "glabella");
  range("cheilion left", "cheilion right", 35, 85, "cheilion");
  if (has("nasion") && has("subnasale") && has("menton")) {
    const double ratio = (at("subnasale") - at("menton")).norm() / (at("nasion") - at("menton")).norm();
    if (ratio < 0.45 || ratio > 0.70)
      fail("menton", "the lower face (subnasale - menton) is " + std::to_string(static_cast<int>(100 * ratio)) +
                         " % of the face height (nasion - menton), outside the adult 45 to 70 %");
  }
  range("exocanthion left", "exocanthion right", 70, 120, "exocanthion");
  range("endocanthion left", "endocanthion right", 20, 50, "endocanthion");
  range("endocanthion left", "exocanthion left", 20, 45, "exocanthion left");
  range("endocanthion right", "exocanthion right", 20, 45, "exocanthion right");
  for (const char* eye : {"endocanthion left", "exocanthion left", "endocanthion right", "exocanthion right"}) {
    if (!has(eye)) continue;
    for (const char* mouth : {"cheilion left", "cheilion right"})
      if (has(mouth) && at(eye).z() <= at(mouth).z()) fail(eye, "it lies below the " + named(mouth));
    if (has("glabella") && at(eye).z() >= at("glabella").z()) fail(eye, "it lies above the glabella");
  }
  // A segmented CT's posterior cut follows its tragi (core/segment/face_cuts.h): the message says how to place it.
  const std::string cut = " (a CT's posterior cut follows the tragi found: --posterior-cut places it)";
  range("tragus left", "tragus right", 110, 175, "tragus", cut);
  for (const char* tragus : {"tragus left", "tragus right"}) {
    if (!has(tragus)) continue;
    range("nasion", tragus, 80, 150, tragus, cut);
    if (has("glabella") && at(tragus).z() >= at("glabella").z()) fail(tragus, "it lies above the glabella" + cut);
    if (has("menton") && at(tragus).z() <= at("menton").z()) fail(tragus, "it lies below the menton" + cut);
  }
}

std::vector<NamedLandmark> named_landmarks(const FaceLandmarks& l) {
  std::vector<NamedLandmark> out;
  for (const std::string& name : landmark_names()) {
    const auto p = l.points.find(name);
    if (p == l.points.end()) continue;
    const bool estimated = std::find(l.estimated.begin(), l.estimated.end(), name) != l.estimated.end();
    out.push_back({name, p->second,
                   l.given     ? LandmarkStatus::given
                   : estimated ? LandmarkStatus::estimated
                               : LandmarkStatus::found});
  }
  return out;
}

FaceLandmarks landmarks_from(const std::vector<NamedLandmark>& given, const std::string& source) {
  FaceLandmarks l;
  for (const NamedLandmark& n : given) {
    l.points[n.name] = n.position;
    if (n.status == LandmarkStatus::estimated) l.estimated.push_back(n.name);
  }
  for (const FeatureSpec& spec : feature_specs())
    if (!l.points.count(spec.landmark))
      throw Error(source, "the " + spec.name + " needs the landmark '" + spec.landmark + "', which the file lacks");
  l.plane.x = l.points.at("pronasale").x();
  l.plane_source = "given";
  l.given = true;
  return l;
}

std::string skin_object_text(const SkinObject& o) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << "an object lies on the skin's front from z = " << o.z_low << " to "
     << o.z_high << " mm, " << 0.5 * (o.thickness_low + o.thickness_high)
     << " mm thick (a strap or tape): the landmarks there are read on the skin under it (estimated; --skin-objects "
        "off reads them on its front); the model keeps it as soft tissue";
  return os.str();
}

std::string landmarks_text(const FaceLandmarks& l, const std::string& indent) {
  std::ostringstream os;
  for (const SkinObject& o : l.skin_objects) os << indent << skin_object_text(o) << "\n";
  if (!std::isnan(l.clipped_from))
    os << indent << "the scan's field of view cuts the face flat from z = " << l.clipped_from << " to " << l.clipped_to
       << " mm: landmarks inside the cut are estimated from typical proportions\n";
  for (const auto& [name, p] : l.points) {
    const bool estimated = std::find(l.estimated.begin(), l.estimated.end(), name) != l.estimated.end();
    os << indent << patient_side_name(name, l.scan_frame) << " at (" << p.x() << ", " << p.y() << ", " << p.z()
       << ") mm" << (estimated ? " (estimated)" : "") << "\n";
  }
  return os.str();
}

const std::vector<FeatureSpec>& feature_specs() {
  static const std::vector<FeatureSpec> specs = {{"mid-sagittal line", "pronasale", 0, 0.0},
                                                 {"eyebrow line", "glabella", 1, 35.0},
                                                 {"below-nose line", "subnasale", 1, 15.0},
                                                 {"middle lip line", "stomion", 1, 25.0}};
  return specs;
}

ConstraintSet feature_constraints(const FaceLandmarks& landmarks, const std::map<std::string, double>& values,
                                  double band) {
  ConstraintSet set;
  for (const FeatureSpec& spec : feature_specs()) {
    Constraint c;
    c.name = spec.name;
    c.field = spec.field;
    const auto value = values.find(spec.name);
    if (value == values.end() && spec.field != 0)
      throw Error("feature constraints", "no value for the " + spec.name + " (take it from the standard's set)");
    c.value = value == values.end() ? 0.5 : value->second;
    PlaneSelection p;
    p.band = band;
    p.exclude_sides = side_bit(static_cast<Side>(2 * spec.field)) | side_bit(static_cast<Side>(2 * spec.field + 1));
    const Eigen::Vector3d at = landmarks.points.at(spec.landmark);
    std::ostringstream origin;
    origin.precision(1);
    origin << std::fixed << "placed at the landmark '" << spec.landmark << "', (" << at.x() << ", " << at.y() << ", "
           << at.z() << ") mm, " << (landmarks.given ? "given" : "found on the model");
    c.origin = origin.str();
    if (spec.field == 0) {
      p.point = Eigen::Vector3d(landmarks.plane.x, landmarks.plane.y, landmarks.plane.z);
      p.normal = landmarks.plane.normal();
      p.region = "volume";
    } else {
      p.point = at;
      // Horizontal in the head frame: a pitched head's features lie on planes pitched with it (a turn keeps the
      // vertical).
      const HeadTurn turn = head_turn_of(landmarks.plane);
      p.normal = turn.to_model(Eigen::Vector3d::UnitZ()) - turn.to_model(Eigen::Vector3d::Zero());
      p.region = "boundary";
      p.within_center = at;
      p.within_radius = spec.radius;
    }
    c.select.plane = p;
    set.constraints.push_back(c);
  }
  return set;
}

}  // namespace facehex
