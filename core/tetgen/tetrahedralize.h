#pragma once
// The one wrapper around TetGen 1.5 (libtet, linked as a library).
#include <Eigen/Core>

#include "core/mesh/mesh.h"
#include "core/util/error.h"

namespace facehex {

struct TetrahedralizeOptions {
  double target_edge_length = 2.0;     // mm; gives TetGen's maximum tet volume (that of a regular tet of this edge)
  double max_radius_edge_ratio = 1.5;  // TetGen -q quality bound
  double min_dihedral_deg = 10.0;      // TetGen -q/… second bound
  bool preserve_surface = false;       // TetGen -Y: no Steiner points on the boundary
  // Refuse, before TetGen starts, a surface whose predicted tet count (predicted_tet_count) is above this; 0: the
  // count this machine's memory can carry through the whole pipeline (max_tets_for_memory).
  double max_tets = 0;
};

// About how many tets TetGen makes in `volume` mm^3 at these options (quality meshes pack fewer, larger-than-ideal
// tets near the bound, and more near the surface; the factor is calibrated on segmented faces).
double predicted_tet_count(double volume, const TetrahedralizeOptions& options);
// The edge length at which predicted_tet_count(volume) is `tets` (the other options as given).
double edge_length_for_tet_count(double volume, double tets, const TetrahedralizeOptions& options);
// The volume a closed, consistently oriented triangle surface encloses (mm^3), negative if its faces are oriented
// inwards.
double enclosed_volume(const SurfaceMesh& surface);
// How many tets a transfer can handle with this machine's physical memory.
double max_tets_for_memory();

struct TetrahedralizeResult {
  VolumeMesh mesh;                  // positively oriented tets (see mesh.h)
  Eigen::MatrixXi boundary_faces;   // #B x 3 boundary triangles of the tet mesh, outward oriented
  Eigen::VectorXi boundary_labels;  // #B label of the input face each boundary triangle lies on (0 if unlabelled)
};

// The surface given to TetGen crosses itself (TetGen's -d check found intersecting triangles).
class SelfIntersectingSurface : public Error {
 public:
  explicit SelfIntersectingSurface(int triangles)
      : Error("tetgen", "the surface intersects itself (" + std::to_string(triangles) + " intersecting triangles)") {}
};

// Tetrahedralizes a closed, manifold, outward-oriented triangle surface. Face labels of the surface (if any,
// values >= 1) are carried to the boundary triangles of the result. Throws facehex::Error("tetgen", ...) when the
// surface is not closed, would give more tets than options.max_tets, or TetGen fails, SelfIntersectingSurface when it
// intersects itself.
TetrahedralizeResult tetrahedralize(const SurfaceMesh& surface, const TetrahedralizeOptions& options = {});

// As tetrahedralize(), for a surface whose labels are Side + 1 per face (0: on no side, sides.h): also sets the
// mesh's point data "side_mask" from the labelled boundary triangles; a vertex on opposite sides of one field is left
// free for it (clear_opposite_sides, side_mask.h).
TetrahedralizeResult tetrahedralize_with_sides(const SurfaceMesh& surface, const TetrahedralizeOptions& options = {});

}  // namespace facehex
