#pragma once
// How far a transfer put each vertex of the standard from where it should be, over all vertices and per anatomical
// region of the standard: its skin (w1) and bone (w0) sides, the rim of each opening (eyes, nostrils, mouth: the
// walls of the hex mesh's holes, where they meet the skin or the bone) and the skin around its facial landmarks.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

struct ErrorSummary {
  int count = 0;
  double mean = 0, p95 = 0, max = 0;  // mm
  double within_1mm = 0;              // share of the vertices, in [0, 1]
};

// The summary of per-vertex errors (mm); p95 is the value at rank ceil(0.95 n) of the sorted errors. Empty: zeros.
ErrorSummary summarize_errors(const Eigen::VectorXd& errors);

// A named set of the standard's vertex ids.
struct VertexRegion {
  std::string name;
  std::vector<int> vertices;
};

// The standard's vertices at least this far from its cut sides (u0, u1, v0, v1: the posterior, bottom and top cuts)
// form the "inner face": where the anatomy decides the answer, not where each model's cuts were placed.
constexpr double kInnerFaceDepth = 15.0;  // mm

// The standard's regions: "skin", "bone", "landmarks" (skin vertices within `landmark_radius` mm of each landmark of
// find_face_landmarks), "inner face" (kInnerFaceDepth), one "rim: NAME" per opening, named by where it lies against the
// landmarks ("eye at -x", "eye at +x", "nostril at -x", "nostril at +x", "mouth"; others "opening N"). standard:
// hex-dominant, point data "side_mask". Throws facehex::Error("landmarks", ...) when the standard's landmarks cannot be
// found.
std::vector<VertexRegion> correspondence_regions(const VolumeMesh& standard, double landmark_radius = 3.0);

// |mapped.row(i) - truth.row(i)| for every vertex (both #V x 3).
Eigen::VectorXd vertex_errors(const Eigen::MatrixXd& mapped, const Eigen::MatrixXd& truth);

// The skin vertices' errors split against the true skin (the standard's w1 side at the true positions, its normals
// from its own boundary triangles): across it, along its normal (where the patient's surface, its segmentation
// included, lies elsewhere), and along it (the map sliding on the skin: the correspondence itself). Means in mm.
// standard: hex-dominant with point data "side_mask"; mapped and truth #V x 3.
struct SkinErrorSplit {
  double across = 0, along = 0;
};
SkinErrorSplit skin_error_split(const VolumeMesh& standard, const Eigen::MatrixXd& mapped,
                                const Eigen::MatrixXd& truth);

struct RegionError {
  std::string name;
  ErrorSummary error;
};
struct CorrespondenceError {
  ErrorSummary all;
  std::vector<RegionError> regions;  // in the order of the regions given
};
CorrespondenceError correspondence_error(const Eigen::VectorXd& errors, const std::vector<VertexRegion>& regions);

}  // namespace facehex
