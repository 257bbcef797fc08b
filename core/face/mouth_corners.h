#pragma once
// The mouth corners (cheilion right and left) on the skin, from the mouth line traced out from the mid-sagittal plane.
//
// Frame as in face_landmarks.h: +x the side named left (landmark_file.h; the right corner lies at -x), +y anterior, +z
// superior.
//  - the skin's front near the mouth as a height field: for 1 mm cells of (x, z), the most anterior skin vertex; the
//    depth y at (x, z) is the mean of those cells' y weighted by a Gaussian of 1 mm over the distance in (x, z)
//    (within 3 mm; none where no cell is that near), so that a column's profile is smooth between the mesh's vertices;
//  - in a column (fixed x, z every 1 mm around the stomion), the slope s(z) = dy/dz: how fast the skin recedes going
//    down. The mouth line is where the skin turns in under the upper lip: the steepest point of the column, and its
//    contrast is s there minus the median of s over the 25 mm of the column around it (the face's own slant);
//  - on the mid-sagittal plane the line starts at the steepest point between the stomion and the labrale superius;
//    in each next column, 1 mm further out, it is the steepest point within 2 mm in z of the previous one. It is
//    followed until its contrast falls below 0.2 (the lips have ended in the cheek), the height field ends or 50 mm
//    from the plane (beyond the widest adult mouth); the corner is the outermost point where the contrast is at
//    least 0.7 (the skin recedes 0.7 mm per mm down more steeply than around it), moved out to where it falls to 0.7
//    (linear between the two columns). On lips too flat for that, none.
#include <Eigen/Core>
#include <optional>
#include <utility>
#include <vector>

namespace facehex {

// V #V x 3; skin: indices of the skin vertices (side w1); x_mid: the mid-sagittal plane; stomion and labrale
// superius as found on the profile. Returns (right corner, left corner), or none unless both are found.
std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> mouth_corners(const Eigen::MatrixXd& V,
                                                                         const std::vector<int>& skin, double x_mid,
                                                                         const Eigen::Vector3d& stomion,
                                                                         const Eigen::Vector3d& labrale_superius);

}  // namespace facehex
