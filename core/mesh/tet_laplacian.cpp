#include "core/mesh/tet_laplacian.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
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

GradientMatrix gradient_operator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  // Filled in place, without a triplet list: row 3t+d holds tet t's four hat-gradient components d, in ascending
  // vertex order (Eigen's compressed storage keeps each row's columns sorted).
  GradientMatrix G(3 * T.rows(), V.rows());
  G.resizeNonZeros(12 * T.rows());
  int* outer = G.outerIndexPtr();
  int* inner = G.innerIndexPtr();
  double* value = G.valuePtr();
  for (Eigen::Index r = 0; r <= 3 * T.rows(); ++r) outer[r] = static_cast<int>(4 * r);
#pragma omp parallel for schedule(static)
  for (int t = 0; t < T.rows(); ++t) {
    Eigen::Matrix<double, 4, 3> g;
    double volume = 0;
    hat_gradients(V, T, t, g, volume);
    std::array<int, 4> local = {0, 1, 2, 3};
    std::sort(local.begin(), local.end(), [&](int a, int b) { return T(t, a) < T(t, b); });
    for (int d = 0; d < 3; ++d)
      for (int k = 0; k < 4; ++k) {
        const size_t at = 12 * static_cast<size_t>(t) + 4 * d + k;
        inner[at] = T(t, local[k]);
        value[at] = g(local[k], d);
      }
  }
  return G;
}

SparseMatrix cotangent_stiffness(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T) {
  // Assembled into its final pattern rather than through a triplet list (16 #T entries, sorted and summed): the
  // pattern is each vertex's neighbours through its tets, and each element entry is added at its place, found by
  // a search in its short column. Each column recomputes the gradients of its own tets, so columns are filled in
  // parallel, and no list of all element entries is allocated, sorted and summed.
  const int n = static_cast<int>(V.rows());
  std::vector<int> tets_start(static_cast<size_t>(n) + 1, 0), vertex_tets(4 * static_cast<size_t>(T.rows()));
  for (Eigen::Index i = 0; i < T.size(); ++i) ++tets_start[T(i) + 1];
  for (int v = 0; v < n; ++v) tets_start[v + 1] += tets_start[v];
  {
    std::vector<int> next(tets_start.begin(), tets_start.end() - 1);
    for (int t = 0; t < T.rows(); ++t)
      for (int i = 0; i < 4; ++i) vertex_tets[next[T(t, i)]++] = t;
  }
  // Column v's rows: v and its neighbours, sorted (K is symmetric, so columns and rows have the same pattern).
  std::vector<int> col_start(static_cast<size_t>(n) + 1, 0);
  // Column v has at most 1 + 3 * (its tets) rows: room for that at rows[v + 3 * tets_start[v]].
  auto room = [&](int v) { return static_cast<size_t>(v) + 3 * static_cast<size_t>(tets_start[v]); };
  std::vector<int> rows(room(n));
#pragma omp parallel for schedule(static)
  for (int v = 0; v < n; ++v) {
    int* first = rows.data() + room(v);
    int* last = first;
    *last++ = v;
    for (int k = tets_start[v]; k < tets_start[v + 1]; ++k)
      for (int i = 0; i < 4; ++i)
        if (T(vertex_tets[k], i) != v) *last++ = T(vertex_tets[k], i);
    std::sort(first, last);
    col_start[v + 1] = static_cast<int>(std::unique(first, last) - first);
  }
  for (int v = 0; v < n; ++v) col_start[v + 1] += col_start[v];
  SparseMatrix K(n, n);
  K.resizeNonZeros(col_start[n]);
  std::copy(col_start.begin(), col_start.end(), K.outerIndexPtr());
  for (int v = 0; v < n; ++v)
    std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(room(v)), col_start[v + 1] - col_start[v],
                K.innerIndexPtr() + col_start[v]);
  std::fill_n(K.valuePtr(), col_start[n], 0.0);
  const int* inner = K.innerIndexPtr();
  double* value = K.valuePtr();
#pragma omp parallel for schedule(static)
  for (int v = 0; v < n; ++v) {
    Eigen::Matrix<double, 4, 3> g;
    double volume = 0;
    for (int k = tets_start[v]; k < tets_start[v + 1]; ++k) {
      const int t = vertex_tets[k];
      hat_gradients(V, T, t, g, volume);
      int j = 0;
      while (T(t, j) != v) ++j;
      // Element stiffness |vol| g g^T; its off-diagonal entries are -(1/6) l_k cot(theta_k).
      for (int i = 0; i < 4; ++i) {
        const int* at = std::lower_bound(inner + col_start[v], inner + col_start[v + 1], T(t, i));
        value[at - inner] += std::abs(volume) * g.row(i).dot(g.row(j));
      }
    }
  }
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

Eigen::MatrixXd tet_gradients(const GradientMatrix& G, const Eigen::VectorXd& u) {
  const Eigen::VectorXd g = G * u;
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(g.data(), g.size() / 3, 3);
}

}  // namespace facehex
