#include "core/shape/slab_schedule.h"

#include <Eigen/Core>
#include <algorithm>

namespace facehex {

std::vector<std::vector<int>> slab_schedule(const VolumeMesh& mesh, const std::vector<std::vector<int>>& cells_of,
                                            const std::vector<int>& free_vertices) {
  constexpr int kMostSlabs = 16, kLeastSlabVertices = 64;
  const int n = static_cast<int>(free_vertices.size());
  if (n == 0) return {};
  Eigen::MatrixXd X(n, 3);
  for (int i = 0; i < n; ++i) X.row(i) = mesh.V.row(free_vertices[i]);
  int axis = 0;
  (X.colwise().maxCoeff() - X.colwise().minCoeff()).maxCoeff(&axis);
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return X(a, axis) < X(b, axis); });
  std::vector<int> slab_of(mesh.num_vertices(), -1);
  for (int slabs = std::min(kMostSlabs, n / kLeastSlabVertices); slabs >= 2; --slabs) {
    for (int rank = 0; rank < n; ++rank)
      slab_of[free_vertices[order[rank]]] = static_cast<int>(static_cast<long long>(rank) * slabs / n);
    bool thick_enough = true;
    for (int i = 0; i < n && thick_enough; ++i)
      for (int c : cells_of[free_vertices[i]]) {
        int lowest = slabs, highest = -1;
        for (int local = 0; local < node_count(mesh.types[c]); ++local) {
          const int slab = slab_of[mesh.C(c, local)];
          if (slab < 0) continue;  // not free: never moves
          lowest = std::min(lowest, slab);
          highest = std::max(highest, slab);
        }
        if (highest - lowest > 1) {
          thick_enough = false;
          break;
        }
      }
    if (!thick_enough) continue;
    std::vector<std::vector<int>> cut(slabs);
    for (int v : free_vertices) cut[slab_of[v]].push_back(v);
    return cut;
  }
  return {free_vertices};
}

}  // namespace facehex
