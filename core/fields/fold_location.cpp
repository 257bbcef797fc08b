#include "core/fields/fold_location.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace facehex {
namespace {

// The vertices' neighbours along the tets' edges (each vertex's list sorted and without repeats).
std::vector<std::vector<int>> vertex_neighbours(const Eigen::MatrixXi& T, Eigen::Index vertices) {
  std::vector<std::vector<int>> neighbours(vertices);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (i != j) neighbours[T(t, i)].push_back(T(t, j));
  for (auto& n : neighbours) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return neighbours;
}

// Per vertex: within `rings` steps of a source (breadth first from all sources at once).
std::vector<char> within_rings(const std::vector<std::vector<int>>& neighbours, const std::vector<int>& sources,
                               int rings) {
  std::vector<int> depth(neighbours.size(), -1);
  std::queue<int> queue;
  for (int s : sources) depth[s] = 0, queue.push(s);
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop();
    if (depth[v] == rings) continue;
    for (int n : neighbours[v])
      if (depth[n] < 0) depth[n] = depth[v] + 1, queue.push(n);
  }
  std::vector<char> near(neighbours.size());
  for (size_t v = 0; v < near.size(); ++v) near[v] = depth[v] >= 0;
  return near;
}

}  // namespace

FoldLocation fold_location(const Eigen::MatrixXi& T, const Eigen::MatrixXd& uvw, const Eigen::MatrixXi& fixed,
                           const std::vector<int>& folded, int rings) {
  FoldLocation location;
  location.folded = static_cast<int>(folded.size());
  location.rings = rings;
  if (folded.empty() || fixed.rows() != uvw.rows()) return location;
  const std::vector<std::vector<int>> neighbours = vertex_neighbours(T, uvw.rows());
  for (int cut = 0; cut < 4; ++cut) {
    const int field = cut / 2;
    const double end = cut % 2;
    std::vector<int> on_cut;
    for (Eigen::Index v = 0; v < uvw.rows(); ++v)
      if (fixed(v, field) != 0 && uvw(v, field) == end) on_cut.push_back(static_cast<int>(v));
    if (on_cut.empty()) continue;
    const std::vector<char> near = within_rings(neighbours, on_cut, rings);
    for (int t : folded) location.near_cut[cut] += near[T(t, 0)] || near[T(t, 1)] || near[T(t, 2)] || near[T(t, 3)];
  }
  return location;
}

std::string fold_location_text(const FoldLocation& location) {
  if (location.folded == 0) return "";
  const auto most = std::max_element(location.near_cut.begin(), location.near_cut.end());
  if (2 * *most < location.folded) return "";
  static const char* const kCuts[] = {"posterior cut at u = 0", "posterior cut at u = 1", "bottom cut (v = 0)",
                                      "top cut (v = 1)"};
  static const char* const kOptions[] = {"--posterior-cut", "--posterior-cut", "--bottom-cut", "--top-cut"};
  const auto cut = most - location.near_cut.begin();
  return "; " + std::to_string(static_cast<int>(std::lround(100.0 * *most / location.folded))) +
         " % of the folded tets lie within " + std::to_string(location.rings) + " cells of the " + kCuts[cut] +
         ", which a CT's model is cut at elsewhere with " + kOptions[cut];
}

}  // namespace facehex
