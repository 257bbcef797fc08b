#include "core/segment/soft_tissue.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>
#include <vector>

#include "core/face/face_landmarks.h"
#include "core/fields/constraint_set.h"
#include "core/mesh/ct_landmarks.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/mesh/scan_frame.h"
#include "core/mesh/side_mask.h"
#include "core/mesh/skin_points.h"
#include "core/segment/distance_transform.h"
#include "core/segment/eye_corners.h"
#include "core/segment/face_anatomy.h"
#include "core/segment/field_of_view.h"
#include "core/segment/head_frame.h"
#include "core/segment/iso_surface.h"
#include "core/segment/morphology.h"
#include "core/segment/mouth_slit.h"
#include "core/segment/palate_pitch.h"
#include "core/segment/remesh.h"
#include "core/segment/side_labels.h"
#include "core/segment/skin_objects.h"
#include "core/segment/stomion.h"
#include "core/util/error.h"

namespace facehex {
namespace {

constexpr double kCtBlur = 0.4;  // Gaussian sigma of the resampled CT, in units of its coarsest voxel spacing
// mm of air kept around the body's box: more than the closing's and the surface blur's reach.
constexpr double kBodyBoxMargin = 10.0;

// The body's box in x and y, with kBodyBoxMargin of air around it (within the grid), and every slice: a scan's field
// of view is often several times the head's section, and every later step costs its voxel count. The slices stay
// whole: the scan's top and bottom are what the cuts' margins are measured from.
std::pair<std::array<int, 3>, std::array<int, 3>> body_box(const Mask& body) {
  const GridGeometry& g = body.geometry;
  auto [lo, hi] = occupied_box(body);
  lo[2] = 0, hi[2] = g.dims[2];
  for (int a = 0; a < 2; ++a) {
    const int margin = static_cast<int>(std::ceil(kBodyBoxMargin / g.spacing(a)));
    lo[a] = std::max(0, lo[a] - margin);
    hi[a] = std::min(g.dims[a], hi[a] + margin);
  }
  return {lo, hi};
}

Mask at_least(const Field& f, double threshold) {
  Mask m(f.geometry, 0);
  for (size_t i = 0; i < f.data.size(); ++i) m.data[i] = f.data[i] >= threshold;
  return m;
}

// The working grid, the CT's box at `spacing` (resampled_geometry), restricted in x and y to where the CT reaches the
// skin threshold, with room for body_box's margin and the blur's kernel (3 sigma) on both: the resampling and the blur
// then skip the air of a wide field of view, and the voxels of the body's box take the values they take in the whole
// grid.
GridGeometry working_grid(const Field& ct, double spacing, double skin, double blur) {
  const GridGeometry& g = ct.geometry;
  GridGeometry w = resampled_geometry(g, spacing);
  const auto [lo, hi] = occupied_box(at_least(ct, skin));
  if (hi[0] == 0) return w;  // nothing reaches the threshold: the caller says so
  const double reach = kBodyBoxMargin + 2 * (std::ceil(3 * blur / spacing) + 2) * spacing;
  for (int a = 0; a < 2; ++a) {
    const double from = g.origin(a) + lo[a] * g.spacing(a) - reach,
                 to = g.origin(a) + (hi[a] - 1) * g.spacing(a) + reach;
    const int first = std::max(0, static_cast<int>(std::floor((from - w.origin(a)) / spacing)));
    const int last = std::min(w.dims[a] - 1, static_cast<int>(std::ceil((to - w.origin(a)) / spacing)));
    w.origin(a) += first * spacing;
    w.dims[a] = last - first + 1;
  }
  return w;
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// "top z 135.0, bottom z 3.0, posterior y 102.0": the cut planes as the errors name them, to the tenth of a mm.
std::string cut_planes_text(const FaceCuts& cuts) {
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << "top z " << cuts.top_z << ", bottom z " << cuts.bottom_z << ", posterior y " << cuts.posterior_y;
  return s.str();
}

// To the tenth, as the summary prints angles and percentages.
std::string tenths(double v) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << v;
  return s.str();
}

// `ct` as segmented: blurred by noise.blur when that is above 0 (ct_noise.h), whose bone threshold then follows the
// soft-tissue peak's width (thresholds.h). `estimated`: the thresholds already found on this very CT, if any.
TissueThresholds choose_thresholds(const CtVolume& ct, const SegmentOptions& options, const CtNoise& noise,
                                   const std::optional<TissueThresholds>& estimated) {
  TissueThresholds t;
  if (!options.skin_threshold || !options.bone_threshold)
    t = estimated ? *estimated
                  : estimate_thresholds(ct.intensity, noise.blur > 0 ? BoneThresholdRule::peak_width
                                                                     : BoneThresholdRule::histogram_tail);
  if (options.skin_threshold) t.skin = *options.skin_threshold;
  if (options.bone_threshold) t.bone = *options.bone_threshold;
  if (!(t.skin < t.bone))
    throw Error("thresholds", "the skin threshold (" + number(t.skin) + ") must be below the bone threshold (" +
                                  number(t.bone) + ")");
  return t;
}

constexpr double kAxisReach = 2.0;  // mm from the face's axis within which the radial test looks sideways

// Step 4 of soft_tissue.h. A voxel is in the model if it is in the head, within max_depth of the air, inside the
// (margin-widened) cut box, and either within min_thickness of the air (bone there is partial-volume skin: the model
// never has a hole through the skin), or soft tissue that sees the air along the horizontal ray from the face's axis
// (x = centre_x, y = posterior_y) through it without crossing bone. The radial test is what makes the model a shell in
// front of the skeleton: the tongue and the floor of the mouth (inside the mandible's arch), the brain, the tissue
// behind the cheekbones are all behind bone on their ray, and leaving them out keeps bones from passing through the
// model (tunnels). Then the piece connected to the skin, with enclosed voids filled.
Mask model_mask(const Mask& head, const Mask& bone, const Field& air_distance, const FaceCuts& cuts,
                const SegmentOptions& options, double margin) {
  const GridGeometry& g = head.geometry;
  const double step = g.spacing.minCoeff() / 2;
  auto voxel_at = [&](const Eigen::Vector3d& x, std::array<int, 3>& ijk) {
    const Eigen::Vector3d t = (x - g.origin).cwiseQuotient(g.spacing);
    for (int a = 0; a < 3; ++a) ijk[a] = static_cast<int>(std::lround(t(a)));
    return g.contains(ijk[0], ijk[1], ijk[2]);
  };
  Mask m(g, 0);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const size_t v = g.index(i, j, k);
        const Eigen::Vector3d p = g.point(i, j, k);
        if (!head.data[v] || air_distance.data[v] > options.max_depth) continue;
        if (p.z() < cuts.bottom_z_at(p.x()) - margin || p.z() > cuts.top_z_at(p.x()) + margin ||
            p.y() < cuts.posterior_y_at(p.x()) - margin)
          continue;
        if (air_distance.data[v] <= options.min_thickness) {
          m.data[v] = 1;
          continue;
        }
        if (bone.data[v]) continue;
        Eigen::Vector3d radial(p.x() - cuts.centre_x, p.y() - cuts.posterior_y, 0);
        // Near the axis the radial direction says nothing (within a voxel it turns from lateral to straight forward,
        // through the chin, as the cut moves by half a voxel): the ray goes sideways, as on the axis's own row.
        if (radial.norm() < kAxisReach) radial = Eigen::Vector3d(radial.x() < 0 ? -1 : 1, 0, 0);
        const Eigen::Vector3d d = radial.normalized() * step;
        std::array<int, 3> at;
        bool behind_bone = false;
        for (Eigen::Vector3d x = p + d; voxel_at(x, at) && head(at[0], at[1], at[2]); x += d)
          if (bone(at[0], at[1], at[2]) && air_distance(at[0], at[1], at[2]) > options.min_thickness) {
            behind_bone = true;
            break;
          }
        m.data[v] = !behind_bone;
      }
  return fill_cavities(largest_component(m), {true, true, true, true, true, true});
}

// The sub-grid holding every voxel of `mask` plus `margin` voxels around (clamped to the grid): [lo, hi] per axis.
std::pair<std::array<int, 3>, std::array<int, 3>> bounding_box(const Mask& mask, int margin) {
  const GridGeometry& g = mask.geometry;
  std::array<int, 3> lo = g.dims, hi = {-1, -1, -1};
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (mask(i, j, k)) {
          const int at[3] = {i, j, k};
          for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], at[a]), hi[a] = std::max(hi[a], at[a]);
        }
  for (int a = 0; a < 3; ++a) lo[a] = std::max(0, lo[a] - margin), hi[a] = std::min(g.dims[a] - 1, hi[a] + margin);
  return {lo, hi};
}

