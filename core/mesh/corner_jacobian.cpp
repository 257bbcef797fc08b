#include "core/mesh/corner_jacobian.h"

#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <iterator>
#include <limits>

namespace facehex {

namespace {

// Each row (k; a, b, c). The orders follow from mesh.h. The hex bottom (0,1,2,3) turns counter-clockwise seen from
// the top, so (next, previous, up) is right-handed at a bottom node and (previous, next, down) at a top node. The
// wedge bottom (0,1,2) turns clockwise seen from the top, so there it is (previous, next, up) at a bottom node and
// (next, previous, down) at a top node. Tet corners are the even permutations of (0,1,2,3) starting with k.
constexpr std::array<std::array<int, 4>, 8> kHexCorners = {
    {{0, 1, 3, 4}, {1, 2, 0, 5}, {2, 3, 1, 6}, {3, 0, 2, 7}, {4, 7, 5, 0}, {5, 4, 6, 1}, {6, 5, 7, 2}, {7, 6, 4, 3}}};
constexpr std::array<std::array<int, 4>, 6> kWedgeCorners = {
    {{0, 2, 1, 3}, {1, 0, 2, 4}, {2, 1, 0, 5}, {3, 4, 5, 0}, {4, 5, 3, 1}, {5, 3, 4, 2}}};
constexpr std::array<std::array<int, 4>, 4> kTetCorners = {{{0, 1, 2, 3}, {1, 2, 0, 3}, {2, 0, 1, 3}, {3, 0, 2, 1}}};

// Makes the ideal element's scaled Jacobian 1 (see the header).
double scaled_jacobian_factor(CellType type) {
  if (type == CellType::Tet) return std::sqrt(2.0);
  if (type == CellType::Wedge) return 2.0 / std::sqrt(3.0);
  return 1.0;
}

}  // namespace

CellNodes ideal_cell(CellType type) {
  const double h = std::sqrt(3.0) / 2;
  CellNodes X = CellNodes::Zero();
  if (type == CellType::Tet)
    X.topRows(4) << 0, 0, 0, 1, 0, 0, 0.5, h, 0, 0.5, h / 3, std::sqrt(2.0 / 3);
  else if (type == CellType::Wedge)
    X.topRows(6) << 0, 0, 0, 0.5, h, 0, 1, 0, 0, 0, 0, 1, 0.5, h, 1, 1, 0, 1;
  else
    X << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  return X;
}

CellNodes cell_nodes(const VolumeMesh& mesh, int cell) {
  CellNodes X = CellNodes::Zero();
  for (int i = 0; i < node_count(mesh.types[cell]); ++i) X.row(i) = mesh.V.row(mesh.C(cell, i));
  return X;
}

const std::array<int, 4>& corner_nodes(CellType type, int k) {
  assert(k >= 0 && k < node_count(type));
  if (type == CellType::Tet) return kTetCorners[k];
  if (type == CellType::Wedge) return kWedgeCorners[k];
  return kHexCorners[k];
}

Eigen::Matrix3d corner_jacobian(CellType type, const CellNodes& X, int k) {
  const std::array<int, 4>& n = corner_nodes(type, k);
  Eigen::Matrix3d A;
  for (int i = 0; i < 3; ++i) A.col(i) = (X.row(n[i + 1]) - X.row(n[0])).transpose();
  return A;
}

namespace {

// d N_i / d(natural coordinates) at point p, rows = nodes: hex on the unit cube [0,1]^3 (node i at the cube corner of
// the same VTK index), wedge on (r, s) in the unit triangle times t in [0, 1].
SampleWeights shape_derivatives(CellType type, const Eigen::Vector3d& p) {
  SampleWeights d = SampleWeights::Zero();
  if (type == CellType::Hex) {
    const int cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (int i = 0; i < 8; ++i)
      for (int a = 0; a < 3; ++a) {
        double v = cube[i][a] ? 1.0 : -1.0;
        for (int b = 0; b < 3; ++b)
          if (b != a) v *= cube[i][b] ? p(b) : 1 - p(b);
        d(i, a) = v;
      }
  } else if (type == CellType::Wedge) {
    const double r = p(0), s = p(1), t = p(2);
    const double tri[3] = {1 - r - s, r, s};
    const double dtri[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
    for (int i = 0; i < 3; ++i) {
      d.row(i) << dtri[i][0] * (1 - t), dtri[i][1] * (1 - t), -tri[i];
      d.row(i + 3) << dtri[i][0] * t, dtri[i][1] * t, tri[i];
    }
  }
  return d;
}

std::vector<SampleWeights> sample_weights(CellType type) {
  const double lo = 0.5 - 0.5 / std::sqrt(3.0), hi = 0.5 + 0.5 / std::sqrt(3.0);
  std::vector<Eigen::Vector3d> points;
  if (type == CellType::Hex) {
    points.emplace_back(0.5, 0.5, 0.5);
    for (double z : {lo, hi})
      for (double y : {lo, hi})
        for (double x : {lo, hi}) points.emplace_back(x, y, z);
  } else if (type == CellType::Wedge) {
    for (double t : {lo, hi})
      for (const auto& [r, s] :
           {std::pair{1 / 6.0, 1 / 6.0}, {2 / 3.0, 1 / 6.0}, {1 / 6.0, 2 / 3.0}, {1 / 3.0, 1 / 3.0}})
        points.emplace_back(r, s, t);
  }
  const CellNodes ideal = ideal_cell(type);
  std::vector<SampleWeights> weights;
  for (const Eigen::Vector3d& p : points) {
    const SampleWeights d = shape_derivatives(type, p);
    const Eigen::Matrix3d ideal_jacobian = ideal.transpose() * d;  // constant over the ideal cell
    weights.push_back(d * ideal_jacobian.inverse());
  }
  return weights;
}

}  // namespace

const std::vector<SampleWeights>& interior_sample_weights(CellType type) {
  static const std::vector<SampleWeights> hex = sample_weights(CellType::Hex), wedge = sample_weights(CellType::Wedge),
                                          none;
  return type == CellType::Hex ? hex : type == CellType::Wedge ? wedge : none;
}

Eigen::Matrix3d hex_center_jacobian(const CellNodes& X) {
  return X.transpose() * interior_sample_weights(CellType::Hex).front();
}

CornerValues corner_determinants(CellType type, const CellNodes& X) {
  CornerValues d = CornerValues::Zero();
  for (int k = 0; k < node_count(type); ++k) d(k) = corner_jacobian(type, X, k).determinant();
  return d;
}

namespace {

// det(A) / (|a_1| |a_2| |a_3|), in [-1, 1]; 0 for a zero-length edge.
double unit_determinant(const Eigen::Matrix3d& A, double det) {
  const double lengths = A.col(0).norm() * A.col(1).norm() * A.col(2).norm();
  return lengths > 0 ? det / lengths : 0.0;
}

}  // namespace

CellJacobians cell_jacobians(CellType type, const CellNodes& X) {
  CellJacobians j{std::numeric_limits<double>::infinity(), 1};  // det(A) / lengths lies in [-1, 1] (Hadamard)
  for (int k = 0; k < node_count(type); ++k) {
    const Eigen::Matrix3d A = corner_jacobian(type, X, k);
    const double det = A.determinant();
    j.min_determinant = std::min(j.min_determinant, det);
    j.scaled_jacobian = std::min(j.scaled_jacobian, unit_determinant(A, det));
  }
  const std::vector<SampleWeights>& samples = interior_sample_weights(type);
  for (size_t s = 0; s < samples.size(); ++s) {
    const Eigen::Matrix3d J = X.transpose() * samples[s];
    const double det = J.determinant();
    j.min_determinant = std::min(j.min_determinant, det);
    // A hex's centre (its first sample) counts in the scaled Jacobian too, as Verdict's.
    if (s == 0 && type == CellType::Hex) j.scaled_jacobian = std::min(j.scaled_jacobian, unit_determinant(J, det));
  }
  j.scaled_jacobian *= scaled_jacobian_factor(type);
  return j;
}

double min_corner_determinant(CellType type, const CellNodes& X) { return cell_jacobians(type, X).min_determinant; }

double scaled_jacobian(CellType type, const CellNodes& X) { return cell_jacobians(type, X).scaled_jacobian; }

bool is_unusable(const CellJacobians& j) {
  return j.min_determinant <= 0 || j.scaled_jacobian < kDegenerateScaledJacobian;
}

bool is_unusable(CellType type, const CellNodes& X) { return is_unusable(cell_jacobians(type, X)); }

CornerJacobianCheck check_corner_jacobians(const VolumeMesh& mesh) {
  CornerJacobianCheck check;
  check.min_determinant.resize(mesh.num_cells());
  for (int c = 0; c < mesh.num_cells(); ++c) {
    const CellNodes X = cell_nodes(mesh, c);
    check.min_determinant(c) = min_corner_determinant(mesh.types[c], X);
    if (check.min_determinant(c) <= 0)
      check.inverted.push_back(c);
    else if (scaled_jacobian(mesh.types[c], X) < kDegenerateScaledJacobian)
      check.degenerate.push_back(c);
  }
  return check;
}

std::vector<int> CornerJacobianCheck::unusable() const {
  std::vector<int> cells;
  std::merge(inverted.begin(), inverted.end(), degenerate.begin(), degenerate.end(), std::back_inserter(cells));
  return cells;
}

}  // namespace facehex
