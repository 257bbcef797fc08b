#pragma once
// The mesh-matching baseline the paper compares with (section 4; its refs [11, 12]: Couteau, Payan, Lavallée 2000;
// Chabanas, Luboz, Payan 2003): an elastic registration of the standard's boundary surface onto the patient's,
// applied to every node of the standard. Used by `facehex map --method mesh-matching` and `facehex compare`.
//
//  1. Similarity (rotation, translation, isotropic scale). Start: no rotation, bounding-box centres aligned, scale the
//     cube root of the bounding-box volume ratio. ASSUMPTION: both models use the FaceHex frame (+y anterior, the
//     face looking to +y; +z superior), which is checked (the skin side must lie in front of the bone side); the
//     frames may differ by any translation and scale (the bundled patient is in CT millimetres, the standard in its
//     own frame) and by a moderate rotation, which the iterations recover. Then iterated closest points with a
//     weighted Umeyama fit.
//  2. Thin-plate spline (thin_plate_spline.h) on about `control_points` control points spread over the standard's
//     labelled boundary, fitted to the closest-point pairs, iterated with a stiffness decreasing step by step (a
//     coarse-to-fine elastic registration).
//  3. Every standard node x -> spline(similarity(x)), then snapped onto the landmarks if any (PointPairs).
//
// Correspondences are symmetric and side-aware: a standard boundary vertex is paired with the closest point of the
// patient's boundary triangles of the same side (skin to skin, bone to bone, each cut to the same cut), and a patient
// boundary vertex with the closest point of the current standard surface of the same side (its source is that
// point's barycentric position on the undeformed standard triangle). Each direction has half the weight; pairs
// farther than `outlier_factor` times their direction's median distance are left out (parts one model has and the
// other not). Boundary vertices
// on no side (the walls of the standard's eye, nose and mouth openings) get no pair and follow the spline.
//
// Inputs: standard hex-dominant mesh and patient tet model (both with point data "side_mask", sides.h). The result
// has the standard's connectivity and point/cell data; nothing is repaired (inverted cells are reported, not fixed).
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/util/progress.h"

namespace facehex {

struct MeshMatchingOptions {
  int similarity_iterations = 30;                            // at most
  std::vector<double> stiffness = {1e-1, 1e-2, 1e-3, 1e-4};  // unitless, see thin_plate_spline.h
  int iterations_per_stiffness = 20;                         // at most
  double convergence = 0.01;       // a stage ends when the mean pair distance improves by less than this share
  int control_points = 600;        // about this many spline control points
  int pairs_per_direction = 3000;  // about this many vertices sampled on each surface
  double outlier_factor = 3;       // pairs farther than this times their direction's median are left out
};

// Points known to correspond on the two models (e.g. facial landmarks), standard -> patient, #L x 3 each: each
// iteration pulls them together with `weight`, a share of the total weight of all pairs; then, with snap_radius > 0,
// a local displacement of that support (landmark_snap.h) carries each registered standard point exactly onto its
// patient point (the spline, fitted to thousands of surface pairs as well, leaves them a millimetre or a few apart).
struct PointPairs {
  Eigen::MatrixXd standard, patient;
  double weight = 0.25;
  double snap_radius = 25;  // mm; 0: the pairs only pull
};

struct MeshMatchingIteration {
  std::string stage;                                              // "similarity" or "spline"
  double stiffness = 0;                                           // spline stage
  double standard_to_patient_mm = 0, patient_to_standard_mm = 0;  // mean closest-point distances before the fit
};

struct MeshMatchingResult {
  VolumeMesh hex;    // the standard's cells at their registered positions
  double scale = 1;  // isotropic scale of the similarity
  int control_points = 0;
  std::vector<MeshMatchingIteration> iterations;
  std::map<std::string, double> seconds;  // "surfaces", "similarity", "spline", "apply"
};

// Sources name the files in error messages. Throws facehex::Error when a model lacks "side_mask", the frame check
// fails, or no pair can be formed.
MeshMatchingResult mesh_matching(const VolumeMesh& standard, const std::string& standard_source,
                                 const VolumeMesh& patient, const std::string& patient_source,
                                 const MeshMatchingOptions& options = {}, const ProgressCallback& progress = {},
                                 const PointPairs* landmarks = nullptr);

}  // namespace facehex
