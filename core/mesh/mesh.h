#pragma once
// Mesh containers shared by every module.
//
// Conventions (libigl style):
//  - V is #V x 3 (double, millimetres), one vertex per row.
//  - T is #T x 4 (int), one tetrahedron per row, POSITIVELY oriented:
//    dot(V1-V0, cross(V2-V0, V3-V0)) > 0  (V3 lies on the side the right-hand normal of (V0,V1,V2) points to).
//  - F is #F x 3 (int), one triangle per row; on a closed surface the right-hand normal points OUT.
//  - Volume meshes store cells in VTK node order:
//      VTK_TETRA (4):      as above.
//      VTK_WEDGE (6):      triangles (0,1,2) and (3,4,5), edges 0-3, 1-4, 2-5; the right-hand normal of (0,1,2)
//                          points AWAY from (3,4,5) (VTK's wedge convention, the reverse of Gmsh/Abaqus/ANSYS).
//      VTK_HEXAHEDRON (8): quads (0,1,2,3) and (4,5,6,7), edges 0-4, 1-5, 2-6, 3-7; the right-hand normal of
//                          (0,1,2,3) points TOWARDS (4,5,6,7).
//    Unused trailing node slots of C hold -1.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace facehex {

enum class CellType : int { Tet = 4, Wedge = 6, Hex = 8 };

inline int node_count(CellType t) { return static_cast<int>(t); }
const char* cell_type_name(CellType t);

using PointData = std::map<std::string, Eigen::MatrixXd>;  // each array #V x k
using CellData = std::map<std::string, Eigen::MatrixXd>;   // each array #C x k
using FieldData = std::map<std::string, Eigen::MatrixXd>;  // each array n x k: facts about the whole mesh

// A tetrahedral or hex-dominant (hex + wedge) volume mesh with attached data arrays.
struct VolumeMesh {
  Eigen::MatrixXd V;            // #V x 3
  Eigen::MatrixXi C;            // #C x 8, VTK node order, unused slots -1
  std::vector<CellType> types;  // #C
  PointData point_data;
  CellData cell_data;
  FieldData field_data;  // e.g. a segmented CT's mid-sagittal plane (core/face/face_landmarks.h)

  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_cells() const { return static_cast<int>(C.rows()); }
  int count(CellType t) const;
  bool is_tet_mesh() const { return num_cells() > 0 && count(CellType::Tet) == num_cells(); }
  // #C x 4 tets; requires is_tet_mesh().
  Eigen::MatrixXi tets() const;
  static VolumeMesh from_tets(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T);
};

// A closed triangle surface with an optional per-face integer label (e.g. which side a face belongs to).
struct SurfaceMesh {
  Eigen::MatrixXd V;       // #V x 3
  Eigen::MatrixXi F;       // #F x 3
  Eigen::VectorXi labels;  // #F, or empty
};

}  // namespace facehex
