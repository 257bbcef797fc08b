#pragma once
// The local material frame of each cell of a mapped mesh: the orthonormalized directions of the three parametric
// fields (paper 5: "assign the hexahedral meshes with anisotropic materials"), for fibre-like soft-tissue materials.
//
// Per cell, the parametric coordinates p = (u, v, w) at its vertices (point data "uvw" on a patient hex mesh) are
// fitted by an affine map p ~ p_c + G (x - x_c) in the least-squares sense; the rows of G are the gradients of u, v
// and w over the cell (exact for an affinely mapped cell). The frame is then, by Gram-Schmidt starting from w:
//
//   e3 = grad w / |grad w|                          depth: bone -> skin, normal to the layers (the best-resolved field)
//   e1 = +-(grad u minus its e3 part), normalized   lateral: along the u lines within the layer
//   e2 = e3 x e1                                    up: the sign of e1 is chosen so that e2 . grad v > 0
//
// so (e1, e2, e3) is orthonormal and right-handed, e2 points towards increasing v and e3 towards increasing w. Since
// u (-x -> +x), v (bottom -> top) and w (bone -> skin, i.e. anterior) form a LEFT-handed triple in a scan where the
// face looks towards +y, e1 is usually -grad u there: it points towards the u0 side (-x). In a mirrored scan it is
// +grad u. Only the sign of grad v is used: v need not be orthogonal to u and w for the frame to be defined.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "core/mesh/mesh.h"

namespace facehex {

// The frames of all cells, one unit vector per row.
struct MaterialFrames {
  Eigen::MatrixXd e1, e2, e3;  // #C x 3 each
  // Cells whose parametric coordinates do not span three directions (a flat cell, or a degenerate parameterization);
  // they get the global axes (x, y, z) so that a forced export still has a valid frame. Ascending.
  std::vector<int> degenerate;
};

// Least-squares gradient G (3 x 3, row i = gradient of parametric coordinate i) of the n values P (n x 3) given at the
// n points X (n x 3), n >= 4. Zero where the points do not span 3-D (minimum-norm solution).
Eigen::Matrix3d parametric_gradient(const Eigen::MatrixXd& X, const Eigen::MatrixXd& P);

// The frame (columns e1, e2, e3) of a parametric gradient as described above. A u or v pinned over the cell (zero
// gradient, a feature line) is left out: e1 comes from the other. nullopt when grad w vanishes, when both u and v
// do, or when all three are present but (numerically) dependent: |det G| <= 1e-9 |grad u| |grad v| |grad w|.
std::optional<Eigen::Matrix3d> frame_from_gradient(const Eigen::Matrix3d& G);

// Frames of every cell of `mesh` from the per-vertex parametric coordinates uvw (#V x 3).
MaterialFrames material_frames(const VolumeMesh& mesh, const Eigen::MatrixXd& uvw);

}  // namespace facehex
