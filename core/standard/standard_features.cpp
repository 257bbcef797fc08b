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
namespace {

std::string opening_name(const Eigen::Vector3d& c, const FaceLandmarks& lm, int index) {
  const auto at = [&](const char* name) { return lm.points.at(name); };
  const std::string end = c.x() < lm.plane.x ? "at -x" : "at +x";
  if (lm.points.count("pronasale") && c.z() > at("pronasale").z() + 5) return "eye " + end;
  if (lm.points.count("subnasale") && c.z() > at("subnasale").z() - 4) return "nostril " + end;
  if (lm.points.count("stomion") && std::abs(c.z() - at("stomion").z()) < 12) return "mouth";
  return "opening " + std::to_string(index + 1);
}

}  // namespace

StandardFeatures standard_features(const VolumeMesh& standard) {
  StandardFeatures f;
  const Eigen::VectorXi mask = side_mask_of(standard);
  f.landmarks = find_face_landmarks(standard.V, mask);
  for (const auto& [name, p] : f.landmarks.points)
    if (const int nearest = closest_skin_vertex(standard.V, mask, p); nearest >= 0) f.landmark_vertices[name] = nearest;
  // An opening's wall may fall into several edge-connected pieces (where its rim vertices touch): pieces of the same
  // name are one rim.
  const TetDomain domain = auxiliary_domain(standard);
  const auto openings = sideless_boundary_pieces(domain);
  std::map<std::string, size_t> largest;  // by name, the piece with the most triangles
  for (size_t o = 0; o < openings.size(); ++o) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const auto& t : openings[o])
      for (int k = 0; k < 3; ++k)
        centroid += domain.V.row(t(k)).transpose() / (3.0 * static_cast<double>(openings[o].size()));
    const std::string name = opening_name(centroid, f.landmarks, static_cast<int>(o));
    if (!largest.count(name) || openings[o].size() > openings[largest[name]].size()) largest[name] = o;
    std::vector<int>& rim = f.rims[name];
    for (const auto& t : openings[o])
      for (int k = 0; k < 3; ++k)
        if (domain.side_mask(t(k)) & (side_bit(W0) | side_bit(W1))) rim.push_back(t(k));
  }
  for (auto it = f.rims.begin(); it != f.rims.end();) {
    std::vector<int>& rim = it->second;
    std::sort(rim.begin(), rim.end());
    rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
    it = rim.empty() ? f.rims.erase(it) : std::next(it);
  }
  // The corners: of the opening's largest piece (a few small sideless walls elsewhere, gaps in a hand-built mesh, can
  // share its name), the skin vertices furthest towards -x and +x.
  const auto corners = [&](const char* opening, const char* at_minus_x, const char* at_plus_x) {
    const auto piece = largest.find(opening);
    if (piece == largest.end()) return;
    int lo = -1, hi = -1;
    for (const auto& t : openings[piece->second])
      for (int k = 0; k < 3; ++k) {
        const int v = t(k);
        if (!(domain.side_mask(v) & side_bit(W1))) continue;
        if (lo < 0 || standard.V(v, 0) < standard.V(lo, 0)) lo = v;
        if (hi < 0 || standard.V(v, 0) > standard.V(hi, 0)) hi = v;
      }
    if (lo < 0) return;
    f.landmark_vertices[at_minus_x] = lo;
    f.landmark_vertices[at_plus_x] = hi;
  };
  corners("eye at -x", "exocanthion right", "endocanthion right");
  corners("eye at +x", "endocanthion left", "exocanthion left");
  corners("mouth", "cheilion right", "cheilion left");
  return f;
}

}  // namespace facehex
