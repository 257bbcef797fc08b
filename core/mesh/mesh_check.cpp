#include "core/mesh/mesh_check.h"

#include "core/mesh/tet_laplacian.h"
#include "core/mesh/tet_topology.h"
#include "core/util/error.h"

namespace facehex {

TetMeshCheck check_and_orient_tet_mesh(VolumeMesh& mesh, const std::string& source) {
  TetMeshCheck check;
  if (mesh.num_cells() == 0) throw Error(source, "the mesh has no cells");
  if (!mesh.is_tet_mesh()) throw Error(source, "expected a tetrahedral model, found hexahedra or wedges");
  Eigen::MatrixXi T = mesh.tets();
  if (T.minCoeff() < 0 || T.maxCoeff() >= mesh.num_vertices()) throw Error(source, "a tet refers to a missing node");
  const Eigen::VectorXd vol = tet_volumes(mesh.V, T);
  const double tiny = 1e-12 * vol.cwiseAbs().mean();
  const long positive = (vol.array() > tiny).count(), negative = (vol.array() < -tiny).count();
  const long degenerate = vol.size() - positive - negative;
  if (degenerate > 0)
    throw Error(source, std::to_string(degenerate) + " tets have zero volume (degenerate); remesh the model");
  if (positive > 0 && negative > 0)
    throw Error(source, std::to_string(std::min(positive, negative)) + " of " + std::to_string(vol.size()) +
                            " tets are inverted (mixed orientation)");
  if (negative > 0) {
    T.col(1).swap(T.col(2));
    mesh.C.leftCols(4) = T;
    check.reoriented = true;
  }
  const TetFaceAdjacency adjacency = tet_face_adjacency(T);
  const BoundaryFaces& boundary = adjacency.boundary;
  if (boundary.nonmanifold_faces > 0)
    throw Error(source, std::to_string(boundary.nonmanifold_faces) +
                            " faces are shared by three or more tets "
                            "(non-manifold mesh)");
  Eigen::VectorXi component;
  const int components = tet_components(adjacency.neighbors, component);
  if (components > 1)
    throw Error(source, "the model has " + std::to_string(components) +
                            " separate parts; keep one connected solid (the parameterization maps one block)");
  check.boundary_faces = static_cast<int>(boundary.F.rows());
  check.volume = vol.cwiseAbs().sum();
  return check;
}

}  // namespace facehex
