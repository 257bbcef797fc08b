#pragma once
// The dense correspondence a transfer imposes on the patient's skin and bone side: the standard's tet domain is
// registered onto the patient (the elastic surface registration of core/baseline/mesh_matching.h: a similarity, then
// a thin-plate spline from stiff to soft, pairing each side with the same side), and the standard's (u, v) at the
// registered points are pulled back to the patient's vertices on those sides (side_correspondence.h). Imposed as
// Dirichlet conditions, they make the harmonic interior follow the registration, where the paper's few feature lines
// leave the fields free on the skin and a change of its shape slides the whole map along it.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/baseline/mesh_matching.h"
#include "core/fields/parameterization.h"
#include "core/fields/tet_domain.h"
#include "core/mesh/mesh.h"
#include "core/mesh/sides.h"
#include "core/quality/surface_distance.h"
#include "core/util/progress.h"

namespace facehex {

struct RegisteredSidesOptions {
  MeshMatchingOptions registration;
  std::vector<Side> sides = {W1};  // the sides whose (u, v) the registration decides
  // mm: patient side vertices farther than this from the registered standard surface get no condition (parts one
  // model has and the other not: an orbit or a nasal aperture open on one bone side, a nose one scan clipped), their
  // fields there follow harmonically from around.
  double max_distance = 3.0;
  // mm: a patient side vertex whose correspondent lies on the rim of the standard's side (where the standard's side
  // ends and the patient's goes on) farther than this gets no condition either: a strip of vertices beyond the rim
  // would all take the rim's values and fold the fields there.
  double rim_tolerance = 0.5;
};

struct RegisteredSides {
  FieldConditions conditions;  // u and v (fields 0 and 1) at the patient's vertices on the sides and on no other,
                               // within max_distance of the registered standard
  // #V of the standard's domain: 1 for its vertices on the registered sides whose registered position lies within
  // max_distance of the patient's same side (where the registration found the patient's surface).
  std::vector<char> standard_matched;
  // How far the patient's side vertices lie from the registered standard surface: what the registration left apart
  // (parts one model has and the other not, or a registration that went wrong); and how many were too far.
  DistanceSummary distance;
  int vertices_too_far = 0;
  // Landmarks whose patient skin triangle takes values that put the standard's landmark vertex exactly on them
  // (snapped landmarks only: PointPairs::snap_radius; on the skin side W1, where facial landmarks lie).
  int pinned_landmarks = 0;
  double seconds = 0;
};

// standard: the standard's tet domain (side_mask set) and its parameters there (uvw #V x 3); patient: a tet model
// with "side_mask". landmarks: points known to correspond (standard -> patient), or null. Throws facehex::Error
// naming patient_source when the patient lacks one of the sides or the registration fails.
RegisteredSides register_sides(const TetDomain& standard, const Eigen::MatrixXd& standard_uvw,
                               const VolumeMesh& patient, const std::string& patient_source,
                               const RegisteredSidesOptions& options, const PointPairs* landmarks = nullptr,
                               const ProgressCallback& progress = {});

}  // namespace facehex
