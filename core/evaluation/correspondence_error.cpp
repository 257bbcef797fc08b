#include "core/evaluation/correspondence_error.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/fields/constraint_set.h"
#include "core/mesh/sides.h"
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
  std::vector<VertexRegion> regions = {{"skin", {}}, {"bone", {}}, {"landmarks", {}}};
  for (int v = 0; v < standard.num_vertices(); ++v) {
    if (mask(v) & side_bit(W1)) regions[0].vertices.push_back(v);
    if (mask(v) & side_bit(W0)) regions[1].vertices.push_back(v);
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