// Signed function of the model, negative inside (~ millimetres near the surface): the blurred mask intersected with
// the cut half-spaces. Evaluated on the mask's bounding box only.
Field model_function(const Mask& model, const FaceCuts& cuts, double sigma) {
  const double h = model.geometry.spacing.minCoeff();
  const auto [lo, hi] = bounding_box(model, static_cast<int>(std::ceil(3 * sigma / h)) + 2);
  GridGeometry g;
  g.spacing = model.geometry.spacing;
  g.origin = model.geometry.point(lo[0], lo[1], lo[2]);
  for (int a = 0; a < 3; ++a) g.dims[a] = hi[a] - lo[a] + 1;
  Field smooth(g, 0.0f);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) smooth(i, j, k) = model(i + lo[0], j + lo[1], k + lo[2]);
  smooth = gaussian_smooth(smooth, sigma);
  // A blurred unit step has slope 1/(sigma sqrt(2 pi)) at its middle: scale to millimetres so that the max() with the
  // plane distances makes clean creases.
  const double scale = sigma > 0 ? sigma * std::sqrt(2 * M_PI) : h;
  const std::vector<CutPlane> planes = cuts.planes();
  Field phi(g, 0.0f);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        double value = (0.5 - smooth(i, j, k)) * scale;
        for (const CutPlane& plane : planes) value = std::max(value, plane.distance(p));
        phi(i, j, k) = static_cast<float>(value);
      }
  return phi;
}

