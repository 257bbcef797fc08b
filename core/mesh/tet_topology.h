#pragma once
// Combinatorics of tetrahedral meshes. T is #T x 4 (see mesh.h).
#include <Eigen/Core>
#include <vector>

namespace facehex {

// Boundary triangles (faces used by exactly one tet), #B x 3, oriented with the right-hand normal pointing out of
// the tet they belong to (out of the mesh, for positively oriented tets), and for each the tet it belongs to.
// Faces used by more than two tets are reported through nonmanifold_faces (count), not returned.
struct BoundaryFaces {
  Eigen::MatrixXi F;          // #B x 3
  Eigen::VectorXi tet;        // #B
  int nonmanifold_faces = 0;  // faces shared by 3 or more tets
};

// Tet-tet adjacency across faces: #T x 4, entry (t, i) is the tet sharing the face opposite vertex i of t, or -1
// (a boundary face, or a face of three or more tets).
struct TetFaceAdjacency {
  Eigen::MatrixXi neighbors;  // #T x 4
  BoundaryFaces boundary;
};
// Both from one sort of the faces; boundary_faces and tet_face_neighbors return one part of it.
TetFaceAdjacency tet_face_adjacency(const Eigen::MatrixXi& T);
BoundaryFaces boundary_faces(const Eigen::MatrixXi& T);
Eigen::MatrixXi tet_face_neighbors(const Eigen::MatrixXi& T);

// Connected components of tets through shared faces (neighbors: tet_face_neighbors); returns the component id of
// each tet (#T) and the count.
int tet_components(const Eigen::MatrixXi& neighbors, Eigen::VectorXi& component);

// Per-vertex flag (#V): 1 for vertices on a boundary face.
std::vector<char> boundary_vertex_flags(int num_vertices, const Eigen::MatrixXi& boundary_F);

}  // namespace facehex
