#pragma once
// Dense correspondence on a side of two models (the skin, the bone): each patient vertex on the side gets the
// standard's parameters at the point of the standard's side it corresponds to, so that the harmonic interior of the
// patient's fields follows a registration of the two surfaces and not only their shapes (issue 18: the fields are
// otherwise free on the skin, and a change of its shape slides the whole map along it).
//
// The standard's side is given at registered positions (register_side.h): the correspondent of a patient vertex is
// its closest point on the registered standard surface, and its parameters are interpolated there.
#include <Eigen/Core>
#include <vector>

#include "core/mesh/sides.h"

namespace facehex {

// Boundary triangles of the tets T (#T x 4) whose three corners lie on `side` (side_mask #V), oriented outwards.
Eigen::MatrixXi side_triangles(const Eigen::MatrixXi& T, const Eigen::VectorXi& side_mask, Side side);

struct SideCorrespondence {
  std::vector<int> vertices;  // patient vertices on the side and on no other side
  Eigen::MatrixXd uvw;        // #vertices x 3: the standard's parameters at their correspondents
  Eigen::VectorXd distance;   // #vertices: mm from each vertex to the registered standard surface
  // #vertices: 1 where the correspondent lies on the rim of the standard's side (its edges of one triangle): the
  // vertex lies beyond where the standard's side ends, and many such vertices share the rim's values.
  std::vector<char> on_rim;
};

// standard_X: #Vs x 3 positions of the standard's domain vertices after registration onto the patient (only those on
// the side matter); standard_F: the standard's side triangles (side_triangles); standard_uvw: #Vs x 3.
// patient_V: #Vp x 3, patient_mask: #Vp.
SideCorrespondence side_correspondence(const Eigen::MatrixXd& standard_X, const Eigen::MatrixXi& standard_F,
                                       const Eigen::MatrixXd& standard_uvw, const Eigen::MatrixXd& patient_V,
                                       const Eigen::VectorXi& patient_mask, Side side);

}  // namespace facehex