// The tunnel repair's steps (build_patient_model): attempt a adds a times these to min_thickness (mm) and to the
// smoothing's relative width.
constexpr int kTunnelRepairAttempts = 2;
constexpr double kTunnelRepairThickness = 1.0;
constexpr double kTunnelRepairBlur = 0.25;

// The options of the tunnel repair's attempt (0: as given).
SegmentOptions tunnel_repair_options(SegmentOptions options, int attempt) {
  options.min_thickness += attempt * kTunnelRepairThickness;
  options.smoothing_sigma *= 1 + attempt * kTunnelRepairBlur;
  return options;
}

// How far the model mask reaches beyond the cuts, so that its blur does not round the creases where they cut it.
double mask_margin(const SegmentOptions& options) { return 3 * options.smoothing_sigma + 2 * options.working_spacing; }

int euler_characteristic(const Eigen::MatrixXi& faces) {
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  for (int f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      vertices.insert(faces(f, k));
      edges.insert(std::minmax(faces(f, k), faces(f, (k + 1) % 3)));
    }
  return static_cast<int>(vertices.size()) - static_cast<int>(edges.size()) + static_cast<int>(faces.rows());
}

void check_topology(const PatientModel& model) {
  const auto unlabelled = (model.boundary_sides.array() < 0).count();
  if (unlabelled > 0)
    throw Error("segment", std::to_string(unlabelled) + " boundary triangles of the tet mesh are on no side");
  const int pieces = count_patches(model.boundary_faces, model.boundary_sides, -1);
  if (pieces != 1)
    throw Error("segment", "the model is " + std::to_string(pieces) +
                               " separate solids; raise --cavity-closing or --smoothing, or move the cuts");
  const int chi = euler_characteristic(model.boundary_faces);
  // A cut that grazes thin tissue can open a tunnel that a cut a few millimetres away does not: the cuts are named
  // with the values the surface was made with. So is the bone threshold, since thin bone below it (a noisy CT's
  // threshold lies high) lets the tissue through.
  if (chi != 2) {
    const CtNoise& noise = model.noise;
    const std::string noise_text = noise.sigma > 0 ? "; the CT's noise " + tenths(100 * noise.sigma / noise.contrast) +
                                                         " % of its contrast, blurred by " + tenths(noise.blur) +
                                                         " mm: --denoise sets the blur"
                                                   : std::string();
    throw Error("segment",
                "the model's boundary has Euler characteristic " + std::to_string(chi) +
                    " instead of 2 (it has tunnels or voids" +
                    (model.repair.empty() ? std::string() : "; " + model.repair) +
                    "); raise --min-thickness, --bone-gap, --cavity-closing or --smoothing, lower "
                    "--max-depth, or move the cuts it was made with (" +
                    cut_planes_text(model.cuts) +
                    ") with --top-cut, --bottom-cut or --posterior-cut; or lower --bone (thin bone below the "
                    "bone threshold " +
                    number(model.thresholds.bone) + " lets the tissue through" + noise_text + ")");
  }
  for (int s = 0; s < kNumSides; ++s) {
    const int n = count_patches(model.boundary_faces, model.boundary_sides, s);
    if (n != 1)
      throw Error("segment", std::string("side ") + kSideNames[s] + " (" + kSideDescriptions[s] + ") is " +
                                 (n == 0 ? std::string("missing") : "split in " + std::to_string(n) + " patches") +
                                 "; move the cuts so that each crosses the soft tissue in one piece");
  }
}

// The model's surface: the zero level of model_function. Where a cut plane grazes a fold of the tissue, that level
// can touch itself (it bounds no solid); the automatic cuts are then moved by a fraction of a voxel, out and in,
// which keeps the anatomy they were placed by and changes the contour there. Cuts the user gave are never moved.
// `cuts` becomes the cuts the surface was made with.
SurfaceMesh level_surface_with_cuts(const Mask& tissue, FaceCuts& cuts, const SegmentOptions& options) {
  const FaceCutOptions& given = options.cuts;
  for (const double fraction : {0.0, 0.3, -0.3, 0.6, -0.6}) {
    const double nudge = fraction * options.working_spacing;
    FaceCuts moved = cuts;
    if (!given.top_z) moved.top_z += nudge;
    if (!given.bottom_z) moved.bottom_z -= nudge;
    if (!given.posterior_y) moved.posterior_y -= nudge;
    try {
      SurfaceMesh surface = zero_level_surface(model_function(tissue, moved, options.smoothing_sigma));
      cuts = moved;
      return surface;
    } catch (const NonManifoldSurface&) {
    }
  }
  throw Error("segment", "the soft-tissue surface between the cuts (" + cut_planes_text(cuts) +
                             ", each moved by up to " + number(0.6 * options.working_spacing) +
                             " mm) is not a closed manifold; raise --smoothing or place the cuts with --top-cut, "
                             "--bottom-cut, --posterior-cut");
}

