#include "core/segment/remesh.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace facehex {
namespace {

constexpr double kSplitRatio = 4.0 / 3.0;     // Botsch & Kobbelt's thresholds: split above 4/3 L,
constexpr double kCollapseRatio = 4.0 / 5.0;  // collapse below 4/5 L
constexpr double kMinTurnCos = 0.5;           // a collapse or flip may not turn a face by more than 60 degrees
constexpr double kFlipCoplanarCos = 0.9;      // only flip an edge whose faces are within ~25 degrees of coplanar

constexpr double kDelaunayTolerance = 1e-6;  // radians

enum Role { kFree, kFeature, kCorner };
enum FlipRule { kValence, kDelaunay };  // flip towards valence 6, or to make the edge locally Delaunay

// Closest points on a set of triangles or segments.
class ClosestPoint {
 public:
  ClosestPoint(const std::vector<Eigen::Vector3d>& points, const std::vector<std::vector<vtkIdType>>& cells) {
    vtkNew<vtkPoints> p;
    for (const auto& x : points) p->InsertNextPoint(x.data());
    vtkNew<vtkCellArray> c;
    for (const auto& cell : cells) c->InsertNextCell(static_cast<vtkIdType>(cell.size()), cell.data());
    poly_ = vtkSmartPointer<vtkPolyData>::New();
    poly_->SetPoints(p);
    if (cells.front().size() == 2)
      poly_->SetLines(c);
    else
      poly_->SetPolys(c);
    locator_ = vtkSmartPointer<vtkStaticCellLocator>::New();
    locator_->SetDataSet(poly_);
    locator_->BuildLocator();
  }
  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const {
    double closest[3], dist2;
    vtkIdType cell;
    int sub;
    locator_->FindClosestPoint(x.data(), closest, cell, sub, dist2);
    return Eigen::Vector3d(closest[0], closest[1], closest[2]);
  }

 private:
  vtkSmartPointer<vtkPolyData> poly_;
  vtkSmartPointer<vtkStaticCellLocator> locator_;
};

class Remesher {
 public:
  Remesher(const SurfaceMesh& s, double target) : target_(target) {
    for (int v = 0; v < s.V.rows(); ++v) points_.push_back(s.V.row(v).transpose());
    vertex_faces_.resize(points_.size());
    for (int f = 0; f < s.F.rows(); ++f) {
      faces_.push_back({s.F(f, 0), s.F(f, 1), s.F(f, 2)});
      labels_.push_back(s.labels(f));
      for (int k = 0; k < 3; ++k) vertex_faces_[s.F(f, k)].push_back(f);
    }
    face_alive_.assign(faces_.size(), 1);
    vertex_alive_.assign(points_.size(), 1);
    build_reference();
  }

  void run(int rounds) {
    for (int r = 0; r < rounds; ++r) {
      split_long_edges();
      collapse_short_edges();
      flip_edges(kValence);
      relax_and_project();
    }
    // Valence flips and smoothing leave the odd thin triangle next to a feature line: Delaunay flips remove most.
    flip_edges(kDelaunay);
  }

