#include "core/segment/iso_surface.h"

#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataConnectivityFilter.h>

#include <Eigen/Geometry>
#include <map>

#include "core/io/vtk_util.h"
#include "core/tetgen/tetrahedralize.h"
#include "core/util/error.h"

namespace facehex {
namespace {}  // namespace

bool is_closed_manifold(const SurfaceMesh& surface) {
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < surface.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (++directed[{surface.F(f, k), surface.F(f, (k + 1) % 3)}] > 1) return false;
  for (const auto& [edge, count] : directed)
    if (!directed.count({edge.second, edge.first})) return false;
  return !directed.empty();
}

SurfaceMesh zero_level_surface(const Field& phi) {
  // One layer of "outside" around the grid closes the surface where the region touches the grid's border.
  const GridGeometry& g = phi.geometry;
  vtkNew<vtkImageData> image;
  image->SetDimensions(g.dims[0] + 2, g.dims[1] + 2, g.dims[2] + 2);
  image->SetSpacing(g.spacing.data());
  const Eigen::Vector3d origin = g.origin - g.spacing;
  image->SetOrigin(origin.data());
  vtkNew<vtkFloatArray> values;
  values->SetNumberOfValues(image->GetNumberOfPoints());
  bool any_inside = false;
  vtkIdType n = 0;
  for (int k = -1; k <= g.dims[2]; ++k)
    for (int j = -1; j <= g.dims[1]; ++j)
      for (int i = -1; i <= g.dims[0]; ++i) {
        const float v = g.contains(i, j, k) ? phi(i, j, k) : 1.0f;
        any_inside |= v < 0;
        values->SetValue(n++, v);
      }
  if (!any_inside) throw Error("segment", "the soft-tissue region is empty");
  image->GetPointData()->SetScalars(values);

  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(image);
  contour->SetValue(0, 0.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  vtkNew<vtkCleanPolyData> merge;  // Flying Edges may emit a degenerate triangle where phi is exactly 0 at a vertex
  merge->SetInputConnection(contour->GetOutputPort());
  merge->ConvertLinesToPointsOff();
  merge->ConvertPolysToLinesOff();
  merge->PointMergingOn();
  vtkNew<vtkPolyDataConnectivityFilter> largest;
  largest->SetInputConnection(merge->GetOutputPort());
  largest->SetExtractionModeToLargestRegion();
  vtkNew<vtkCleanPolyData> compact;
  compact->SetInputConnection(largest->GetOutputPort());
  compact->Update();
  SurfaceMesh full = io::triangles_of("surface extraction", compact->GetOutput());
  if (enclosed_volume(full) < 0) full.F.col(1).swap(full.F.col(2));

  if (!is_closed_manifold(full)) throw NonManifoldSurface();
  return full;
}

}  // namespace facehex
