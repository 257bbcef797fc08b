#pragma once
// Distances from points to a closed triangle surface (vtkStaticCellLocator), e.g. from the mapped side vertices of
// a patient hex mesh to the patient model's boundary.
#include <Eigen/Core>

namespace facehex {

struct DistanceSummary {
  int points = 0;
  double max = 0, p95 = 0, mean = 0;  // mm
};

// points: #P x 3; surface: V #V x 3 and F #F x 3 triangles.
Eigen::VectorXd distances_to_surface(const Eigen::MatrixXd& points, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
DistanceSummary summarize_distances(const Eigen::VectorXd& d);

}  // namespace facehex
