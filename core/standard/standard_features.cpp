#include "core/standard/standard_features.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/fields/constraint_set.h"
#include "core/fields/tet_domain.h"
#include "core/mesh/side_mask.h"
#include "core/mesh/sides.h"
#include "core/standard/closed_domain.h"

namespace facehex {
StandardFeatures standard_features(const VolumeMesh& standard) {
  StandardFeatures f;
  const Eigen::VectorXi mask = side_mask_of(standard);
  // An opening's wall may fall into several edge-connected pieces (where its rim vertices touch): pieces of the same
  // name are one rim.
  const TetDomain domain = auxiliary_domain(standard);
  const auto openings = sideless_boundary_pieces(domain);
  const std::vector<std::vector<int>> rims = opening_rims(domain, openings, side_bit(W0) | side_bit(W1));
  const std::vector<std::vector<int>> skin_rims = opening_rims(domain, openings, side_bit(W1));
  // The eye and mouth corners are the ends of the openings' rims on the skin (LandmarkOptions::opening_rims), each
  // a vertex of the standard.
  LandmarkOptions options;
  for (const std::vector<int>& rim : skin_rims) options.opening_rims.push_back(domain.V(rim, Eigen::all));
  f.landmarks = find_face_landmarks(standard.V, mask, options);
  for (const auto& [name, p] : f.landmarks.points)
    if (const int nearest = closest_skin_vertex(standard.V, mask, p); nearest >= 0) f.landmark_vertices[name] = nearest;
  for (size_t o = 0; o < openings.size(); ++o) {
    if (rims[o].empty()) continue;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& t : openings[o])
      for (int k = 0; k < 3; ++k)
        centroid += domain.V.row(t(k)).transpose() / (3.0 * static_cast<double>(openings[o].size()));
    std::vector<int>& rim = f.rims[opening_name(centroid, f.landmarks, static_cast<int>(o))];
    rim.insert(rim.end(), rims[o].begin(), rims[o].end());
  }
  for (auto& [name, rim] : f.rims) {
    std::sort(rim.begin(), rim.end());
    rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
  }
  return f;
}

}  // namespace facehex
