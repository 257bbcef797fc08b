#pragma once
// The six sides of a layered hex-dominant shell (a standard facial mesh), found from its structure, not by hand.
//
// Through-thickness test: from a boundary face, step to the opposite face of its cell (hex: the parallel quad; wedge:
// the other triangle) and on through the neighbouring cells until the boundary is reached again. On the skin and
// bone sides this "chord" crosses the element layers of the shell (the same number everywhere in a layered shell);
// on the cut sides and the walls of openings (eyes, nostrils, mouth) it runs along the shell for more elements (or
// cannot be continued through a wedge).
//  - chords of the most common length (at most max_layers cells): the face is on the outer (w1) or inner (w0) side;
//    of the two ends of a chord, the outer one is the end whose outward normal points more away from frame.center.
//    The skin and the bone are each one surface, connected from cell to cell (through edges shared by faces of two
//    cells); a patch of such faces apart from the largest (chords across a pillar between two openings, such as the
//    columella between the nostrils) lies in the openings' walls and goes to the strips.
//  - the remaining faces form strips; the largest connected strip is the cut rim, split by its face normals
//    against frame.up into the top cut (v1: n.up > cos 60deg), the bottom cut (v0: n.up < -cos 60deg) and the two
//    lateral ends (u0 / u1 by the sign of (x - center).lateral). Smaller strips are walls of openings: left free.
//  - a vertex on two opposite sides of one field (where skin and bone sides touch at the rim of an opening) is left
//    free for that field.
#include <Eigen/Core>
#include <array>

#include "core/mesh/mesh.h"

namespace facehex {

struct ShellFrame {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();    // a point behind the face, inside the head
  Eigen::Vector3d lateral = Eigen::Vector3d::UnitX();  // from the u0 end towards the u1 end
  Eigen::Vector3d up = Eigen::Vector3d::UnitZ();       // towards the top cut
  int max_layers = 8;
};

struct ShellSides {
  Eigen::VectorXi side_mask;            // #V, bits as in sides.h
  std::array<int, 6> faces_per_side{};  // boundary faces labelled with each side
  int opening_faces = 0;                // faces on the walls of openings (no side)
  int layers = 0;                       // element layers through the thickness (the chord length)
  int conflicting_vertices = 0;         // on both opposite sides of a field: left free for that field
};

ShellSides label_shell_sides(const VolumeMesh& mesh, const ShellFrame& frame);

// A frame for a face-like shell in the FaceHex convention (+x lateral, +y anterior, +z superior): the centre is at
// the middle of the x and z ranges and at the back of the y range.
ShellFrame default_shell_frame(const Eigen::MatrixXd& V);

}  // namespace facehex
