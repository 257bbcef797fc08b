#include "core/mesh/tet_topology.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>

#include "core/mesh/cell_faces.h"

namespace facehex {
namespace {

// Face i of a tet is the one opposite its vertex i, ordered so its right-hand normal points out (cell_faces.h).
const int* opposite_face_nodes(int i) { return cell_faces(CellType::Tet)[i].node.data(); }

struct FaceRecord {
  std::array<int, 3> key;  // sorted vertex ids
  int tet, local;          // owner tet and the local index of the vertex opposite the face
};

// All tet faces sorted by vertex set, so equal faces are adjacent: a counting sort on the smallest vertex (each face
// written straight to its bucket), then each bucket (a vertex's faces, a few dozen) sorted on the other two vertices
// packed in one 64-bit key, buckets in parallel. O(#T), and each record is written once.
std::vector<FaceRecord> sorted_faces(const Eigen::MatrixXi& T) {
  const size_t count = static_cast<size_t>(T.rows()) * 4;
  const int num_vertices = T.size() > 0 ? T.maxCoeff() + 1 : 0;
  auto sorted_key = [&T](int t, int i) {
    const int* o = opposite_face_nodes(i);
    std::array<int, 3> k = {T(t, o[0]), T(t, o[1]), T(t, o[2])};
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    if (k[1] > k[2]) std::swap(k[1], k[2]);
    if (k[0] > k[1]) std::swap(k[0], k[1]);
    return k;
  };
  std::vector<int> bucket_start(static_cast<size_t>(num_vertices) + 1, 0);
  for (int t = 0; t < T.rows(); ++t)
    for (int i = 0; i < 4; ++i) ++bucket_start[static_cast<size_t>(sorted_key(t, i)[0]) + 1];
  std::partial_sum(bucket_start.begin(), bucket_start.end(), bucket_start.begin());
  std::vector<FaceRecord> faces(count);
  std::vector<int> next(bucket_start.begin(), bucket_start.end() - 1);
  for (int t = 0; t < T.rows(); ++t)
    for (int i = 0; i < 4; ++i) {
      const std::array<int, 3> k = sorted_key(t, i);
      faces[static_cast<size_t>(next[k[0]]++)] = {k, t, i};
    }
  const auto rest = [](const FaceRecord& f) {
    return (static_cast<std::uint64_t>(f.key[1]) << 32) | static_cast<std::uint32_t>(f.key[2]);
  };
#pragma omp parallel for schedule(dynamic, 1024)
  for (int v = 0; v < num_vertices; ++v)
    std::sort(faces.begin() + bucket_start[v], faces.begin() + bucket_start[v + 1],
              [&rest](const FaceRecord& a, const FaceRecord& b) { return rest(a) < rest(b); });
  return faces;
}

// Calls visit(first, last) for each run of equal faces.
template <class Visit>
void for_each_face_group(const std::vector<FaceRecord>& faces, Visit visit) {
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    visit(i, j);
    i = j;
  }
}

}  // namespace

TetFaceAdjacency tet_face_adjacency(const Eigen::MatrixXi& T) {
  const auto faces = sorted_faces(T);
  TetFaceAdjacency out;
  out.neighbors = Eigen::MatrixXi::Constant(T.rows(), 4, -1);
  std::vector<std::array<int, 4>> found;  // three vertices + owner tet
  for_each_face_group(faces, [&](size_t first, size_t last) {
    if (last - first == 2) {
      const FaceRecord &a = faces[first], &b = faces[first + 1];
      out.neighbors(a.tet, a.local) = b.tet;
      out.neighbors(b.tet, b.local) = a.tet;
    } else if (last - first == 1) {
      const FaceRecord& f = faces[first];
      const int* o = opposite_face_nodes(f.local);
      found.push_back({T(f.tet, o[0]), T(f.tet, o[1]), T(f.tet, o[2]), f.tet});
    } else {
      ++out.boundary.nonmanifold_faces;
    }
  });
  out.boundary.F.resize(static_cast<Eigen::Index>(found.size()), 3);
  out.boundary.tet.resize(static_cast<Eigen::Index>(found.size()));
  for (size_t i = 0; i < found.size(); ++i) {
    for (int k = 0; k < 3; ++k) out.boundary.F(static_cast<Eigen::Index>(i), k) = found[i][k];
    out.boundary.tet(static_cast<Eigen::Index>(i)) = found[i][3];
  }
  return out;
}

BoundaryFaces boundary_faces(const Eigen::MatrixXi& T) { return tet_face_adjacency(T).boundary; }

Eigen::MatrixXi tet_face_neighbors(const Eigen::MatrixXi& T) { return tet_face_adjacency(T).neighbors; }

int tet_components(const Eigen::MatrixXi& N, Eigen::VectorXi& component) {
  component = Eigen::VectorXi::Constant(N.rows(), -1);
  int count = 0;
  std::vector<int> stack;
  for (int seed = 0; seed < N.rows(); ++seed) {
    if (component(seed) != -1) continue;
    component(seed) = count;
    stack.push_back(seed);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      for (int i = 0; i < 4; ++i) {
        const int n = N(t, i);
        if (n >= 0 && component(n) == -1) {
          component(n) = count;
          stack.push_back(n);
        }
      }
    }
    ++count;
  }
  return count;
}

std::vector<char> boundary_vertex_flags(int num_vertices, const Eigen::MatrixXi& boundary_F) {
  std::vector<char> flags(num_vertices, 0);
  for (int f = 0; f < boundary_F.rows(); ++f)
    for (int k = 0; k < 3; ++k) flags[boundary_F(f, k)] = 1;
  return flags;
}

}  // namespace facehex