// The landmarks read in the CT by the ones found on the model's skin (its mid-sagittal plane, nasion, pronasale and
// labralia) into `found`: the eye corners (eye_corners.h), the stomion (stomion.h), the mouth corners from it or, lips
// apart, from the ends of their gap (mouth_slit.h) and, with `objects`, the objects on
// the skin above the nose tip (skin_objects.h), and how far apart the lips are into `parted_lips` (stomion.h). False,
// and none read, when those are not found: the transfer says why.
bool read_slit_landmarks(const CtVolume& ct, const PatientModel& model, bool objects, CtLandmarks& found,
                         double& parted_lips) {
  FaceLandmarks landmarks;
  try {
    landmarks = find_face_landmarks(model.mesh.V, side_mask_of(model.mesh), landmark_options_for(model.mesh, "model"));
  } catch (const Error&) {
    return false;
  }
  const auto has = [&](const char* name) { return landmarks.points.count(name) > 0; };
  const double skin = model.thresholds.skin;
  if (has("nasion") && has("pronasale"))
    found.eye_corners = find_eye_corners(ct.intensity, skin, landmarks.plane, landmarks.points.at("nasion"),
                                         landmarks.points.at("pronasale"));
  if (objects && has("pronasale"))
    found.skin_objects = find_skin_objects(ct.intensity, skin, landmarks.plane, landmarks.points.at("pronasale"));
  if (has("labrale superius") && has("labrale inferius")) {
    const Eigen::Vector3d &upper = landmarks.points.at("labrale superius"),
                          &lower = landmarks.points.at("labrale inferius");
    found.stomion = find_stomion(ct.intensity, skin, landmarks.plane, upper, lower);
    if (!found.stomion) parted_lips = parted_lips_gap(ct.intensity, skin, landmarks.plane, upper, lower);
    if (parted_lips > 0)
      found.mouth_corners = find_open_mouth_corners(ct.intensity, skin, landmarks.plane, upper, lower);
  }
  if (found.stomion)
    found.mouth_corners = find_mouth_corners(ct.intensity, skin, landmarks.plane, found.stomion->point);
  return true;
}

}  // namespace

double open_mouth_closing(double parted_lips, double cavity_closing_radius) {
  if (parted_lips < 2 * cavity_closing_radius) return 0;
  const double needed = std::ceil(parted_lips + 2) / 2;  // half the gap and a millimetre, in halves
  if (needed > kMostMouthClosing)
    throw Error("segment",
                "the lips are " + number(parted_lips) +
                    " mm apart at the midline (an open mouth), wider than the closing raised for an open "
                    "mouth closes (--cavity-closing " +
                    number(kMostMouthClosing) +
                    "): the standard's closed mouth cannot follow the pocket it leaves in the skin; close "
                    "it with --cavity-closing " +
                    number(needed) +
                    " (which also fills the face's deeper folds), or segment a CT taken with the mouth closed");
  return needed;
}

double scan_edge_length(const Eigen::Vector3d& spacing, double target_edge_length) {
  return std::max(target_edge_length, std::min(spacing.maxCoeff(), kMostScanEdgeLength));
}

