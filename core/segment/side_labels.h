#pragma once
// Which of the six sides (core/sides.h) each boundary face of the patient model lies on, decided by how the face was
// made:
//   on the top cut plane                  -> v1      on the bottom or the jaw cut plane -> v0
//   on the posterior cut plane            -> u0 if x < centre_x, u1 otherwise
//   ("on" = centroid within plane_tolerance of the plane and normal within ~45 degrees of the plane's)
//   anywhere else: closer to the air outside the head than to the non-model tissue/bone inside -> w1 (skin),
//                  otherwise -> w0 (bone, or the depth limit).
// Then every side is made one connected patch: smaller patches of a side (specks at creases, where a cut plane
// meets the skin at a grazing angle) take the side of the faces around them.
#include <Eigen/Core>

#include "core/mesh/mesh.h"
#include "core/mesh/sides.h"
#include "core/segment/face_cuts.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// air_distance / inner_distance: distance (mm) to the air outside the head / to the head voxels not in the model.
// plane_tolerance (mm): how far from a cut plane a face centroid may be and still be on it.
Eigen::VectorXi classify_sides(const SurfaceMesh& surface, const FaceCuts& cuts, const Field& air_distance,
                               const Field& inner_distance, double plane_tolerance);

// Relabels all but the largest edge-connected patch of each side with the sides around them.
void merge_side_islands(const Eigen::MatrixXi& faces, Eigen::VectorXi& sides);

// Number of edge-connected patches of the faces with sides(f) == side (all faces when side < 0).
int count_patches(const Eigen::MatrixXi& faces, const Eigen::VectorXi& sides, int side);

}  // namespace facehex