  SurfaceMesh result() const {
    std::vector<int> index(points_.size(), -1);
    int n = 0;
    for (size_t v = 0; v < points_.size(); ++v)
      if (vertex_alive_[v]) index[v] = n++;
    SurfaceMesh s;
    s.V.resize(n, 3);
    for (size_t v = 0; v < points_.size(); ++v)
      if (index[v] >= 0) s.V.row(index[v]) = points_[v].transpose();
    const int m = static_cast<int>(std::count(face_alive_.begin(), face_alive_.end(), 1));
    s.F.resize(m, 3);
    s.labels.resize(m);
    int f_out = 0;
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!face_alive_[f]) continue;
      for (int k = 0; k < 3; ++k) s.F(f_out, k) = index[faces_[f][k]];
      s.labels(f_out++) = labels_[f];
    }
    return s;
  }

 private:
  // ---- projection targets: the input's patches per label and feature lines per label pair ----
  void build_reference() {
    std::map<int, std::vector<std::vector<vtkIdType>>> patches;
    std::map<std::pair<int, int>, std::vector<std::vector<vtkIdType>>> lines;
    for (size_t f = 0; f < faces_.size(); ++f)
      patches[labels_[f]].push_back({faces_[f][0], faces_[f][1], faces_[f][2]});
    for (size_t v = 0; v < points_.size(); ++v)
      for (int n : neighbours(static_cast<int>(v))) {
        if (n < static_cast<int>(v)) continue;
        const auto fs = edge_faces(static_cast<int>(v), n);
        if (fs.size() == 2 && labels_[fs[0]] != labels_[fs[1]])
          lines[std::minmax(labels_[fs[0]], labels_[fs[1]])].push_back({static_cast<vtkIdType>(v), n});
      }
    for (auto& [label, cells] : patches) patch_.emplace(label, ClosestPoint(points_, cells));
    for (auto& [pair, cells] : lines) line_.emplace(pair, ClosestPoint(points_, cells));
  }

  // ---- connectivity ----
  std::vector<int> edge_faces(int a, int b) const {
    std::vector<int> out;
    for (int f : vertex_faces_[a])
      if (faces_[f][0] == b || faces_[f][1] == b || faces_[f][2] == b) out.push_back(f);
    return out;
  }
  // Sorted, without repeats (a sorted vector: called for every edge operation, so no per-node allocation of a
  // std::set).
  std::vector<int> neighbours(int v) const {
    std::vector<int> out;
    for (int f : vertex_faces_[v])
      for (int w : faces_[f])
        if (w != v) out.push_back(w);
    return sorted_unique(std::move(out));
  }
  std::vector<int> face_labels(int v) const {
    std::vector<int> out;
    for (int f : vertex_faces_[v]) out.push_back(labels_[f]);
    return sorted_unique(std::move(out));
  }
  static std::vector<int> sorted_unique(std::vector<int> values) {
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    return values;
  }
  bool is_feature_edge(int a, int b) const {
    const auto fs = edge_faces(a, b);
    return fs.size() == 2 && labels_[fs[0]] != labels_[fs[1]];
  }
  Role role(int v) const {
    const std::vector<int> labels = face_labels(v);
    if (labels.size() == 1) return kFree;
    if (labels.size() > 2) return kCorner;
    int feature_edges = 0;
    for (int n : neighbours(v)) feature_edges += is_feature_edge(v, n);
    return feature_edges == 2 ? kFeature : kCorner;
  }
  Eigen::Vector3d normal(int a, int b, int c) const { return (points_[b] - points_[a]).cross(points_[c] - points_[a]); }
  Eigen::Vector3d normal(int f) const { return normal(faces_[f][0], faces_[f][1], faces_[f][2]); }
  double length(int a, int b) const { return (points_[a] - points_[b]).norm(); }
  // Angle at vertex v of the triangle (v, a, b).
  double angle(int v, int a, int b) const {
    const Eigen::Vector3d e = points_[a] - points_[v], f = points_[b] - points_[v];
    return std::atan2(e.cross(f).norm(), e.dot(f));
  }
  void remove_face_from(int v, int f) {
    auto& list = vertex_faces_[v];
    list.erase(std::remove(list.begin(), list.end(), f), list.end());
  }
  std::vector<std::pair<int, int>> edges_where(bool long_edges) const {
    std::vector<std::pair<int, int>> out;
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!face_alive_[f]) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = faces_[f][k], b = faces_[f][(k + 1) % 3];
        if (a > b) continue;  // each edge once (the other face has it as b -> a)
        const double l = length(a, b);
        if (long_edges ? l > kSplitRatio * target_ : l < kCollapseRatio * target_) out.push_back({a, b});
      }
    }
    return out;
  }

  // ---- split ----
  void split_long_edges() {
    for (auto edges = edges_where(true); !edges.empty(); edges = edges_where(true))
      for (const auto& [a, b] : edges)
        if (length(a, b) > kSplitRatio * target_) split(a, b);
  }
  void split(int a, int b) {
    const std::vector<int> fs = edge_faces(a, b);
    if (fs.size() != 2) return;
    const int m = static_cast<int>(points_.size());
    points_.push_back((points_[a] + points_[b]) / 2);
    vertex_faces_.emplace_back();
    vertex_alive_.push_back(1);
    for (int f : fs) {
      auto t = faces_[f];
      int i = 0;
      while (!((t[i] == a && t[(i + 1) % 3] == b) || (t[i] == b && t[(i + 1) % 3] == a))) ++i;
      const int x = t[i], y = t[(i + 1) % 3], z = t[(i + 2) % 3];
      faces_[f] = {x, m, z};
      const int g = static_cast<int>(faces_.size());
      faces_.push_back({m, y, z});
      labels_.push_back(labels_[f]);
      face_alive_.push_back(1);
      remove_face_from(y, f);
      vertex_faces_[y].push_back(g);
      vertex_faces_[z].push_back(g);
      vertex_faces_[m].push_back(f);
      vertex_faces_[m].push_back(g);
    }
  }

  // ---- collapse ----
  void collapse_short_edges() {
    for (const auto& [a, b] : edges_where(false)) {
      if (!vertex_alive_[a] || !vertex_alive_[b] || length(a, b) >= kCollapseRatio * target_) continue;
      if (!collapse(a, b)) collapse(b, a);
    }
  }
  // Removes a, moving its faces to b. Returns false (and changes nothing) when that is not allowed.
  bool collapse(int a, int b) {
    const std::vector<int> fs = edge_faces(a, b);
    if (fs.size() != 2) return false;
    const Role ra = role(a);
    if (ra == kCorner || (ra == kFeature && !is_feature_edge(a, b))) return false;
    const std::vector<int> na = neighbours(a), nb = neighbours(b);
    std::vector<int> common;
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    if (common.size() != 2) return false;  // link condition: else the surface would pinch
    for (int c : common)
      if (neighbours(c).size() <= 3) return false;
    for (int n : na)
      if (n != b && length(b, n) > kSplitRatio * target_) return false;
    for (int f : vertex_faces_[a]) {
      if (f == fs[0] || f == fs[1]) continue;
      auto t = faces_[f];
      const Eigen::Vector3d before = normal(f);
      for (int& v : t)
        if (v == a) v = b;
      const Eigen::Vector3d after = normal(t[0], t[1], t[2]);
      if (after.norm() < 1e-12 * target_ * target_) return false;
      if (before.norm() > 0 && before.normalized().dot(after.normalized()) < kMinTurnCos) return false;
    }
    for (int f : fs) {
      face_alive_[f] = 0;
      for (int v : faces_[f])
        if (v != a) remove_face_from(v, f);
    }
    for (int f : vertex_faces_[a]) {
      if (!face_alive_[f]) continue;
      for (int& v : faces_[f])
        if (v == a) v = b;
      vertex_faces_[b].push_back(f);
    }
    vertex_faces_[a].clear();
    vertex_alive_[a] = 0;
    return true;
  }

  // ---- flip ----
  void flip_edges(FlipRule rule) {
    for (size_t f = 0; f < faces_.size(); ++f) {
      if (!face_alive_[f]) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = faces_[f][k], b = faces_[f][(k + 1) % 3];
        if (a < b) flip(rule, static_cast<int>(f), a, b);
        if (faces_[f][k] != a) break;  // this face changed: its other edges are visited with the new faces
      }
    }
  }
  void flip(FlipRule rule, int f1, int a, int b) {
    const std::vector<int> fs = edge_faces(a, b);
    if (fs.size() != 2 || labels_[fs[0]] != labels_[fs[1]]) return;
    const int f2 = fs[0] == f1 ? fs[1] : fs[0];
    const int c = faces_[f1][0] + faces_[f1][1] + faces_[f1][2] - a - b;
    const int d = faces_[f2][0] + faces_[f2][1] + faces_[f2][2] - a - b;
    if (c == d) return;
    const std::vector<int> nc = neighbours(c);
    if (std::binary_search(nc.begin(), nc.end(), d)) return;
    const int va = static_cast<int>(neighbours(a).size()), vb = static_cast<int>(neighbours(b).size());
    const int vc = static_cast<int>(nc.size()), vd = static_cast<int>(neighbours(d).size());
    if (va <= 3 || vb <= 3) return;
    if (rule == kValence) {
      const int before = std::abs(va - 6) + std::abs(vb - 6) + std::abs(vc - 6) + std::abs(vd - 6);
      const int after = std::abs(va - 7) + std::abs(vb - 7) + std::abs(vc - 5) + std::abs(vd - 5);
      if (after >= before) return;
    } else if (angle(c, a, b) + angle(d, a, b) <= M_PI + kDelaunayTolerance) {
      return;  // already locally Delaunay
    }
    const Eigen::Vector3d n1 = normal(f1), n2 = normal(f2);
    if (n1.norm() == 0 || n2.norm() == 0 || n1.normalized().dot(n2.normalized()) < kFlipCoplanarCos) return;
    // f1 = (a, b, c) and f2 = (b, a, d) up to rotation become (a, d, c) and (b, c, d).
    const Eigen::Vector3d m1 = normal(a, d, c), m2 = normal(b, c, d), mean = (n1.normalized() + n2.normalized());
    if (m1.norm() < 1e-12 * target_ * target_ || m2.norm() < 1e-12 * target_ * target_) return;
    if (m1.normalized().dot(mean.normalized()) < kMinTurnCos || m2.normalized().dot(mean.normalized()) < kMinTurnCos)
      return;
    faces_[f1] = {a, d, c};
    faces_[f2] = {b, c, d};
    remove_face_from(b, f1);
    remove_face_from(a, f2);
    vertex_faces_[d].push_back(f1);
    vertex_faces_[c].push_back(f2);
  }

  // ---- tangential smoothing, then back onto the input surface ----
  void relax_and_project() {
    std::vector<Eigen::Vector3d> moved = points_;
    for (size_t i = 0; i < points_.size(); ++i) {
      const int v = static_cast<int>(i);
      if (!vertex_alive_[v]) continue;
      const Role r = role(v);
      if (r == kCorner) continue;
      const Eigen::Vector3d& p = points_[v];
      if (r == kFree) {
        Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
        const std::vector<int> ns = neighbours(v);
        for (int w : ns) centroid += points_[w];
        centroid /= static_cast<double>(ns.size());
        for (int f : vertex_faces_[v]) n += normal(f);
        if (n.norm() == 0) continue;
        n.normalize();
        const Eigen::Vector3d q = p + (centroid - p) - n.dot(centroid - p) * n;
        moved[v] = patch_.at(labels_[vertex_faces_[v].front()])(q);
      } else {
        std::vector<int> along;
        for (int w : neighbours(v))
          if (is_feature_edge(v, w)) along.push_back(w);
        const Eigen::Vector3d t = (points_[along[1]] - points_[along[0]]).normalized();
        const Eigen::Vector3d q = p + t.dot((points_[along[0]] + points_[along[1]]) / 2 - p) * t;
        const std::vector<int> labels = face_labels(v);
        const auto line = line_.find({labels.front(), labels.back()});
        moved[v] = line == line_.end() ? q : line->second(q);
      }
    }
    points_ = std::move(moved);
  }

  double target_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<int> labels_;
  std::vector<char> face_alive_, vertex_alive_;
  std::vector<std::vector<int>> vertex_faces_;
  std::map<int, ClosestPoint> patch_;
  std::map<std::pair<int, int>, ClosestPoint> line_;
};

}  // namespace

SurfaceMesh remesh_isotropic(const SurfaceMesh& surface, double target_edge_length, int rounds) {
  Remesher remesher(surface, target_edge_length);
  remesher.run(rounds);
  return remesher.result();
}

}  // namespace facehex
