#pragma once
// Distances from points to a closed triangle surface (vtkStaticCellLocator), e.g. from the mapped side vertices of
// a patient hex mesh to the patient model's boundary, and the closest points themselves (registration).
#include <Eigen/Core>
#include <memory>

namespace facehex {

struct DistanceSummary {
  int points = 0;
  double max = 0, p95 = 0, mean = 0;  // mm
};

// Closest points on a fixed triangle surface (V #V x 3, F #F x 3), for many queries (e.g. the iterations of a
// registration). F may be empty: every query then reports face -1 and an infinite distance.
class SurfaceLocator {
 public:
  SurfaceLocator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
  ~SurfaceLocator();
  SurfaceLocator(const SurfaceLocator&) = delete;
  SurfaceLocator& operator=(const SurfaceLocator&) = delete;

  struct Hits {
    Eigen::MatrixXd point;     // #P x 3, the closest surface point of each query
    Eigen::VectorXi face;      // #P, the row of F it lies on
    Eigen::VectorXd distance;  // #P
  };
  Hits closest(const Eigen::MatrixXd& points) const;  // points #P x 3
  // The nearest point where the line through each point along `direction` meets the surface, within `reach` either
  // way; where it meets nothing, face -1, distance infinite and the point itself.
  Hits along(const Eigen::MatrixXd& points, const Eigen::Vector3d& direction, double reach) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Barycentric coordinates of p in triangle (a, b, c), clamped to the triangle (a closest point lies in its triangle
// up to round-off); (1, 0, 0) for a degenerate triangle.
Eigen::Vector3d triangle_barycentric(const Eigen::RowVector3d& p, const Eigen::RowVector3d& a,
                                     const Eigen::RowVector3d& b, const Eigen::RowVector3d& c);

// points: #P x 3; surface: V #V x 3 and F #F x 3 triangles.
Eigen::VectorXd distances_to_surface(const Eigen::MatrixXd& points, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
DistanceSummary summarize_distances(const Eigen::VectorXd& d);

}  // namespace facehex
