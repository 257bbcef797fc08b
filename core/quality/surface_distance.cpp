#include "core/quality/surface_distance.h"

#include <vtkCellArray.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSMPTools.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace facehex {

struct SurfaceLocator::Impl {
  vtkNew<vtkPolyData> surface;
  vtkNew<vtkStaticCellLocator> locator;
  bool empty = true;
};

SurfaceLocator::SurfaceLocator(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) : impl_(std::make_unique<Impl>()) {
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) pts->SetPoint(i, V(i, 0), V(i, 1), V(i, 2));
  vtkNew<vtkCellArray> tris;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const vtkIdType ids[3] = {F(f, 0), F(f, 1), F(f, 2)};
    tris->InsertNextCell(3, ids);
  }
  impl_->surface->SetPoints(pts);
  impl_->surface->SetPolys(tris);
  impl_->empty = F.rows() == 0;
  if (impl_->empty) return;
  impl_->locator->SetDataSet(impl_->surface);
  // Built serially: a parallel build orders the cells of a bin by thread timing, and where two triangles are equally
  // close (a point over their common edge) the first one found would then depend on the thread count.
  vtkSMPTools::LocalScope(vtkSMPTools::Config{std::string("Sequential")}, [this] { impl_->locator->BuildLocator(); });
}

SurfaceLocator::~SurfaceLocator() = default;

SurfaceLocator::Hits SurfaceLocator::closest(const Eigen::MatrixXd& points) const {
  Hits hits;
  hits.point = points;
  hits.face = Eigen::VectorXi::Constant(points.rows(), -1);
  hits.distance = Eigen::VectorXd::Constant(points.rows(), std::numeric_limits<double>::infinity());
  if (impl_->empty) return hits;
  vtkNew<vtkGenericCell> cell;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    double x[3] = {points(i, 0), points(i, 1), points(i, 2)}, closest[3], dist2 = 0;
    vtkIdType cell_id = -1;
    int sub_id = 0;
    impl_->locator->FindClosestPoint(x, closest, cell, cell_id, sub_id, dist2);
    hits.point.row(i) << closest[0], closest[1], closest[2];
    hits.face(i) = static_cast<int>(cell_id);
    hits.distance(i) = std::sqrt(dist2);
  }
  return hits;
}

SurfaceLocator::Hits SurfaceLocator::along(const Eigen::MatrixXd& points, const Eigen::Vector3d& direction,
                                           double reach) const {
  Hits hits;
  hits.point = points;
  hits.face = Eigen::VectorXi::Constant(points.rows(), -1);
  hits.distance = Eigen::VectorXd::Constant(points.rows(), std::numeric_limits<double>::infinity());
  if (impl_->empty || !(direction.norm() > 0)) return hits;
  const Eigen::Vector3d d = direction.normalized();
  vtkNew<vtkGenericCell> cell;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d p = points.row(i).transpose();
    for (const double sign : {1.0, -1.0}) {  // the first hit from p each way; the nearer one wins
      const Eigen::Vector3d end = p + sign * reach * d;
      double a[3] = {p.x(), p.y(), p.z()}, b[3] = {end.x(), end.y(), end.z()}, x[3], pcoords[3], t = 0;
      int sub_id = 0;
      vtkIdType cell_id = -1;
      if (!impl_->locator->IntersectWithLine(a, b, 0.0, t, x, pcoords, sub_id, cell_id, cell)) continue;
      const double distance = t * reach;
      if (distance < hits.distance(i)) {
        hits.point.row(i) << x[0], x[1], x[2];
        hits.face(i) = static_cast<int>(cell_id);
        hits.distance(i) = distance;
      }
    }
  }
  return hits;
}

Eigen::Vector3d triangle_barycentric(const Eigen::RowVector3d& p, const Eigen::RowVector3d& a,
                                     const Eigen::RowVector3d& b, const Eigen::RowVector3d& c) {
  const Eigen::RowVector3d e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1), d20 = d.dot(e0), d21 = d.dot(e1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0)) return Eigen::Vector3d(1, 0, 0);
  Eigen::Vector3d l(0, (d11 * d20 - d01 * d21) / den, (d00 * d21 - d01 * d20) / den);
  l = l.cwiseMax(0.0);
  l(0) = std::max(0.0, 1 - l(1) - l(2));
  return l / l.sum();
}

Eigen::VectorXd distances_to_surface(const Eigen::MatrixXd& points, const Eigen::MatrixXd& V,
                                     const Eigen::MatrixXi& F) {
  return SurfaceLocator(V, F).closest(points).distance;
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
