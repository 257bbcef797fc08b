#include "core/tet_laplacian.h"

#include <Eigen/Dense>
#include <vector>

namespace facehex {
namespace {

// Gradients of the four hat functions of tet t as the rows of a 4 x 3 matrix, and the tet's signed volume.
void hat_gradients(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, int t, Eigen::Matrix<double, 4, 3>& grads,
                   double& volume) {
  const Eigen::RowVector3d p0 = V.row(T(t, 0));
  Eigen::Matrix3d D;  // columns are the edges p1-p0, p2-p0, p3-p0
  for (int k = 0; k < 3; ++k) D.col(k) = (V.row(T(t, k + 1)) - p0).transpose();
  const double det = D.determinant();
  volume = det / 6.0;
  // Barycentric coordinates (l1,l2,l3) = D^-1 (x - p0): their gradients are the rows of D^-1.
  const Eigen::Matrix3d Dinv = D.inverse();
  grads.bottomRows<3>() = Dinv;
  grads.row(0) = -Dinv.colwise().sum();
}

}  // namespace

Eigen::VectorXd tet_volumes(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  Eigen::VectorXd vol(T.rows());
  for (int t = 0; t < T.rows(); ++t) {
    const Eigen::Vector3d p0 = V.row(T(t, 0)).transpose();
    const Eigen::Vector3d a = V.row(T(t, 1)).transpose() - p0, b = V.row(T(t, 2)).transpose() - p0,
                          c = V.row(T(t, 3)).transpose() - p0;
    vol(t) = a.dot(b.cross(c)) / 6.0;
  }
  return vol;
}

SparseMatrix gradient_operator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(T.rows()) * 12);
  Eigen::Matrix<double, 4, 3> g;
  double volume = 0;
  for (int t = 0; t < T.rows(); ++t) {
    hat_gradients(V, T, t, g, volume);
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d) triplets.emplace_back(3 * t + d, T(t, i), g(i, d));
  }
  SparseMatrix G(3 * T.rows(), V.rows());
  G.setFromTriplets(triplets.begin(), triplets.end());
  return G;
}

SparseMatrix cotangent_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<size_t>(T.rows()) * 16);
  Eigen::Matrix<double, 4, 3> g;
  double volume = 0;
  for (int t = 0; t < T.rows(); ++t) {
    hat_gradients(V, T, t, g, volume);
    // Element stiffness |vol| g g^T; its off-diagonal entries are -(1/6) l_k cot(theta_k).
    const Eigen::Matrix4d Ke = std::abs(volume) * (g * g.transpose());
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) triplets.emplace_back(T(t, i), T(t, j), Ke(i, j));
  }
  SparseMatrix K(V.rows(), V.rows());
  K.setFromTriplets(triplets.begin(), triplets.end());
  return K;
}

Eigen::VectorXd dual_volumes(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  Eigen::VectorXd dual = Eigen::VectorXd::Zero(V.rows());
  const Eigen::VectorXd vol = tet_volumes(V, T);
  for (int t = 0; t < T.rows(); ++t)
    for (int i = 0; i < 4; ++i) dual(T(t, i)) += std::abs(vol(t)) / 4.0;
  return dual;
}

SparseMatrix normalized_laplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  const Eigen::VectorXd inv_dual = dual_volumes(V, T).cwiseInverse();
  return inv_dual.asDiagonal() * cotangent_stiffness(V, T);
}

Eigen::MatrixXd tet_gradients(const SparseMatrix& G, const Eigen::VectorXd& u) {
  const Eigen::VectorXd g = G * u;
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(g.data(), g.size() / 3, 3);
}

}  // namespace facehex
