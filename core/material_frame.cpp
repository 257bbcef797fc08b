#include "core/material_frame.h"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <cmath>

namespace facehex {

Eigen::Matrix3d parametric_gradient(const Eigen::MatrixXd& X, const Eigen::MatrixXd& P) {
  // Centring removes the constant term of the affine fit, leaving X_c G^T = P_c.
  const Eigen::MatrixXd Xc = X.rowwise() - X.colwise().mean();
  const Eigen::MatrixXd Pc = P.rowwise() - P.colwise().mean();
  return Xc.completeOrthogonalDecomposition().solve(Pc).transpose();
}

std::optional<Eigen::Matrix3d> frame_from_gradient(const Eigen::Matrix3d& G) {
  const Eigen::Vector3d gu = G.row(0), gv = G.row(1), gw = G.row(2);
  // A relative test: |det G| / (|gu| |gv| |gw|) is the volume of the parallelepiped of the unit gradients.
  const double scale = gu.norm() * gv.norm() * gw.norm();
  if (!(scale > 0) || !(std::abs(G.determinant()) > 1e-9 * scale)) return std::nullopt;
  const Eigen::Vector3d e3 = gw.normalized();
  Eigen::Vector3d e1 = (gu - gu.dot(e3) * e3).normalized();
  if (e3.cross(e1).dot(gv) < 0) e1 = -e1;
  Eigen::Matrix3d frame;
  frame << e1, e3.cross(e1), e3;
  return frame;
}

MaterialFrames material_frames(const VolumeMesh& mesh, const Eigen::MatrixXd& uvw) {
  const int nc = mesh.num_cells();
  MaterialFrames frames;
  frames.e1.resize(nc, 3);
  frames.e2.resize(nc, 3);
  frames.e3.resize(nc, 3);
  for (int c = 0; c < nc; ++c) {
    const int n = node_count(mesh.types[c]);
    Eigen::MatrixXd X(n, 3), P(n, 3);
    for (int k = 0; k < n; ++k) {
      X.row(k) = mesh.V.row(mesh.C(c, k));
      P.row(k) = uvw.row(mesh.C(c, k));
    }
    std::optional<Eigen::Matrix3d> frame = frame_from_gradient(parametric_gradient(X, P));
    if (!frame) {
      frames.degenerate.push_back(c);
      frame = Eigen::Matrix3d::Identity();
    }
    frames.e1.row(c) = frame->col(0).transpose();
    frames.e2.row(c) = frame->col(1).transpose();
    frames.e3.row(c) = frame->col(2).transpose();
  }
  return frames;
}

}  // namespace facehex
