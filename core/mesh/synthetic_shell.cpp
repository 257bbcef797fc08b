#include "core/mesh/synthetic_shell.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include "core/mesh/sides.h"

namespace facehex {
namespace {

struct Builder {
  const SyntheticShellOptions& o;
  std::vector<Eigen::RowVector3d> points;
  std::map<std::tuple<int, int, int>, int> index;  // grid (i, j, k) -> point, shared between the six sides
  std::vector<Eigen::Vector3i> faces;
  std::vector<int> labels;
  int nt, nz, nr;

  Eigen::RowVector3d position(int i, int j, int k) const {
    const double t = -o.t_max + 2 * o.t_max * i / nt, z = o.z_min + (o.z_max - o.z_min) * j / nz;
    const double r = static_cast<double>(k) / nr;
    const double zc = 0.55 * (o.z_min + o.z_max);
    const double bump =
        r * o.nose_height *
        std::exp(-(t * t * o.inner_a * o.inner_a + (z - zc) * (z - zc)) / (o.nose_width * o.nose_width));
    const double a = o.inner_a + r * o.thickness, b = o.inner_b + r * o.thickness + bump;
    return {a * std::sin(t), b * std::cos(t), z};
  }
  int point(int i, int j, int k) {
    const auto key = std::make_tuple(i, j, k);
    const auto it = index.find(key);
    if (it != index.end()) return it->second;
    points.push_back(position(i, j, k));
    return index[key] = static_cast<int>(points.size() - 1);
  }
  // A quad grid over two of the (i, j, k) directions at a fixed third one, split into triangles; `flip` turns the
  // orientation so the normal points out.
  void side(Side s, int fixed_axis, int fixed_value, bool flip) {
    const int n[3] = {nt, nz, nr};
    const int a = (fixed_axis + 1) % 3, b = (fixed_axis + 2) % 3;
    for (int p = 0; p < n[a]; ++p)
      for (int q = 0; q < n[b]; ++q) {
        int v[4];
        const int corners[4][2] = {{p, q}, {p + 1, q}, {p + 1, q + 1}, {p, q + 1}};
        for (int c = 0; c < 4; ++c) {
          int ijk[3];
          ijk[fixed_axis] = fixed_value;
          ijk[a] = corners[c][0];
          ijk[b] = corners[c][1];
          v[c] = point(ijk[0], ijk[1], ijk[2]);
        }
        if (flip) std::swap(v[1], v[3]);
        faces.emplace_back(v[0], v[1], v[2]);
        faces.emplace_back(v[0], v[2], v[3]);
        labels.insert(labels.end(), 2, static_cast<int>(s) + 1);
      }
  }
};

}  // namespace

SurfaceMesh synthetic_shell_surface(const SyntheticShellOptions& o) {
  const double mean_radius = 0.5 * (o.inner_a + o.inner_b) + o.thickness / 2;
  Builder b{o,
            {},
            {},
            {},
            {},
            std::max(2, static_cast<int>(std::ceil(2 * o.t_max * mean_radius / o.edge_length))),
            std::max(2, static_cast<int>(std::ceil((o.z_max - o.z_min) / o.edge_length))),
            std::max(1, static_cast<int>(std::ceil(o.thickness / o.edge_length)))};
  // Axis 0 = t (i), 1 = z (j), 2 = r (k). Orientation flags chosen so every normal points out of the shell.
  b.side(U0, 0, 0, false);
  b.side(U1, 0, b.nt, true);
  b.side(V0, 1, 0, false);
  b.side(V1, 1, b.nz, true);
  b.side(W0, 2, 0, false);
  b.side(W1, 2, b.nr, true);
  SurfaceMesh s;
  s.V.resize(static_cast<Eigen::Index>(b.points.size()), 3);
  for (size_t i = 0; i < b.points.size(); ++i) s.V.row(static_cast<Eigen::Index>(i)) = b.points[i];
  s.F.resize(static_cast<Eigen::Index>(b.faces.size()), 3);
  for (size_t f = 0; f < b.faces.size(); ++f) s.F.row(static_cast<Eigen::Index>(f)) = b.faces[f].transpose();
  s.labels = Eigen::Map<Eigen::VectorXi>(b.labels.data(), static_cast<Eigen::Index>(b.labels.size()));
  return s;
}

}  // namespace facehex
