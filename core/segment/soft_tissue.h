#pragma once
// From a CT to the labelled patient tet model of the facial soft tissue: the "bent thin cuboid" between the skin and
// the bone, from below the chin to above the brows, wrapping around the cheeks to just in front of the ears.
//
// Steps (all on an isotropic working grid resampled from the CT and blurred by 0.4 of its coarsest spacing, a noisy
// CT first blurred down to a diagnostic CT's noise, ct_noise.h; docs/segmentation.md has the reasoning):
//  1. thresholds: skin/bone from the histogram (thresholds.h) unless given;
//  2. body  = largest connected region with intensity >= skin, opened with a ball of opening_radius (drops thin
//             things stuck to the skin: tubes, straps, the head rest's padding);
//     head  = body, closed with a ball of cavity_closing_radius, then every enclosed air cavity filled. The eyes,
//             nostrils, mouth, sinuses and airway are therefore CLOSED: the model is one solid without tunnels;
//  3. bone  = head voxels with intensity >= bone;
//  4. model = head voxels at most max_depth below the skin that are either within min_thickness of it, or soft
//             tissue not behind bone on the horizontal ray from the face's vertical axis (x = centre_x,
//             y = posterior_y; sideways within 2 mm of it, where the radial direction depends on where the cut falls
//             between two rows; bone closed by bone_gap_radius, so the gap between the teeth counts): no tongue or
//             floor of the mouth inside the mandible, no brain, nothing behind the cheekbones, so no bone passes
//             through the model; connected to the skin; enclosed voids filled;
//  5. cut by the planes of face_cuts.h (top v1, bottom and jaw v0, posterior u0/u1);
//  6. surface = zero level of max(smoothed model mask, cut planes) (iso_surface.h), faces labelled by side
//     (side_labels.h), remeshed to near-equilateral triangles of target_edge_length keeping the sides (remesh.h);
//  7. TetGen with the side labels as facet markers, side_mask per vertex from the labelled boundary triangles;
//     When that surface has tunnels (Euler characteristic other than 2; thin tissue pierced), steps 4-6 run again
//     with min_thickness and smoothing_sigma raised, up to twice (PatientModel::repair says what was done);
//  8. the landmarks the model's skin does not show, read in the CT and kept as field data (core/mesh/ct_landmarks.h):
//     the tragi (tragus.h, with the cuts), the eye corners, the stomion and the mouth corners (eye_corners.h,
//     stomion.h, mouth_slit.h, by the landmarks found on the model), and the objects lying on the skin's front above
//     the nose tip (skin_objects.h);
//  9. checks: one solid, boundary of Euler characteristic 2 (a ball), each of the six sides one connected patch.
// Lips parted wider than cavity_closing_radius closes (an open mouth: a bite block, a tube, a trauma patient) leave a
// pocket in the skin that the standard's closed mouth cannot follow: steps 2-9 run again with the closing radius raised
// to close it, and PatientModel::repair says so; a gap wider than kMostMouthClosing closes is an error naming the
// radius that would.
#include <optional>
#include <string>

#include "core/mesh/mesh.h"
#include "core/segment/ct_noise.h"
#include "core/segment/ct_volume.h"
#include "core/segment/face_cuts.h"
#include "core/segment/thresholds.h"
#include "core/tetgen/tetrahedralize.h"
#include "core/util/progress.h"

