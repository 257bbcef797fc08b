#include "core/shape/vertex_placement.h"

namespace facehex {

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
