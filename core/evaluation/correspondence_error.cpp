#include "core/evaluation/correspondence_error.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/face/face_landmarks.h"
#include "core/fields/constraint_set.h"
#include "core/fields/tet_domain.h"
#include "core/mesh/sides.h"
#include "core/standard/closed_domain.h"

namespace facehex {
namespace {

// An opening's anatomical name from where its centroid lies against the landmarks.
std::string opening_name(const Eigen::Vector3d& c, const FaceLandmarks& lm, int index) {
  const auto at = [&](const char* name) { return lm.points.at(name); };
  const std::string end = c.x() < lm.plane.x ? "at -x" : "at +x";
  if (lm.points.count("pronasale") && c.z() > at("pronasale").z() + 5) return "eye " + end;
  if (lm.points.count("subnasale") && c.z() > at("subnasale").z() - 4) return "nostril " + end;
  if (lm.points.count("stomion") && std::abs(c.z() - at("stomion").z()) < 12) return "mouth";
  return "opening " + std::to_string(index + 1);
}

}  // namespace

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
  const FaceLandmarks landmarks = find_face_landmarks(standard.V, mask);
  for (const int v : regions[0].vertices)
    for (const auto& [name, p] : landmarks.points)
      if ((standard.V.row(v).transpose() - p).norm() <= landmark_radius) {
        regions[2].vertices.push_back(v);
        break;
      }
  // An opening's wall may fall into several edge-connected pieces (where its rim vertices touch): pieces of the same
  // name are one region.
  const TetDomain domain = auxiliary_domain(standard);
  const auto openings = sideless_boundary_pieces(domain);
  std::map<std::string, std::vector<int>> rims;
  for (size_t o = 0; o < openings.size(); ++o) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& t : openings[o])
      for (int k = 0; k < 3; ++k)
        centroid += domain.V.row(t(k)).transpose() / (3.0 * static_cast<double>(openings[o].size()));
    std::vector<int>& rim = rims["rim: " + opening_name(centroid, landmarks, static_cast<int>(o))];
    for (const auto& t : openings[o])
      for (int k = 0; k < 3; ++k)
        if (domain.side_mask(t(k)) & (side_bit(W0) | side_bit(W1))) rim.push_back(t(k));
  }
  for (auto& [name, rim] : rims) {
    std::sort(rim.begin(), rim.end());
    rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
    if (!rim.empty()) regions.push_back({name, std::move(rim)});
  }
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
