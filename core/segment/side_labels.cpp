#include "core/segment/side_labels.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <vector>

namespace facehex {
namespace {

constexpr double kCapNormalCos = 0.7;  // a face on a cut plane faces out of it within ~45 degrees
constexpr int kMaxMergeRounds = 20;

// Faces sharing an edge with each face (manifold surfaces: at most 3).
std::vector<std::vector<int>> face_neighbours(const Eigen::MatrixXi& F) {
  std::map<std::pair<int, int>, std::vector<int>> by_edge;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) by_edge[std::minmax(F(f, k), F(f, (k + 1) % 3))].push_back(f);
  std::vector<std::vector<int>> adjacent(F.rows());
  for (const auto& [edge, faces] : by_edge)
    for (int a : faces)
      for (int b : faces)
        if (a != b) adjacent[a].push_back(b);
  return adjacent;
}

// Patch id per face (faces of the same side connected through edges), -1 for faces not selected.
int patches(const std::vector<std::vector<int>>& adjacent, const Eigen::VectorXi& sides, std::vector<int>& patch) {
  patch.assign(sides.size(), -1);
  int n = 0;
  for (int seed = 0; seed < sides.size(); ++seed) {
    if (patch[seed] >= 0) continue;
    patch[seed] = n;
    std::deque<int> queue = {seed};
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop_front();
      for (int g : adjacent[f])
        if (patch[g] < 0 && sides(g) == sides(seed)) patch[g] = n, queue.push_back(g);
    }
    ++n;
  }
  return n;
}

}  // namespace

Eigen::VectorXi classify_sides(const SurfaceMesh& surface, const FaceCuts& cuts, const Field& air_distance,
                               const Field& inner_distance, double plane_tolerance) {
  const std::vector<CutPlane> planes = cuts.planes();
  Eigen::VectorXi sides(surface.F.rows());
  for (int f = 0; f < surface.F.rows(); ++f) {
    const Eigen::Vector3d a = surface.V.row(surface.F(f, 0)), b = surface.V.row(surface.F(f, 1)),
                          c = surface.V.row(surface.F(f, 2));
    const Eigen::Vector3d centroid = (a + b + c) / 3;
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    sides(f) = -1;
    for (const CutPlane& plane : planes)
      if (std::abs(plane.distance(centroid)) < plane_tolerance && normal.dot(plane.normal) > kCapNormalCos)
        sides(f) = plane.side == U0 && centroid.x() > cuts.centre_x ? U1 : plane.side;
    if (sides(f) < 0) sides(f) = sample(air_distance, centroid) <= sample(inner_distance, centroid) ? W1 : W0;
  }
  return sides;
}

void merge_side_islands(const Eigen::MatrixXi& faces, Eigen::VectorXi& sides) {
  const auto adjacent = face_neighbours(faces);
  for (int round = 0; round < kMaxMergeRounds; ++round) {
    std::vector<int> patch;
    const int n = patches(adjacent, sides, patch);
    std::vector<int> size(n, 0);
    for (int p : patch) ++size[p];
    std::vector<int> largest(kNumSides, -1);  // largest patch of each side
    for (int f = 0; f < sides.size(); ++f) {
      int& best = largest[sides(f)];
      if (best < 0 || size[patch[f]] > size[best]) best = patch[f];
    }
    std::vector<char> island(sides.size(), 0);
    bool any = false;
    for (int f = 0; f < sides.size(); ++f) any |= island[f] = patch[f] != largest[sides(f)];
    if (!any) return;
    // Grow the kept patches into the islands, one ring of faces at a time, each face taking the most common side
    // among its kept neighbours.
    bool changed = true;
    while (changed) {
      changed = false;
      std::vector<std::pair<int, int>> updates;
      for (int f = 0; f < sides.size(); ++f) {
        if (!island[f]) continue;
        int votes[kNumSides] = {};
        for (int g : adjacent[f])
          if (!island[g]) ++votes[sides(g)];
        const int best = static_cast<int>(std::max_element(votes, votes + kNumSides) - votes);
        if (votes[best] > 0) updates.push_back({f, best});
      }
      for (const auto& [f, side] : updates) sides(f) = side, island[f] = 0, changed = true;
    }
  }
}

int count_patches(const Eigen::MatrixXi& faces, const Eigen::VectorXi& sides, int side) {
  std::vector<int> selected;
  for (int f = 0; f < faces.rows(); ++f)
    if (side < 0 || sides(f) == side) selected.push_back(f);
  Eigen::MatrixXi sub(static_cast<int>(selected.size()), 3);
  for (size_t i = 0; i < selected.size(); ++i) sub.row(i) = faces.row(selected[i]);
  std::vector<int> patch;
  return patches(face_neighbours(sub), Eigen::VectorXi::Zero(sub.rows()), patch);
}

}  // namespace facehex
