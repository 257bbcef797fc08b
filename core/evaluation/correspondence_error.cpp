#include "core/evaluation/correspondence_error.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/fields/constraint_set.h"
#include "core/mesh/hex_to_tets.h"
#include "core/mesh/sides.h"
#include "core/mesh/tet_topology.h"
#include "core/standard/standard_features.h"

namespace facehex {
ErrorSummary summarize_errors(const Eigen::VectorXd& errors) {
  ErrorSummary s;
  s.count = static_cast<int>(errors.size());
  if (s.count == 0) return s;
  std::vector<double> sorted(errors.data(), errors.data() + errors.size());
  std::sort(sorted.begin(), sorted.end());
  s.mean = errors.mean();
  s.max = sorted.back();
  const auto rank = static_cast<size_t>(std::ceil(0.95 * static_cast<double>(s.count)));
  s.p95 = sorted[std::max<size_t>(rank, 1) - 1];
  s.within_1mm = static_cast<double>(std::upper_bound(sorted.begin(), sorted.end(), 1.0) - sorted.begin()) / s.count;
  return s;
}

std::vector<VertexRegion> correspondence_regions(const VolumeMesh& standard, double landmark_radius) {
  const Eigen::VectorXi mask = side_mask_of(standard);
  std::vector<VertexRegion> regions = {{"skin", {}}, {"bone", {}}, {"landmarks", {}}, {"inner face", {}}};
  const int cut_sides = side_bit(U0) | side_bit(U1) | side_bit(V0) | side_bit(V1);
  std::vector<int> cut;
  for (int v = 0; v < standard.num_vertices(); ++v) {
    if (mask(v) & side_bit(W1)) regions[0].vertices.push_back(v);
    if (mask(v) & side_bit(W0)) regions[1].vertices.push_back(v);
    if (mask(v) & cut_sides) cut.push_back(v);
  }
  for (int v = 0; v < standard.num_vertices(); ++v) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const int c : cut) nearest = std::min(nearest, (standard.V.row(v) - standard.V.row(c)).squaredNorm());
    if (nearest >= kInnerFaceDepth * kInnerFaceDepth) regions[3].vertices.push_back(v);
  }
  StandardFeatures features = standard_features(standard);
  for (const int v : regions[0].vertices)
    for (const auto& [name, p] : features.landmarks.points)
      if ((standard.V.row(v).transpose() - p).norm() <= landmark_radius) {
        regions[2].vertices.push_back(v);
        break;
      }
  for (auto& [name, rim] : features.rims) regions.push_back({"rim: " + name, std::move(rim)});
  return regions;
}

SkinErrorSplit skin_error_split(const VolumeMesh& standard, const Eigen::MatrixXd& mapped,
                                const Eigen::MatrixXd& truth) {
  const Eigen::VectorXi mask = side_mask_of(standard);
  VolumeMesh at_truth = standard;
  at_truth.V = truth;
  const Eigen::MatrixXi F = boundary_faces(split_into_tets(at_truth).T).F;
  Eigen::MatrixXd normals = Eigen::MatrixXd::Zero(truth.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const auto on_skin = [&](int k) { return (mask(F(f, k)) & side_bit(W1)) != 0; };
    if (!on_skin(0) || !on_skin(1) || !on_skin(2)) continue;
    const Eigen::RowVector3d a = truth.row(F(f, 0)), b = truth.row(F(f, 1)), c = truth.row(F(f, 2));
    const Eigen::RowVector3d area_normal = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) normals.row(F(f, k)) += area_normal;
  }
  SkinErrorSplit split;
  int count = 0;
  for (int v = 0; v < truth.rows(); ++v) {
    const double length = normals.row(v).norm();
    if (!(mask(v) & side_bit(W1)) || length == 0) continue;
    const Eigen::RowVector3d n = normals.row(v) / length, d = mapped.row(v) - truth.row(v);
    split.across += std::abs(d.dot(n));
    split.along += (d - d.dot(n) * n).norm();
    ++count;
  }
  if (count > 0) split.across /= count, split.along /= count;
  return split;
}

Eigen::VectorXd vertex_errors(const Eigen::MatrixXd& mapped, const Eigen::MatrixXd& truth) {
  return (mapped - truth).rowwise().norm();
}

CorrespondenceError correspondence_error(const Eigen::VectorXd& errors, const std::vector<VertexRegion>& regions) {
  CorrespondenceError e;
  e.all = summarize_errors(errors);
  for (const VertexRegion& r : regions) {
    Eigen::VectorXd sub(static_cast<Eigen::Index>(r.vertices.size()));
    for (size_t i = 0; i < r.vertices.size(); ++i) sub(static_cast<Eigen::Index>(i)) = errors(r.vertices[i]);
    e.regions.push_back({r.name, summarize_errors(sub)});
  }
  return e;
}

}  // namespace facehex