namespace {

// The segmentation with the cuts placed as `options` say (build_patient_model), of `ct` as denoised (`noise`), with
// its thresholds when they were `estimated` already.
PatientModel build_once(const CtVolume& ct, const SegmentOptions& options, const CtNoise& noise,
                        const std::optional<TissueThresholds>& estimated, const ProgressCallback& progress) {
  if (!(options.working_spacing > 0) || !(options.tets.target_edge_length > 0) || !(options.max_depth > 0))
    throw Error("segment", "working_spacing, target_edge_length and max_depth must be positive");
  // Fractions of the whole from the stages' share of the time on the bundled CT.
  const auto step = [&progress](const char* stage, double fraction) {
    report_progress(progress, std::string("segmentation: ") + stage, fraction);
  };
  PatientModel model;
  model.gantry_tilt_degrees = ct.gantry_tilt_degrees;
  step("thresholds", 0.0);
  model.noise = noise;
  model.thresholds = choose_thresholds(ct, options, noise, estimated);

  // Trilinear interpolation of a coarse CT has creases along its voxel planes, which the thresholded surface would
  // show as terraces: blur by a fraction of the CT's coarsest spacing first.
  step("resampling the CT", 0.02);
  Field intensity;
  Mask raw_body;
  std::optional<ScanSlab> slab;  // where a pitched head's scan ends
  {
    const double blur = kCtBlur * ct.intensity.geometry.spacing.maxCoeff();
    Field scan = gaussian_smooth(
        resample(ct.intensity, working_grid(ct.intensity, options.working_spacing, model.thresholds.skin, blur)), blur);
    Mask scan_body = largest_component(at_least(scan, model.thresholds.skin));
    if (std::count(scan_body.data.begin(), scan_body.data.end(), 1) == 0)
      throw Error("segment", "no voxel reaches the skin threshold " + number(model.thresholds.skin) +
                                 "; lower the skin threshold");
    // The cuts are planes of the head frame, where a turned or pitched head's face looks to +y, upright.
    HeadTurn& turn = model.cuts.turn;
    const auto [body_lo, body_hi] = occupied_box(scan_body);
    if (options.cuts.head_turn) {
      turn.degrees = *options.cuts.head_turn;
      turn.axis = 0.5 * (scan.geometry.point(body_lo[0], body_lo[1], 0) +
                         scan.geometry.point(body_hi[0] - 1, body_hi[1] - 1, 0))
                            .head<2>();
    } else {
      turn = find_head_turn(scan_body);
      if (std::abs(turn.degrees) < kMinHeadTurn) turn.degrees = 0;
    }
    if (options.cuts.head_pitch) {
      turn.pitch = *options.cuts.head_pitch;
      turn.axis_z = 0.5 * (scan.geometry.point(0, 0, body_lo[2]).z() + scan.geometry.point(0, 0, body_hi[2] - 1).z());
    }
    if (turn.pitch != 0) slab = ScanSlab{ct.intensity.geometry.lower(2), ct.intensity.geometry.upper(2), turn};
    if (turn.turned()) {
      step("resampling the CT in the head frame", 0.03);
      // From the CT itself: a second interpolation would blur the skin. Only around the body: the crop below keeps
      // the body's box and kBodyBoxMargin, and the blur reaches a few sigma further.
      const std::vector<float>& values = ct.intensity.data;
      const Eigen::Vector2d reach = Eigen::Vector2d::Constant(kBodyBoxMargin + 4 * blur + 2 * options.working_spacing);
      scan = gaussian_smooth(
          turned_to_head_frame(ct.intensity, turn, options.working_spacing,
                               *std::min_element(values.begin(), values.end()),
                               scan.geometry.point(body_lo[0], body_lo[1], 0).head<2>() - reach,
                               scan.geometry.point(body_hi[0] - 1, body_hi[1] - 1, 0).head<2>() + reach),
          blur);
      scan_body = largest_component(at_least(scan, model.thresholds.skin));
    }
    const auto [box_lo, box_hi] = body_box(scan_body);
    intensity = crop(scan, box_lo, box_hi);
    raw_body = crop(scan_body, box_lo, box_hi);
  }
  check_head_size(raw_body);
  step("the head", 0.05);
  const Mask body = open(raw_body, options.opening_radius);
  // Where the scan ends across the head (core/segment/field_of_view.h).
  const GridGeometry& scan_grid = ct.intensity.geometry;
  const ScanSides scan_sides{{scan_grid.lower(0), scan_grid.lower(1)},
                             {scan_grid.upper(0), scan_grid.upper(1)},
                             find_reconstruction_disc(ct.intensity),
                             model.cuts.turn};
  const std::vector<FieldOfViewContact> scan_edge = field_of_view_contacts(
      raw_body, scan_sides, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  // The trachea leaves through the bottom slice and the head through the top: only the x and y faces of the grid
  // are open air, and of those only the ones the scan does not end on across the head (an airway cut there is no
  // opening of the face).
  const std::array<bool, 6> cut_faces = cut_grid_faces(raw_body, scan_edge);
  const Mask head = fill_cavities(close(body, options.cavity_closing_radius),
                                  {!cut_faces[0], !cut_faces[1], !cut_faces[2], !cut_faces[3], false, false});
  Mask bone = at_least(intensity, model.thresholds.bone);
  for (size_t i = 0; i < bone.data.size(); ++i) bone.data[i] &= head.data[i];
  // Without bone the model would have no depth limit but max_depth and the chin nothing to be found by.
  if (std::count(bone.data.begin(), bone.data.end(), 1) == 0)
    throw Error("segment", "not a plausible head: no voxel of the head reaches the bone threshold " +
                               number(model.thresholds.bone) + "; lower it (--bone) if this is a head CT");
  // The ears, thin, do not survive the opening: the cuts find them where the body before it stands out of it.
  const HeadTurn turn = model.cuts.turn;
  std::optional<double> palate = palate_pitch(head, bone, turn.axis.x());
  if (palate) *palate += turn.pitch;  // the slope in the CT's frame
  try {
    model.cuts = find_face_cuts(raw_body, body, bone, options.cuts, slab, scan_edge);
  } catch (const Error& e) {
    const Error stated =
        !turn.turned()
            ? e
            : Error(e.subject(), e.problem() + " (the head was looked for turned " + tenths(turn.degrees) +
                                     " degrees about the vertical axis" +
                                     (turn.pitch != 0 ? " and pitched " + tenths(turn.pitch) + " degrees" : "") +
                                     "; --head-turn sets the turn" +
                                     (turn.pitch != 0 ? ", --head-pitch the pitch" : "") + ", 0 for none)");
    throw FaceNotFound(stated, palate);
  }
  model.cuts.turn = turn;
  model.cuts.palate_pitch = palate;

  step("the soft tissue", 0.2);
  // From here on only the slices between the cuts matter, with the model mask's margin beyond them (the widest, a
  // tunnel repair's) and max_depth more: every distance the mask and the side labels compare with max_depth or less
  // is then the same as on all the slices, and so is the model. A scan of the neck and shoulders costs no more.
  const auto [head_slices, bone_slices] = [&] {
    const GridGeometry& g = head.geometry;
    const double reach =
        mask_margin(tunnel_repair_options(options, kTunnelRepairAttempts)) + options.max_depth + 2 * g.spacing.z();
    std::array<int, 3> lo = {0, 0, 0}, hi = g.dims;
    const double bottom = std::min(model.cuts.bottom_z_at(g.lower(0)), model.cuts.bottom_z_at(g.upper(0)));
    lo[2] = std::clamp(static_cast<int>(std::floor((bottom - reach - g.origin.z()) / g.spacing.z())), 0, g.dims[2] - 1);
    const double top = std::max(model.cuts.top_z_at(g.lower(0)), model.cuts.top_z_at(g.upper(0)));
    hi[2] =
        std::clamp(static_cast<int>(std::ceil((top + reach - g.origin.z()) / g.spacing.z())) + 1, lo[2] + 1, g.dims[2]);
    return std::pair{crop(head, lo, hi), crop(bone, lo, hi)};
  }();
  Mask air = head_slices;
  for (auto& v : air.data) v = !v;
  const Field air_distance = distance_to(air);
  // Bone with its narrow gaps closed (between the teeth, in thin orbital walls) hides what is behind it.
  Mask hiding_bone = close(bone_slices, options.bone_gap_radius);
  for (size_t i = 0; i < hiding_bone.data.size(); ++i) hiding_bone.data[i] &= head_slices.data[i];

  // Where the tissue is only a voxel or two thick (thin skin over bone, a warped or streaky scan), its surface can
  // pierce it: a tunnel. The surface is then made again with a thicker minimum layer and a wider blur, which fill
  // such holes at the price of a slightly smoother skin everywhere; the attempt used is stated (PatientModel::repair).
  const FaceCuts automatic_cuts = model.cuts;
  SurfaceMesh surface;
  Field inner_distance;
  int first_chi = 2;
  // The skin vertices (head frame) of a surface with its sides found.
  const auto skin_of = [&](const SurfaceMesh& s, const Eigen::VectorXi& sides) {
    std::vector<Eigen::Vector3d> skin;
    const Eigen::VectorXi mask = side_mask_from_faces(static_cast<int>(s.V.rows()), s.F, sides);
    for (Eigen::Index v = 0; v < mask.size(); ++v)
      if (mask(v) & side_bit(W1)) skin.push_back(s.V.row(v).transpose());
    return skin;
  };
  const auto sides_of = [&](const SurfaceMesh& s) {
    Eigen::VectorXi sides = classify_sides(s, model.cuts, air_distance, inner_distance, 0.3 * options.working_spacing);
    merge_side_islands(s.F, sides);
    return sides;
  };
  // A tunnel repair smooths the whole skin, which can flatten the lips' edges the landmarks are read on (the mouth
  // corners): the landmarks read the first surface's skin, whose tunnels do not matter to them.
  std::vector<Eigen::Vector3d> first_skin;
  for (int attempt = 0;; ++attempt) {
    model.options = tunnel_repair_options(options, attempt);
    const SegmentOptions& used = model.options;
    model.cuts = automatic_cuts;
    const Mask tissue = model_mask(head_slices, hiding_bone, air_distance, model.cuts, used, mask_margin(used));
    if (std::count(tissue.data.begin(), tissue.data.end(), 1) == 0)
      throw Error("segment", "no soft tissue between the cuts; check the thresholds and the cut planes");
    // Clear of the blurred mask's edge, so the posterior cut meets two separate pieces.
    find_jaw_cut(tissue, 2 * used.smoothing_sigma + used.working_spacing, model.cuts);
    Mask inner = head_slices;
    for (size_t i = 0; i < inner.data.size(); ++i) inner.data[i] = head_slices.data[i] && !tissue.data[i];
    inner_distance = distance_to(inner);
    step(attempt == 0 ? "the surface" : "the surface again (the first had tunnels)", 0.33);
    surface = level_surface_with_cuts(tissue, model.cuts, used);
    const int chi = euler_characteristic(surface.F);
    if (attempt == 0) first_chi = chi;
    if (attempt == 0 && chi != 2) first_skin = skin_of(surface, sides_of(surface));
    if (chi == 2 || attempt == kTunnelRepairAttempts) {
      if (attempt > 0)
        model.repair = "the first surface had tunnels (Euler characteristic " + std::to_string(first_chi) +
                       "); made with --min-thickness " + number(used.min_thickness) + " --smoothing " +
                       number(used.smoothing_sigma) + (chi == 2 ? "" : ", which left tunnels too");
      break;
    }
  }
  const Eigen::VectorXi sides = sides_of(surface);
  surface.labels = sides;
  surface.labels.array() += 1;  // TetGen's marker 0 means "on no input facet"

  // The remesher keeps every vertex on the input surface, but where the bone side meets a cut in a thin wedge (bone
  // within a millimetre or two of the bottom cut), a triangle of one patch can cross one of the other, at some edge
  // lengths and not at others close to them. TetGen finds crossings before meshing; the surface is then remeshed at
  // an edge length 3 % shorter, then 3 % longer, which places the vertices differently.
  // A vertex where skin touches bone at a zero-thickness rim is left free in w (tetrahedralize_with_sides).
  TetrahedralizeOptions tet_options = options.tets;
  if (options.follow_scan_spacing) {
    const double scan = scan_edge_length(ct.intensity.geometry.spacing, tet_options.target_edge_length);
    if (scan > tet_options.target_edge_length) model.edge_length_rule = "the CT's coarsest voxel spacing";
    tet_options.target_edge_length = scan;
  }
  if (options.coarsen_above_tets > 0) {
    const double coarse =
        edge_length_for_tet_count(std::abs(enclosed_volume(surface)), options.coarsen_above_tets, tet_options);
    if (coarse > tet_options.target_edge_length) {
      model.edge_length_rule = "coarsened for the face's size";
      tet_options.target_edge_length = coarse;
    }
  }
  model.edge_length = tet_options.target_edge_length;
  TetrahedralizeResult tets;
  for (const double scale : {1.0, 0.97, 1.03}) {
    step(scale == 1.0 ? "remeshing the surface" : "remeshing the surface again (it crossed itself)", 0.38);
    const SurfaceMesh remeshed = remesh_isotropic(surface, scale * tet_options.target_edge_length);
    step("tetrahedralizing (TetGen)", 0.55);
    try {
      tets = tetrahedralize_with_sides(remeshed, tet_options);
      break;
    } catch (const SelfIntersectingSurface& e) {
      if (scale == 1.03)
        throw Error("segment", std::string("the remeshed surface intersects itself at three edge lengths near ") +
                                   number(tet_options.target_edge_length) + " mm (" + e.what() +
                                   "); choose another --edge-length or move the cuts");
    }
  }
  model.mesh = std::move(tets.mesh);
  // Back into the CT's frame, so that the model overlays the CT; its plane says how the head is turned.
  const ModelFromHead to_model(turn);
  for (int v = 0; v < model.mesh.V.rows(); ++v)
    model.mesh.V.row(v) = to_model(model.mesh.V.row(v).transpose()).transpose();
  MidSagittalPlane plane = landmark_plane(model.cuts, options.cuts);
  plane.y = turn.axis.y();
  set_mid_sagittal_plane(model.mesh, turn.to_model(plane));
  set_scan_frame(model.mesh, ct.scan_frame);
  // The skin at the working spacing, for the landmarks (core/mesh/skin_points.h).
  const std::vector<Eigen::Vector3d> skin_points = first_skin.empty() ? skin_of(surface, sides) : first_skin;
  Eigen::MatrixXd skin(static_cast<Eigen::Index>(skin_points.size()), 3);
  for (size_t i = 0; i < skin_points.size(); ++i) skin.row(static_cast<Eigen::Index>(i)) = to_model(skin_points[i]);
  set_skin_points(model.mesh, skin);
  CtLandmarks found;
  if (model.cuts.anatomy) {
    found.tragi = model.cuts.anatomy->tragi;
    for (std::optional<CtLandmark>& tragus : found.tragi)
      if (tragus) tragus->point = turn.to_model(tragus->point);
    found.bony_menton = CtLandmark{turn.to_model(model.cuts.anatomy->menton), false};
  }
  step("the eye corners, the stomion and the mouth corners", 0.93);
  if (read_slit_landmarks(ct, model, options.find_skin_objects, found, model.parted_lips) || model.cuts.anatomy)
    set_ct_landmarks(model.mesh, found);
  model.boundary_faces = std::move(tets.boundary_faces);
  model.boundary_sides = tets.boundary_labels.array() - 1;
  step("checks", 0.95);
  check_topology(model);
  return model;
}

// The glabella read on the skin under the objects lying on it (skin_objects.h), in the cuts' head frame, where an
// object was found and the head profile's glabella, which placed the top cut, lies more than kGlabellaTolerance from
// it in height: a strap over the brow comes forward as a brow does, and one over the nose's root moves the profile's
// nasion and the glabella read above it. The top cut belongs brow_clearance above the skin's brow instead. None where
// the top cut was given or placed otherwise, no object was found, or the two agree.
std::optional<Eigen::Vector3d> glabella_under_object(const PatientModel& model, const SegmentOptions& options) {
  constexpr double kGlabellaTolerance = 2.0;  // mm: the two readings' own difference on a bare brow is within it
  if (options.cuts.top_z || options.cuts.glabella || !model.cuts.anatomy || model.cuts.anatomy->brow_unseen)
    return std::nullopt;
  const std::optional<CtLandmarks> read = ct_landmarks(model.mesh, "the model");
  if (!read || read->skin_objects.empty()) return std::nullopt;
  FaceLandmarks under;
  try {
    under = find_face_landmarks(model.mesh.V, side_mask_of(model.mesh), landmark_options_for(model.mesh, "model"));
  } catch (const Error&) {
    return std::nullopt;
  }
  const Eigen::Vector3d glabella = model.cuts.turn.to_head(under.points.at("glabella"));
  if (std::abs(glabella.z() - model.cuts.anatomy->glabella.z()) <= kGlabellaTolerance) return std::nullopt;
  return glabella;
}

// The CT blurred as SegmentOptions::denoising_blur says, when it says to; `noise` gets what was measured and done, and
// `estimated` the thresholds of the CT as given when it is segmented so (the noise is measured between the same
// histogram's modes).
std::optional<CtVolume> denoised(const CtVolume& ct, const SegmentOptions& options, CtNoise& noise,
                                 std::optional<TissueThresholds>& estimated, const ProgressCallback& progress) {
  if (options.denoising_blur == 0) return std::nullopt;
  report_progress(progress, "segmentation: the CT's noise", 0);
  try {
    IntensityModes modes;
    estimated = estimate_thresholds(ct.intensity, BoneThresholdRule::histogram_tail, &modes);
    noise = measure_ct_noise(ct.intensity, modes);
  } catch (const Error&) {
    // No air and soft tissue to measure the noise between: it stays unmeasured, and the thresholds' step says why.
  }
  if (options.denoising_blur > 0) {
    noise.blur = options.denoising_blur;
    noise.sigma_after = noise.sigma * white_noise_after_blur(ct.intensity.geometry.spacing, noise.blur);
  }
  if (noise.blur <= 0) return std::nullopt;
  estimated.reset();  // the blurred CT's are its own
  report_progress(progress, "segmentation: blurring the noisy CT", 0);
  return CtVolume{gaussian_smooth(ct.intensity, noise.blur), ct.source, ct.gantry_tilt_degrees, ct.scan_frame};
}

}  // namespace

PatientModel build_patient_model(const CtVolume& raw_ct, const SegmentOptions& options,
                                 const ProgressCallback& progress) {
  CtNoise noise;
  std::optional<TissueThresholds> estimated;
  const std::optional<CtVolume> quieter = denoised(raw_ct, options, noise, estimated, progress);
  const CtVolume& ct = quieter ? *quieter : raw_ct;
  PatientModel model = build_once(ct, options, noise, estimated, progress);
  SegmentOptions again = options;
  std::vector<std::string> why;
  // A strap over the brow is the profile's most anterior point there: the cut above "the glabella" would lie above
  // the strap. The model is made again with the top cut above the glabella read on the skin under it.
  if (const std::optional<Eigen::Vector3d> glabella = glabella_under_object(model, options)) {
    again.cuts.glabella = *glabella;
    why.push_back("the top cut above the glabella under the object on the skin");
  }
  std::string mouth;
  if (const double radius = open_mouth_closing(model.parted_lips, options.cavity_closing_radius)) {
    again.cavity_closing_radius = radius;
    mouth = "the lips are " + number(model.parted_lips) + " mm apart at the midline (an open mouth): segmented again " +
            "with --cavity-closing " + number(radius) + ", which closes it across the lips";
    why.push_back("the open mouth closed");
  }
  if (why.empty()) return model;
  std::string stages = why.front();
  for (size_t i = 1; i < why.size(); ++i) stages += " and " + why[i];
  report_progress(progress, "segmentation: again, " + stages, 0);
  PatientModel second = build_once(ct, again, noise, estimated, progress);
  if (!mouth.empty()) {
    second.repair = second.repair.empty() ? mouth : mouth + "; " + second.repair;
    second.parted_lips = model.parted_lips;  // the gap the closing was chosen by
  }
  return second;
}

}  // namespace facehex
