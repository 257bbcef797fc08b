#include "core/quality/surface_distance.h"

#include <vtkCellArray.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace facehex {

Eigen::VectorXd distances_to_surface(const Eigen::MatrixXd& points, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  vtkNew<vtkPoints> pts;
  pts->SetNumberOfPoints(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) pts->SetPoint(i, V(i, 0), V(i, 1), V(i, 2));
  vtkNew<vtkCellArray> tris;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const vtkIdType ids[3] = {F(f, 0), F(f, 1), F(f, 2)};
    tris->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> surface;
  surface->SetPoints(pts);
  surface->SetPolys(tris);
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(surface);
  locator->BuildLocator();
  Eigen::VectorXd d(points.rows());
  vtkNew<vtkGenericCell> cell;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    double x[3] = {points(i, 0), points(i, 1), points(i, 2)}, closest[3], dist2 = 0;
    vtkIdType cell_id = -1;
    int sub_id = 0;
    locator->FindClosestPoint(x, closest, cell, cell_id, sub_id, dist2);
    d(i) = std::sqrt(dist2);
  }
  return d;
}

DistanceSummary summarize_distances(const Eigen::VectorXd& d) {
  DistanceSummary s;
  s.points = static_cast<int>(d.size());
  if (d.size() == 0) return s;
  std::vector<double> sorted(d.data(), d.data() + d.size());
  std::sort(sorted.begin(), sorted.end());
  s.max = sorted.back();
  s.p95 = sorted[static_cast<size_t>(std::floor(0.95 * static_cast<double>(sorted.size() - 1)))];
  s.mean = d.mean();
  return s;
}

}  // namespace facehex
