#include "core/standard/own_constraints.h"

#include "core/mesh/side_mask.h"
#include "core/segment/remesh.h"
#include "core/standard/closed_domain.h"
#include "core/standard/own_feature_values.h"

namespace facehex {

ConstraintSet own_automatic_constraints(const VolumeMesh& standard, const std::string& source, double band,
                                        double skin_edge_length) {
  const SurfaceMesh skin = remesh_isotropic(domain_surface(closed_domain(standard)), skin_edge_length);
  const Eigen::VectorXi sides = skin.labels.array() - 1;  // labels are Side + 1
  const FaceLandmarks landmarks =
      find_face_landmarks(skin.V, side_mask_from_faces(static_cast<int>(skin.V.rows()), skin.F, sides));
  ConstraintSet set = side_constraints();
  for (const Constraint& c :
       feature_constraints(landmarks, own_feature_values(standard, landmarks, band, source), band).constraints)
    set.constraints.push_back(c);
  return set;
}

}  // namespace facehex
