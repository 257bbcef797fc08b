#include "core/mesh/shell_sides.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "core/mesh/cell_faces.h"
#include "core/mesh/side_mask.h"
#include "core/mesh/sides.h"

namespace facehex {
namespace {

struct BoundaryFace {
  int cell, face;
  std::vector<int> v;
  Eigen::Vector3d centroid, normal;  // normal: unit, outward (Newell)
};

Eigen::Vector3d newell_normal(const Eigen::MatrixXd& V, const std::vector<int>& f) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < f.size(); ++i) {
    const Eigen::Vector3d a = V.row(f[i]).transpose(), b = V.row(f[(i + 1) % f.size()]).transpose();
    n += a.cross(b);
  }
  return n.normalized();
}

// The boundary face reached by walking through cells from boundary face (cell, face), and the number of cells
// crossed; {-1,-1,0} if the walk is longer than max_cells or meets a cell without an opposite face.
std::array<int, 3> chord_end(const VolumeMesh& mesh, const FaceNeighbors& nb, int cell, int face, int max_cells) {
  for (int length = 1; length <= max_cells; ++length) {
    const int exit = opposite_face(mesh.types[cell], face);
    if (exit < 0) return {-1, -1, 0};
    const auto [next, next_face] = nb[cell][exit];
    if (next < 0) return {cell, exit, length};
    cell = next;
    face = next_face;
  }
  return {-1, -1, 0};
}

// Connected components, through shared edges, of the faces `member` selects: the component of each face (-1 for
// faces not selected) and each component's face count (faces of one mesh have comparable sizes: counting them is
// enough to rank components). across_cells: two faces of one cell (meeting at the cell's edge, e.g. its top and the
// wall of an opening beside it) are not connected through that edge.
std::pair<std::vector<int>, std::vector<int>> face_components(const std::vector<BoundaryFace>& faces,
                                                              const std::vector<char>& member, bool across_cells) {
  std::map<std::pair<int, int>, std::vector<int>> edge_faces;
  const auto edge = [&](const std::vector<int>& v, size_t k) {
    return std::make_pair(std::min(v[k], v[(k + 1) % v.size()]), std::max(v[k], v[(k + 1) % v.size()]));
  };
  for (size_t i = 0; i < faces.size(); ++i)
    if (member[i])
      for (size_t k = 0; k < faces[i].v.size(); ++k) edge_faces[edge(faces[i].v, k)].push_back(static_cast<int>(i));
  std::vector<int> component(faces.size(), -1), size;
  for (size_t seed = 0; seed < faces.size(); ++seed) {
    if (!member[seed] || component[seed] >= 0) continue;
    const int id = static_cast<int>(size.size());
    size.push_back(0);
    std::vector<int> stack = {static_cast<int>(seed)};
    component[seed] = id;
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      ++size[id];
      for (size_t k = 0; k < faces[i].v.size(); ++k)
        for (int j : edge_faces[edge(faces[i].v, k)])
          if (component[j] < 0 && !(across_cells && faces[j].cell == faces[i].cell)) {
            component[j] = id;
            stack.push_back(j);
          }
    }
  }
  return {component, size};
}

int largest(const std::vector<int>& size) {
  return size.empty() ? -1 : static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
}

}  // namespace

ShellFrame default_shell_frame(const Eigen::MatrixXd& V) {
  const Eigen::Vector3d lo = V.colwise().minCoeff().transpose(), hi = V.colwise().maxCoeff().transpose();
  ShellFrame frame;
  frame.center = Eigen::Vector3d(0.5 * (lo.x() + hi.x()), lo.y(), 0.5 * (lo.z() + hi.z()));
  return frame;
}

