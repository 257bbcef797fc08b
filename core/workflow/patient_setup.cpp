#include "core/workflow/patient_setup.h"

#include <filesystem>
#include <optional>

#include "core/face/automatic_constraints.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/side_mask.h"
#include "core/mesh/sides.h"
#include "core/mesh/synthetic_shell.h"
#include "core/segment/ct_volume.h"
#include "core/standard/closed_domain.h"
#include "core/tetgen/tetrahedralize.h"
#include "core/util/error.h"
#include "core/util/resources.h"

namespace facehex {
namespace fs = std::filesystem;

void choose_constraints(PatientSetup& patient, const std::string& constraints_file,
                        const std::map<std::string, double>* feature_values, const std::string& landmarks_file) {
  patient.landmarks.reset();
  patient.features_problem.clear();
  patient.landmarks_path = landmarks_file;
  if (!constraints_file.empty()) {
    patient.constraints = read_constraint_set(constraints_file);
    patient.constraints_path = constraints_file;
    patient.constraints_note = "constraints from " + constraints_file;
    return;
  }
  patient.constraints_path.clear();
  if (patient.domain.side_mask.size() == 0) {
    patient.constraints = ConstraintSet();
    patient.features_problem = "the model has no \"side_mask\" array: no sides to constrain and no face to find";
    patient.constraints_note = "no constraints (" + patient.features_problem + ")";
    return;
  }
  patient.constraints = side_constraints();
  patient.constraints_note = "the six sides";
  if (!feature_values) {
    patient.features_problem = "no standard to value the facial features with";
    return;
  }
  try {
    FaceLandmarks landmarks;
    const std::optional<FaceLandmarks> given =
        landmarks_file.empty()
            ? std::nullopt
            : std::optional<FaceLandmarks>(landmarks_from(
                  read_landmark_file(landmarks_file, scan_frame(patient.mesh, patient.path)), landmarks_file));
    // A model with open eyes or an open mouth (a face model, a standard's re-meshing) has its corners read at its
    // openings' ends, as the standard's are.
    LandmarkOptions landmark_options = landmark_options_for(patient.mesh, patient.path);
    for (const std::vector<int>& rim :
         opening_rims(patient.domain, sideless_boundary_pieces(patient.domain), side_bit(W1)))
      landmark_options.opening_rims.push_back(patient.domain.V(rim, Eigen::all));
    patient.constraints = automatic_constraints(patient.domain.V, patient.domain.side_mask, landmark_options,
                                                *feature_values, kFeatureBand, &landmarks, given ? &*given : nullptr);
    patient.landmarks = landmarks;
    patient.constraints_note = "automatic constraints: six sides and " + std::to_string(feature_specs().size()) +
                               " features at the landmarks" + (landmarks_file.empty() ? "" : " of " + landmarks_file);
    for (const SkinObject& object : landmarks.skin_objects) patient.constraints_note += "; " + skin_object_text(object);
  } catch (const Error& e) {
    patient.features_problem = e.what();
    patient.constraints_note += " only: no facial features (" + patient.features_problem + ")";
  }
}

Eigen::Vector3d closest_skin_point(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                   const Eigen::Vector3d& point) {
  const int best = closest_skin_vertex(V, side_mask, point);
  if (best < 0) throw Error("landmarks", "the model has no skin (side w1) to place a landmark on");
  return V.row(best).transpose();
}

PatientSetup load_patient(const std::string& path, const SegmentOptions& segment, const std::string& constraints_file,
                          const std::map<std::string, double>* feature_values, const ProgressCallback& progress,
                          const std::string& landmarks_file) {
  return setup_patient(load_patient_model(path, segment, progress), path, constraints_file, feature_values,
                       landmarks_file);
}

PatientSetup setup_patient(PatientTetModel model, const std::string& path, const std::string& constraints_file,
                           const std::map<std::string, double>* feature_values, const std::string& landmarks_file) {
  PatientSetup p;
  p.path = path;
  p.mesh = std::move(model.mesh);
  p.reoriented = model.check.reoriented;
  p.segmentation = std::move(model.segmentation);
  p.domain = own_domain(p.mesh);
  // A constraint file beside a CT would select from a model the file was not made for: only mesh files have one.
  const std::string file = !constraints_file.empty() ? constraints_file
                           : is_ct_input(path)       ? std::string()
                                                     : constraints_beside(path);
  choose_constraints(p, file, feature_values, landmarks_file);
  return p;
}

PatientSetup patient_from_mesh(VolumeMesh mesh, const std::string& name,
                               const std::map<std::string, double>* feature_values) {
  PatientSetup p;
  p.reoriented = check_and_orient_tet_mesh(mesh, name).reoriented;
  p.path = name;
  p.mesh = std::move(mesh);
  p.domain = own_domain(p.mesh);
  choose_constraints(p, "", feature_values);
  return p;
}

VolumeMesh synthetic_shell_patient(double edge_length) {
  SyntheticShellOptions shell;
  shell.edge_length = edge_length;
  TetrahedralizeOptions options;
  options.target_edge_length = edge_length;
  return tetrahedralize_with_sides(synthetic_shell_surface(shell), options).mesh;
}

}  // namespace facehex
