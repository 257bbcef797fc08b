#include "core/segment/face_cuts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "core/util/error.h"

namespace facehex {
namespace {

std::string mm(double v) {
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << v << " mm";
  return s.str();
}

// How far the line between the two tragi found leans from level, as the plane's lean is measured (a head tilted
// towards its left shoulder raises its right tragus); none unless both were found.
std::optional<double> tragi_roll_degrees(const Tragi& tragi) {
  const std::optional<CtLandmark>&right = tragi[0], &left = tragi[1];
  if (!right || !left || right->estimated || left->estimated) return std::nullopt;
  const Eigen::Vector3d d = left->point - right->point;
  if (!(d.x() > 0)) return std::nullopt;
  return std::atan2(-d.z(), d.x()) * 180 / M_PI;
}

// The face region's end (face_cuts.h, top_z): going up from `from`, the section's area (mm^2) per level and the width
// of its base level; where the area lost over a rise, per mm of the base's width, exceeds kScanEndSlope times the
// rise, the section is whole up to the last level within a voxel's depth of the base.
double section_end(const Mask& head, const FaceCuts& cuts, double from) {
  const GridGeometry& g = head.geometry;
  const int first = std::max(0, static_cast<int>(std::ceil((from - g.origin.z()) / g.spacing.z())));
  const double voxel_area = g.spacing.x() * g.spacing.y();
  std::vector<double> area(g.dims[2], 0), width(g.dims[2], 0);
  for (int k = first; k < g.dims[2]; ++k)
    for (int i = 0; i < g.dims[0]; ++i) {
      int in_front = 0;
      for (int j = 0; j < g.dims[1]; ++j)
        in_front += head(i, j, k) && g.point(i, j, k).y() > cuts.posterior_y_at(g.point(i, j, k).x());
      area[k] += in_front * voxel_area;
      width[k] += in_front > 0 ? g.spacing.x() : 0;
    }
  const int rise = std::max(2, static_cast<int>(std::ceil(kScanEndRise / g.spacing.z())));
  for (int k = first + 1; k < g.dims[2]; ++k) {
    const int base = std::max(first, k - rise);
    if (!(width[base] > 0)) return std::numeric_limits<double>::infinity();
    const auto receded = [&](int at) { return (area[base] - area[at]) / width[base]; };  // mm of mean depth
    if (!(receded(k) > kScanEndSlope * (k - base) * g.spacing.z())) continue;
    int whole = k - 1;
    while (whole > base && receded(whole) > g.spacing.y()) --whole;
    return g.point(0, 0, whole).z();
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

std::vector<CutPlane> FaceCuts::planes() const {
  // The posterior cut y = posterior_y + s (x - centre_x): points with s x - y > s centre_x - posterior_y are cut; the
  // top cut z = top_z + t (x - centre_x): points with z - t x > top_z - t centre_x; the bottom cut z = bottom_z + b (x
  // - centre_x): points with b x - z > b centre_x - bottom_z; the jaw cut z = jaw_z + (posterior_y_at(x) - y) + b (x -
  // centre_x), rising at 45 degrees from the posterior cut.
  const double s = posterior_slope, t = top_slope, b = bottom_slope, along = s * centre_x - posterior_y;
  const Eigen::Vector3d posterior(s, -1, 0), top(-t, 0, 1), bottom(b, 0, -1);
  std::vector<CutPlane> p = {{top.normalized(), (top_z - t * centre_x) / top.norm(), V1},
                             {bottom.normalized(), (b * centre_x - bottom_z) / bottom.norm(), V0},
                             {posterior.normalized(), along / posterior.norm(), U0}};
  if (jaw_z > -std::numeric_limits<double>::infinity()) {
    const Eigen::Vector3d jaw(s + b, -1, -1);
    p.push_back({jaw.normalized(), (along + b * centre_x - jaw_z) / jaw.norm(), V0});
  }
  return p;
}

double FaceCuts::posterior_turn_degrees() const { return std::atan(posterior_slope) * 180 / M_PI; }

// mm the tragus lies in front of the auricle's front edge that rule 5 finds, where no tragus is seen: on the two real
// CTs the more anterior tragus lies 2-3 mm in front of it (docs/benchmarks.md).
constexpr double kTragusBeforeAuricleEdge = 3.0;

double front_of_the_ears(const FaceAnatomy& anatomy) {
  double front = -std::numeric_limits<double>::infinity();
  for (const std::optional<CtLandmark>& tragus : anatomy.tragi)
    if (tragus && !tragus->estimated) front = std::max(front, tragus->point.y());
  return std::isfinite(front) ? front : anatomy.ear_front_y + kTragusBeforeAuricleEdge;
}

EarsLine ears_line(const FaceAnatomy& anatomy, double centre_x) {
  const EarsLine coronal{front_of_the_ears(anatomy), 0};
  std::array<std::optional<Eigen::Vector3d>, 2> ear;  // -x side, +x side
  for (int s = 0; s < 2; ++s)
    if (anatomy.tragi[s] && !anatomy.tragi[s]->estimated) ear[s] = anatomy.tragi[s]->point;
  for (int s = 0; s < 2; ++s)
    if (!ear[s] && ear[1 - s] && !anatomy.ears_estimated && std::isfinite(anatomy.ear_fronts_y[s]))
      ear[s] = Eigen::Vector3d(2 * centre_x - ear[1 - s]->x(), anatomy.ear_fronts_y[s] + kTragusBeforeAuricleEdge, 0);
  if (!ear[0] || !ear[1]) return coronal;
  const Eigen::Vector3d d = *ear[1] - *ear[0];
  if (!(d.x() > 0) || std::abs(std::atan2(d.y(), d.x())) > kMaxPosteriorCutTurn * M_PI / 180) return coronal;
  const double slope = d.y() / d.x();
  return {ear[0]->y() + slope * (centre_x - ear[0]->x()), slope};
}

namespace {

// The posterior cut from the anatomy and from where the scan ends across the head (face_cuts.h).
void place_posterior_cut(const FaceAnatomy& a, const FaceCutOptions& options,
                         const std::vector<FieldOfViewContact>& scan_edge, FaceCuts& cuts) {
  const EarsLine line = ears_line(a, cuts.centre_x);
  const double ears = line.y_at_centre + options.ear_clearance;
  // Where the scan ends across the head from the mouth's level (half way from the chin's lowest bone to the nose tip)
  // up: lower down, a scan that ends across the shoulders beside the neck says nothing of the face. The scan ends in
  // front of the ears' cut; or the ears' cut leaves less than a face region: what the ear rules read in a scan that
  // ends behind the face (a cheek's bulge standing out, the rows where the head is widest because the scan ends
  // there) is no ear.
  const double z_lo = 0.5 * (a.menton.z() + a.pronasale.z()), z_hi = a.glabella.z() + options.brow_clearance;
  bool scan_edge_in_front = false;
  for (const FieldOfViewContact& contact : scan_edge) {
    const Eigen::Vector3d& p = contact.point;
    if (p.z() < z_lo || p.z() > z_hi) continue;
    if (p.y() > cuts.scan_edge_y.value_or(-std::numeric_limits<double>::infinity())) {
      cuts.scan_edge_y = p.y();
      cuts.scan_edge_at_disc = contact.on_disc;
    }
    scan_edge_in_front |= p.y() + options.border_margin > ears + line.slope * (p.x() - cuts.centre_x);
  }
  cuts.posterior_at_scan_edge = cuts.scan_edge_y && (scan_edge_in_front || a.pronasale.y() - ears < kMinFaceDepth);
  cuts.posterior_slope = cuts.posterior_at_scan_edge ? 0 : line.slope;
  cuts.posterior_y =
      std::round(10 * (cuts.posterior_at_scan_edge ? *cuts.scan_edge_y + options.border_margin : ears)) / 10;
  const double depth = a.pronasale.y() - cuts.posterior_y;
  if (cuts.posterior_at_scan_edge && depth < kMinFaceDepth)
    throw Error("segment", "the scan ends across the head " + mm(a.pronasale.y() - *cuts.scan_edge_y) +
                               " behind the nose tip (at y " + mm(*cuts.scan_edge_y) +
                               "), in front of the ears: a face region of " + mm(depth) +
                               " holds too little of the "
                               "face for the standard, which reaches back to in front of the ears (at least " +
                               mm(kMinFaceDepth) +
                               "); a scan of the whole face is needed, or place the posterior cut "
                               "with --posterior-cut to mesh what lies in front of it");
}

// The lowest and highest x of the head's section at the level of `at` in front of the posterior cut.
std::pair<double, double> section_extent(const Mask& head, const FaceCuts& cuts, const Eigen::Vector3d& at) {
  const GridGeometry& g = head.geometry;
  const int k = std::clamp(static_cast<int>(std::lround((at.z() - g.origin.z()) / g.spacing.z())), 0, g.dims[2] - 1);
  double x_lo = at.x(), x_hi = at.x();
  for (int j = 0; j < g.dims[1]; ++j)
    for (int i = 0; i < g.dims[0]; ++i)
      if (head(i, j, k) && g.point(i, j, k).y() >= cuts.posterior_y_at(g.point(i, j, k).x()))
        x_lo = std::min(x_lo, g.point(i, j, k).x()), x_hi = std::max(x_hi, g.point(i, j, k).x());
  return {x_lo, x_hi};
}

// A cut perpendicular to the mid-sagittal plane the landmarks are read on (landmark_plane), `offset` mm above the
// landmark `at` (below it where negative): its dz/dx, its z at the mid-plane, and its lowest and highest z over the
// head's section at the landmark's level in front of the posterior cut; none where that plane is vertical. A head
// tilted towards a shoulder has its top and bottom cuts so, where the scan holds them.
struct TiltedCut {
  double slope = 0, z = 0, lowest = 0, highest = 0;
};
std::optional<TiltedCut> tilted_cut(const Mask& head, const FaceCutOptions& options, const FaceCuts& cuts,
                                    const Eigen::Vector3d& at, double offset) {
  const MidSagittalPlane lean = landmark_plane(cuts, options);
  if (lean.slope == 0) return std::nullopt;
  const auto [x_lo, x_hi] = section_extent(head, cuts, at);
  TiltedCut t;
  t.slope = -lean.slope;
  t.z = at.z() + offset - t.slope * (at.x() - cuts.centre_x);
  const double z_lo = t.z + t.slope * (x_lo - cuts.centre_x), z_hi = t.z + t.slope * (x_hi - cuts.centre_x);
  t.lowest = std::min(z_lo, z_hi), t.highest = std::max(z_lo, z_hi);
  return t;
}

}  // namespace

FaceCuts find_face_cuts(const Mask& head, const Mask& without_ears, const Mask& bone, const FaceCutOptions& options,
                        const std::optional<ScanSlab>& slab, const std::vector<FieldOfViewContact>& scan_edge) {
  const GridGeometry& g = head.geometry;
  // The first body voxel in slice order lies in the lowest slice with any body: below it a scan holds air only (a
  // field of view that starts above its lowest slices, or a volume resampled into a larger box).
  const auto first_body = std::find(head.data.begin(), head.data.end(), 1);
  if (first_body == head.data.end()) throw Error("segment", "the head mask is empty");
  const double lowest_body_z = g.point(0, 0, g.ijk(static_cast<size_t>(first_body - head.data.begin()))[2]).z();
  FaceCuts cuts;
  if (!options.top_z || !options.bottom_z || !options.posterior_y || !options.centre_x)
    cuts.anatomy = find_face_anatomy(head, without_ears, bone);
  if (options.glabella && cuts.anatomy && !cuts.anatomy->brow_unseen) {
    cuts.anatomy->glabella = *options.glabella;
    cuts.anatomy->glabella_under_object = true;
  }
  cuts.centre_x = options.centre_x ? *options.centre_x : cuts.anatomy->centre_x;
  // To the tenth of a millimetre the cuts are printed and shown with, so that a cut given as printed is the same cut.
  if (options.posterior_y)
    cuts.posterior_y = *options.posterior_y;
  else
    place_posterior_cut(*cuts.anatomy, options, scan_edge, cuts);
  double scan_lo = g.lower(2), scan_hi = g.upper(2);
  if (slab && slab->turn.pitch != 0 && cuts.anatomy) {
    // The scan's slices are tilted in the head frame: the top cut stays below the last over the face's depth (from
    // the posterior cut to the pronasale), the bottom cut above the first at the chin (behind the chin the jaw cut,
    // rising at 45 degrees, takes the region above the bottom cut away).
    const HeadTurn& t = slab->turn;
    const FaceAnatomy& a = *cuts.anatomy;
    scan_lo = std::max(scan_lo, t.head_height_of_level(slab->z_lo, a.menton.y()));
    scan_hi = std::min({scan_hi, t.head_height_of_level(slab->z_hi, cuts.posterior_y),
                        t.head_height_of_level(slab->z_hi, a.pronasale.y())});
  }
  const double z_min = std::max(scan_lo, lowest_body_z) + options.border_margin;
  const double z_max = scan_hi - options.border_margin;
  cuts.bottom_z =
      options.bottom_z ? *options.bottom_z : std::max(z_min, cuts.anatomy->menton.z() - options.chin_clearance);
  // A tilted head's bottom cut chin_clearance under the menton: a level cut would leave in the model the shoulder the
  // tilt raises on one side. It stays level where it would leave the scan (below z_min).
  if (!options.bottom_z)
    if (const auto t = tilted_cut(head, options, cuts, cuts.anatomy->menton, -options.chin_clearance);
        t && t->lowest >= z_min)
      cuts.bottom_slope = t->slope, cuts.bottom_z = t->z;
  if (options.top_z) {
    cuts.top_z = *options.top_z;
  } else {
    const FaceAnatomy& a = *cuts.anatomy;
    cuts.section_end_z = section_end(head, cuts, a.brow_unseen ? a.pronasale.z() + 15 : a.nasion.z());
    const double limit =
        std::min({z_max, a.highest_head_z - options.border_margin, a.forehead_end_z - options.border_margin,
                  cuts.section_end_z - options.border_margin});
    cuts.top_z = a.brow_unseen ? limit : std::min(limit, a.glabella.z() + options.brow_clearance);
    // A tilted head's top cut brow_clearance above the glabella, where the glabella placed it: its brows lie the same
    // distance under it on both sides. It stays level where so tilted it would rise above `limit` (where the scan, the
    // head or the forehead's whole front ends).
    if (!a.brow_unseen)
      if (const auto t = tilted_cut(head, options, cuts, a.glabella, options.brow_clearance); t && t->highest <= limit)
        cuts.top_slope = t->slope, cuts.top_z = t->z;
  }
  if (!(cuts.top_z > cuts.bottom_z + 10.0))
    throw Error("segment", "the top cut (z = " + mm(cuts.top_z) + ") must be well above the bottom cut (z = " +
                               mm(cuts.bottom_z) + "); check the cut options and the CT's superior axis");
  return cuts;
}

void find_jaw_cut(const Mask& model, double clearance, FaceCuts& cuts) {
  const GridGeometry& g = model.geometry;
  const int j = static_cast<int>(std::lround((cuts.posterior_y - g.origin.y()) / g.spacing.y()));
  const double x_reach = g.spacing.x();
  if (j < 0 || j >= g.dims[1]) return;
  // Only the lower half of the face: higher up, tissue across the mid-plane is the scalp over the skull's vertex.
  const double z_limit = 0.5 * (cuts.bottom_z + cuts.top_z);
  for (int k = g.dims[2] - 1; k >= 0; --k) {
    if (g.point(0, 0, k).z() > z_limit) continue;
    for (int i = 0; i < g.dims[0]; ++i)
      if (model(i, j, k) && std::abs(g.point(i, j, k).x() - cuts.centre_x) <= x_reach) {
        cuts.jaw_z = g.point(i, j, k).z() + clearance;
        return;
      }
  }
}

MidSagittalPlane landmark_plane(const FaceCuts& cuts, const FaceCutOptions& given) {
  if (cuts.anatomy && !given.centre_x && std::abs(cuts.anatomy->roll_degrees) > kLandmarkPlaneMinLean) {
    const FaceAnatomy& a = *cuts.anatomy;
    const std::optional<double> tragi = tragi_roll_degrees(a.tragi);
    const bool mirror_agrees = std::abs(a.mirror_roll_degrees - a.roll_degrees) <= kLandmarkPlaneLeanAgreement;
    if (tragi ? std::abs(*tragi - a.roll_degrees) <= kLandmarkPlaneLeanAgreement
              : a.roll_support >= kLandmarkPlaneLeanSupport || mirror_agrees)
      return {a.centre_x, a.roll_slope, a.roll_z};
  }
  return {cuts.centre_x, 0, 0};
}

}  // namespace facehex
