#include "core/mesh/material_frame.h"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
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
  // A field pinned to one value over the whole cell (a feature line through it) has no gradient there: the frame
  // is then built from the other two. Otherwise the three must span 3-D: |det G| / (|gu| |gv| |gw|) is the volume of
  // the parallelepiped of the unit gradients.
  const double largest = std::max({gu.norm(), gv.norm(), gw.norm()});
  const bool has_u = gu.norm() > 1e-9 * largest, has_v = gv.norm() > 1e-9 * largest;
  if (!(largest > 0) || !(gw.norm() > 1e-9 * largest) || (!has_u && !has_v)) return std::nullopt;
  if (has_u && has_v && !(std::abs(G.determinant()) > 1e-9 * gu.norm() * gv.norm() * gw.norm())) return std::nullopt;
  const Eigen::Vector3d e3 = gw.normalized();
  Eigen::Vector3d e1;
  if (has_u) {
    e1 = (gu - gu.dot(e3) * e3).normalized();
    if (has_v && e3.cross(e1).dot(gv) < 0) e1 = -e1;
  } else {
    const Eigen::Vector3d e2 = (gv - gv.dot(e3) * e3).normalized();
    e1 = e2.cross(e3);
  }
  if (!e1.allFinite()) return std::nullopt;
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