namespace facehex {

// The remeshed surface already has triangles of the target size: TetGen keeps it (-Y) instead of splitting it, which
// would multiply the tet count (its volume bound encroaches on the boundary everywhere).
inline TetrahedralizeOptions patient_tet_options() {
  TetrahedralizeOptions o;
  o.preserve_surface = true;
  return o;
}

// The longest edge the scan's spacing sets (SegmentOptions::follow_scan_spacing): a face's thin parts (the lips, the
// nose's tip) keep a few tets across.
constexpr double kMostScanEdgeLength = 4.0;

// mm: the largest cavity_closing_radius an open mouth is closed with (lips up to twice this apart, less 2 mm);
// a wider closing would also fill the folds beside the nose and the eyes' sockets.
constexpr double kMostMouthClosing = 10.0;

// The tets' edge length of a model segmented from a scan whose voxels are `spacing` (mm) apart, for the given target
// edge length, as SegmentOptions::follow_scan_spacing sets it.
double scan_edge_length(const Eigen::Vector3d& spacing, double target_edge_length);

// Each setting below is an option of the command line (app/transfer_options.cpp: --skin, --bone, --min-thickness,
// --bone-gap, --cavity-closing, --smoothing, --max-depth, the cut options, --edge-length, --skin-objects), named in the
// errors.
struct SegmentOptions {
  std::optional<double> skin_threshold, bone_threshold;  // file units; estimated from the histogram when unset
  double working_spacing = 1.0;                          // mm, isotropic grid the CT is resampled to
  double opening_radius = 3.5;         // mm: things attached to the skin thinner than twice this are removed
  double cavity_closing_radius = 4.0;  // mm: openings (nostrils, lips, eyelids) narrower than twice this are closed
  double max_depth = 25.0;             // mm below the skin where no bone is nearer
  double min_thickness = 3.0;          // mm below the skin always in the model (bone this close is partial volume)
  double bone_gap_radius = 5.0;        // mm: gaps in the bone narrower than twice this (teeth) still hide tissue
  double smoothing_sigma = 1.5;        // mm, Gaussian blur of the model mask before its surface is extracted
  // mm, Gaussian blur of the CT before everything else; negative: the blur that brings the CT's measured noise down to
  // a diagnostic CT's (ct_noise.h: none for a CT that quiet); 0: none.
  double denoising_blur = -1;
  FaceCutOptions cuts;
  TetrahedralizeOptions tets = patient_tet_options();  // target_edge_length also sets the surface's edge length
  // The tets' edge length grows above tets.target_edge_length until the model's predicted tet count
  // (predicted_tet_count) is at most this (0: the edge length as given). A large face at the paper's 2 mm has more
  // tets than the transfer gains from, while the time and memory of every later stage follow their count; a face of
  // the bundled CT's size keeps 2 mm. The command line sets 0 when --edge-length is given.
  double coarsen_above_tets = 700000;
  // The tets' edge length is at least the scan's coarsest voxel spacing, up to kMostScanEdgeLength: the model's surface
  // holds no shape finer than the scan resolves, so shorter edges only cost time (a CT of 3 mm slices meshes at 3 mm).
  // The command line sets false when --edge-length is given.
  bool follow_scan_spacing = true;
  // Objects lying on the skin's front above the nose tip (a head strap, thick tape) found by their edges, and the
  // landmarks there read on the skin under them (skin_objects.h); false: the landmarks are read on the skin as
  // segmented, an object's front included.
  bool find_skin_objects = true;
  CtOrientation orientation;  // only used when reading a file
  std::string dicom_series;   // only used when reading a DICOM folder: read_dicom_series' `series`
};

// The cavity_closing_radius that closes lips `parted_lips` mm apart (PatientModel::parted_lips) when the given radius
// leaves them open: half the gap and a millimetre, rounded up to half a millimetre; 0 when the given radius closes
// them. Throws facehex::Error("segment", ...) naming the radius needed when that is above kMostMouthClosing.
double open_mouth_closing(double parted_lips, double cavity_closing_radius);

struct PatientModel {
  VolumeMesh mesh;                 // positive tets; point data "side_mask" (core/sides.h)
  Eigen::MatrixXi boundary_faces;  // #B x 3 outward boundary triangles of `mesh`
  Eigen::VectorXi boundary_sides;  // #B side (Side) of each boundary triangle
  TissueThresholds thresholds;     // as used
  FaceCuts cuts;                   // as used
  double edge_length = 0;          // mm, the tets' target edge length as used
  std::string edge_length_rule;    // why longer than SegmentOptions::tets asked (the scan, the face's size), or empty
  SegmentOptions options;          // as used: min_thickness and smoothing_sigma raised by a tunnel repair
  std::string repair;              // the tunnel repair made, the open mouth closed, the head pitched back, or empty
  // mm: how far apart the lips are at the midline in the CT (stomion.h: parted_lips_gap, between the labralia of the
  // first segmentation's model, which an open mouth's closing is chosen by), 0 where they meet or the lips were not
  // found
  double parted_lips = 0;
  double gantry_tilt_degrees = 0;  // CtVolume's: the CT's slices were resampled upright from this tilt
  CtNoise noise;                   // as measured (sigma 0 when SegmentOptions::denoising_blur is 0), blur as used
};

// The face's anatomy was not found (find_face_cuts): the error, and the hard palate's slope in the CT's frame when one
// was found (FaceCuts::palate_pitch), by which a caller can try again with the head pitched back (patient_input.h).
class FaceNotFound : public Error {
 public:
  FaceNotFound(const Error& error, std::optional<double> palate_pitch)
      : Error(error.subject(), error.problem()), palate_pitch(palate_pitch) {}
  std::optional<double> palate_pitch;
};

// Throws facehex::Error naming the stage ("thresholds", "segment", "tetgen") with what to change, FaceNotFound where
// the face's anatomy is not found. `progress` hears of
// each step ("segmentation: ..."); cancelling throws facehex::Cancelled at the next step (TetGen, the longest one,
// runs to its end first).
PatientModel build_patient_model(const CtVolume& ct, const SegmentOptions& options = {},
                                 const ProgressCallback& progress = {});

}  // namespace facehex
