#pragma once
// The patient as both front ends take it: the tet model from a CT, a tet mesh or a closed surface
// (core/segment/patient_input.h), the domain its fields live on (the model itself), and its constraint set chosen by
// the one policy below.
#include <map>
#include <optional>
#include <string>

#include "core/face/face_landmarks.h"
#include "core/fields/constraint_set.h"
#include "core/fields/tet_domain.h"
#include "core/mesh/mesh.h"
#include "core/segment/patient_input.h"
#include "core/util/progress.h"

namespace facehex {

struct PatientSetup {
  std::string path;         // the file it came from; a name for a model made in memory
  VolumeMesh mesh;          // positively oriented tets; point data "side_mask" when its sides are labelled
  bool reoriented = false;  // the file's tets were all negative and have been flipped
  std::optional<CtSegmentation> segmentation;  // a CT's thresholds and cuts; empty for a mesh file
  TetDomain domain;                            // own_domain(mesh)
  ConstraintSet constraints;
  std::string constraints_path;            // the file the constraints came from, or empty when placed automatically
  std::string landmarks_path;              // the user's landmark file the features were placed at, or empty
  std::optional<FaceLandmarks> landmarks;  // where the automatic feature constraints were placed
  std::string features_problem;  // why no feature constraints were placed (then only the six sides, or none), or empty
  std::string constraints_note;  // one line for the user: which constraints, from where

  // What error messages about this patient name: its constraint file, else its model file.
  std::string source() const { return constraints_path.empty() ? path : constraints_path; }
};

// The one constraint policy: `constraints_file` when given; else, for a model with side labels, its six sides and the
// facial feature constraints at its landmarks (those of `landmarks_file` when given, core/face/landmark_file.h, else
// found on its skin; either set checked for plausibility) valued as the standard's (`feature_values`,
// core/face/automatic_constraints.h) or, when no values are given or the landmarks cannot be found, its six sides
// alone (features_problem says why); a model with neither a constraint file nor side labels gets no constraints
// (features_problem says so), for the user to place them.
void choose_constraints(PatientSetup& patient, const std::string& constraints_file,
                        const std::map<std::string, double>* feature_values, const std::string& landmarks_file = "");

// The skin vertex (side w1 of side_mask #V, the side the landmarks lie on) closest to `point`, for a landmark the user
// moves. Throws facehex::Error("landmarks", ...) when the model has no skin.
Eigen::Vector3d closest_skin_point(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                   const Eigen::Vector3d& point);

// The model of `path` (a CT is segmented with `segment`; `progress` hears of it) with its constraints as
// choose_constraints picks them, the file being `constraints_file`, else for a mesh file constraints_beside it
// (core/util/resources.h). Throws facehex::Error naming the file or the stage.
PatientSetup load_patient(const std::string& path, const SegmentOptions& segment, const std::string& constraints_file,
                          const std::map<std::string, double>* feature_values, const ProgressCallback& progress = {},
                          const std::string& landmarks_file = "");

// load_patient's second half, on a model read (or segmented) beforehand from `path`.
PatientSetup setup_patient(PatientTetModel model, const std::string& path, const std::string& constraints_file,
                           const std::map<std::string, double>* feature_values, const std::string& landmarks_file = "");

// A tet model made in memory (checked and oriented), constrained by choose_constraints without a file.
PatientSetup patient_from_mesh(VolumeMesh mesh, const std::string& name,
                               const std::map<std::string, double>* feature_values);

// The synthetic face-like shell the demo falls back on when no sample patient is bundled (core/mesh/synthetic_shell.h,
// tetrahedralized, its six sides labelled) at about `edge_length` mm.
VolumeMesh synthetic_shell_patient(double edge_length);

}  // namespace facehex
