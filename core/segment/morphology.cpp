#include "core/segment/morphology.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/segment/distance_transform.h"

namespace facehex {
namespace {

Mask invert(const Mask& mask) {
  Mask out = mask;
  for (auto& v : out.data) v = !v;
  return out;
}

}  // namespace

Mask dilate(const Mask& mask, double radius) { return within_distance(mask, radius); }

Mask erode(const Mask& mask, double radius) {
  // Outside the grid is background: pad by one layer so the distance sees it.
  const GridGeometry& g = mask.geometry;
  GridGeometry padded = g;
  for (int a = 0; a < 3; ++a) padded.dims[a] += 2, padded.origin(a) -= g.spacing(a);
  Mask background(padded, 1);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) background(i + 1, j + 1, k + 1) = !mask(i, j, k);
  const Mask near_background = within_distance(background, radius);
  Mask out(g, 0);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) out(i, j, k) = !near_background(i + 1, j + 1, k + 1);
  return out;
}

Mask close(const Mask& mask, double radius) {
  const GridGeometry& g = mask.geometry;
  int pad[3];
  GridGeometry padded = g;
  for (int a = 0; a < 3; ++a) {
    pad[a] = static_cast<int>(std::ceil(radius / g.spacing(a))) + 1;
    padded.dims[a] += 2 * pad[a];
    padded.origin(a) -= pad[a] * g.spacing(a);
  }
  Mask big(padded, 0);
  for (int k = 0; k < padded.dims[2]; ++k)
    for (int j = 0; j < padded.dims[1]; ++j)
      for (int i = 0; i < padded.dims[0]; ++i)
        big(i, j, k) = mask(std::clamp(i - pad[0], 0, g.dims[0] - 1), std::clamp(j - pad[1], 0, g.dims[1] - 1),
                            std::clamp(k - pad[2], 0, g.dims[2] - 1));
  // Erosion inside the padded grid: its border replicates the mask, so treating beyond-the-padding as background
  // only reaches the padding, never the original voxels (pad > radius).
  const Mask closed = erode(dilate(big, radius), radius);
  Mask out(g, 0);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) out(i, j, k) = closed(i + pad[0], j + pad[1], k + pad[2]);
  return out;
}

Mask open(const Mask& mask, double radius) {
  if (radius <= 0) return mask;
  Mask out = dilate(largest_component(erode(mask, radius)), radius);
  for (size_t i = 0; i < out.data.size(); ++i) out.data[i] &= mask.data[i];
  return out;
}

namespace {

// A run of mask voxels along x: row (j, k) = row index j + dims[1] k, voxels [begin, end).
struct Run {
  int row, begin, end;
};

int find_root(std::vector<int>& parent, int r) {
  while (parent[r] != r) r = parent[r] = parent[parent[r]];
  return r;
}

// Joins the runs of two rows whose x ranges overlap (face neighbours share x): a merge of two sorted run lists.
void join_overlapping(const std::vector<Run>& runs, int a, int a_end, int b, int b_end, std::vector<int>& parent) {
  while (a < a_end && b < b_end) {
    if (runs[a].end > runs[b].begin && runs[b].end > runs[a].begin) {
      const int ra = find_root(parent, a), rb = find_root(parent, b);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);  // the root is a component's first run
    }
    if (runs[a].end < runs[b].end)
      ++a;
    else
      ++b;
  }
}

}  // namespace

// Union-find over the runs along x, each run joined to the overlapping runs of the row below it in y and in z: a
// row's voxels are read in memory order, where a voxel-by-voxel flood fill jumps between slices.
int label_components(const Mask& mask, std::vector<int>& labels, std::vector<size_t>& sizes) {
  const GridGeometry& g = mask.geometry;
  const int rows = g.dims[1] * g.dims[2];
  std::vector<Run> runs;
  std::vector<int> first_run(static_cast<size_t>(rows) + 1, 0);
  for (int row = 0; row < rows; ++row) {
    first_run[row] = static_cast<int>(runs.size());
    const std::uint8_t* line = mask.data.data() + static_cast<size_t>(row) * g.dims[0];
    for (int i = 0; i < g.dims[0];) {
      if (!line[i]) {
        ++i;
        continue;
      }
      const int begin = i;
      while (i < g.dims[0] && line[i]) ++i;
      runs.push_back({row, begin, i});
    }
  }
  first_run[rows] = static_cast<int>(runs.size());
  std::vector<int> parent(runs.size());
  for (size_t r = 0; r < runs.size(); ++r) parent[r] = static_cast<int>(r);
  for (int row = 0; row < rows; ++row) {
    const int j = row % g.dims[1];
    if (j > 0) join_overlapping(runs, first_run[row], first_run[row + 1], first_run[row - 1], first_run[row], parent);
    if (row >= g.dims[1])
      join_overlapping(runs, first_run[row], first_run[row + 1], first_run[row - g.dims[1]],
                       first_run[row - g.dims[1] + 1], parent);
  }
  // Labels in the order of each component's first voxel in memory, as a flood fill from each unlabelled voxel gives.
  labels.assign(g.size(), 0);
  sizes.assign(1, 0);
  std::vector<int> label_of_root(runs.size(), 0);
  int n = 0;
  for (size_t r = 0; r < runs.size(); ++r) {
    const int root = find_root(parent, static_cast<int>(r));
    if (!label_of_root[root]) {
      label_of_root[root] = ++n;
      sizes.push_back(0);
    }
    const int label = label_of_root[root];
    sizes[label] += static_cast<size_t>(runs[r].end - runs[r].begin);
    const size_t start = static_cast<size_t>(runs[r].row) * g.dims[0];
    std::fill(labels.begin() + static_cast<std::ptrdiff_t>(start + runs[r].begin),
              labels.begin() + static_cast<std::ptrdiff_t>(start + runs[r].end), label);
  }
  return n;
}

Mask largest_component(const Mask& mask) {
  std::vector<int> labels;
  std::vector<size_t> sizes;
  const int n = label_components(mask, labels, sizes);
  Mask out(mask.geometry, 0);
  if (n == 0) return out;
  const int best = static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
  for (size_t i = 0; i < labels.size(); ++i) out.data[i] = labels[i] == best;
  return out;
}

Mask fill_cavities(const Mask& mask, const std::array<bool, 6>& open) {
  const GridGeometry& g = mask.geometry;
  std::vector<int> labels;
  std::vector<size_t> sizes;
  const int n = label_components(invert(mask), labels, sizes);
  std::vector<char> exterior(n + 1, 0);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const bool on_open_face = (open[0] && i == 0) || (open[1] && i == g.dims[0] - 1) || (open[2] && j == 0) ||
                                  (open[3] && j == g.dims[1] - 1) || (open[4] && k == 0) ||
                                  (open[5] && k == g.dims[2] - 1);
        if (on_open_face) exterior[labels[g.index(i, j, k)]] = 1;
      }
  Mask out(g, 0);
  for (size_t i = 0; i < labels.size(); ++i) out.data[i] = mask.data[i] || !exterior[labels[i]];
  return out;
}

}  // namespace facehex
