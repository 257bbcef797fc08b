#pragma once
// Per-vertex side masks (sides.h) from per-face side labels.
#include <Eigen/Core>

namespace facehex {

// #V mask: the OR of side_bit(side(f)) over the faces around each vertex. F is #F x 3 (or x 4); side(f) is a Side, or
// -1 for a face on no side.
Eigen::VectorXi side_mask_from_faces(int num_vertices, const Eigen::MatrixXi& F, const Eigen::VectorXi& side);

}  // namespace facehex
