#pragma once
// The patient tet model from whatever the user has: a head CT (segmented, soft_tissue.h), a tet mesh, or a closed
// surface (tetrahedralized at options.tets.target_edge_length), checked and positively oriented (mesh_check.h).
// `facehex run`, `facehex segment` and the desktop application's File > Open all start here.
#include <optional>
#include <string>

#include "core/mesh/mesh.h"
#include "core/mesh/mesh_check.h"
#include "core/segment/soft_tissue.h"
#include "core/util/progress.h"

namespace facehex {

// How a CT was segmented: the options as given (a tunnel repair's thicker layer and wider blur included:
// PatientModel::options), the edge length the tets were made at (the given one, or what the
// scan's and the face's rules made of it), and the thresholds and cut planes used (found or given), for the user to
// check and to give back changed (SegmentOptions::cuts).
struct CtSegmentation {
  SegmentOptions options;
  TissueThresholds thresholds;
  FaceCuts cuts;
  std::string repair;              // PatientModel::repair, and the second segmentation of a pitched head
  double edge_length = 0;          // mm, PatientModel::edge_length
  std::string edge_length_rule;    // PatientModel::edge_length_rule
  double gantry_tilt_degrees = 0;  // PatientModel::gantry_tilt_degrees
  CtNoise noise;                   // PatientModel::noise
};

struct PatientTetModel {
  VolumeMesh mesh;     // positive tets; a segmented CT's has point data "side_mask"
  TetMeshCheck check;  // check.reoriented: the file's tets were all negatively oriented and have been flipped
  std::optional<CtSegmentation> segmentation;  // empty for a mesh file
};

// A CT is recognized by is_ct_input (ct_volume.h). When its face's anatomy (FaceNotFound) or the landmarks on its
// model (find_face_landmarks, check_plausible) are not found and its hard palate slopes kMinHeadPitch or more
// (FaceCuts::palate_pitch) with no pitch given, it is segmented again with the head pitched back by the palate's
// slope, and that model is taken if its landmarks are found (CtSegmentation::repair says so); a face found in neither
// frame is an error that says both. Throws facehex::Error naming the file or the segmentation stage;
// `progress` hears of the segmentation's steps.
PatientTetModel load_patient_model(const std::string& path, const SegmentOptions& options = {},
                                   const ProgressCallback& progress = {});

// One line for the user: "skin threshold 563.6, bone threshold 1169.4 (file units); cuts (mm, segmentation frame):
// top z 133.0, bottom z 3.0, posterior y 102.0, mid-plane x 98.7, jaw cut rising to z 22.0 at the posterior cut".
std::string segmentation_summary(const CtSegmentation& segmentation);

}  // namespace facehex