ShellSides label_shell_sides(const VolumeMesh& mesh, const ShellFrame& frame) {
  const FaceNeighbors nb = face_neighbors(mesh);
  std::vector<BoundaryFace> faces;
  std::map<std::pair<int, int>, int> index_of;  // (cell, face) -> boundary face index
  for (int c = 0; c < mesh.num_cells(); ++c)
    for (int f = 0; f < static_cast<int>(nb[c].size()); ++f)
      if (nb[c][f][0] < 0) {
        BoundaryFace b{c, f, face_vertices(mesh, c, f), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
        for (int v : b.v) b.centroid += mesh.V.row(v).transpose() / static_cast<double>(b.v.size());
        b.normal = newell_normal(mesh.V, b.v);
        index_of[{c, f}] = static_cast<int>(faces.size());
        faces.push_back(std::move(b));
      }

  ShellSides out;
  constexpr int kUnknown = -1, kOpening = -2;
  std::vector<int> side(faces.size(), kUnknown);
  // 1. Through-thickness chords: the shell has the same number of element layers everywhere, so those chords
  //    all have the most common length (at most max_layers); longer ones run along the shell (e.g. from the top
  //    cut down to an eye opening) and belong to strips.
  std::vector<std::array<int, 3>> ends(faces.size());
  std::map<int, int> length_count;
  for (size_t i = 0; i < faces.size(); ++i) {
    ends[i] = chord_end(mesh, nb, faces[i].cell, faces[i].face, frame.max_layers);
    if (ends[i][2] > 0) ++length_count[ends[i][2]];
  }
  int layers = 0;
  for (const auto& [length, count] : length_count)
    if (layers == 0 || count > length_count[layers]) layers = length;
  out.layers = layers;
  for (size_t i = 0; i < faces.size(); ++i) {
    if (side[i] != kUnknown || ends[i][2] != layers || layers == 0) continue;
    const size_t j = static_cast<size_t>(index_of.at({ends[i][0], ends[i][1]}));
    if (j == i) continue;
    const Eigen::Vector3d radial = (0.5 * (faces[i].centroid + faces[j].centroid) - frame.center).normalized();
    const bool i_outer = faces[i].normal.dot(radial) >= faces[j].normal.dot(radial);
    side[i] = i_outer ? W1 : W0;
    side[j] = i_outer ? W0 : W1;
  }
  // 2. The skin and the bone are each one surface, connected from cell to cell (holed by the openings); a patch of
  //    chords of the common length apart from it lies in the walls of openings (e.g. across the columella between
  //    the nostrils) and is left to the strips.
  for (const Side w : {W0, W1}) {
    std::vector<char> on_side(faces.size());
    for (size_t i = 0; i < faces.size(); ++i) on_side[i] = side[i] == w;
    const auto [component, size] = face_components(faces, on_side, true);
    const int surface = largest(size);
    for (size_t i = 0; i < faces.size(); ++i)
      if (on_side[i] && component[i] != surface) side[i] = kUnknown;
  }
  // 3. Strips: connected components of the remaining faces through shared edges; the largest is the cut rim.
  std::vector<char> unknown(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) unknown[i] = side[i] == kUnknown;
  const auto [strip, strip_size] = face_components(faces, unknown, false);
  const int rim = largest(strip_size);
  const double cos60 = 0.5;
  for (size_t i = 0; i < faces.size(); ++i) {
    if (side[i] != kUnknown) continue;
    if (strip[i] != rim) {
      side[i] = kOpening;
      continue;
    }
    const double up = faces[i].normal.dot(frame.up);
    if (up > cos60)
      side[i] = V1;
    else if (up < -cos60)
      side[i] = V0;
    else
      side[i] = (faces[i].centroid - frame.center).dot(frame.lateral) < 0 ? U0 : U1;
  }

  out.side_mask = Eigen::VectorXi::Zero(mesh.num_vertices());
  for (size_t i = 0; i < faces.size(); ++i) {
    if (side[i] == kOpening) {
      ++out.opening_faces;
      continue;
    }
    ++out.faces_per_side[side[i]];
    for (int v : faces[i].v) out.side_mask(v) |= side_bit(static_cast<Side>(side[i]));
  }
  out.conflicting_vertices = clear_opposite_sides(out.side_mask);
  return out;
}

}  // namespace facehex
