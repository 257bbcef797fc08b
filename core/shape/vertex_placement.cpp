#include "core/shape/vertex_placement.h"

namespace facehex {

std::vector<char> within_cell_rings(const VolumeMesh& mesh, std::vector<char> marked, int rings) {
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> grown = marked;
    for (int c = 0; c < mesh.num_cells(); ++c) {
      bool touches = false;
      for (int i = 0; i < node_count(mesh.types[c]); ++i) touches |= marked[mesh.C(c, i)] != 0;
      if (touches)
        for (int i = 0; i < node_count(mesh.types[c]); ++i) grown[mesh.C(c, i)] = 1;
    }
    marked.swap(grown);
  }
  return marked;
}

VertexPlacement spatial_placement(const Eigen::MatrixXd& V, const std::vector<char>& fixed) {
  VertexPlacement placement;
  placement.p = V;
  placement.movable.resize(fixed.size());
  for (size_t v = 0; v < fixed.size(); ++v)
    placement.movable[v] = fixed[v] ? Eigen::Matrix3d::Zero().eval() : Eigen::Matrix3d::Identity().eval();
  placement.place = [](int, const Eigen::Vector3d& q, Eigen::Vector3d& x, Eigen::Matrix3d& dxdq) {
    x = q;
    dxdq.setIdentity();
    return true;
  };
  return placement;
}

}  // namespace facehex
