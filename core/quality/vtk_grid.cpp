#include "core/quality/vtk_grid.h"

#include <vtkCellType.h>
#include <vtkPoints.h>

namespace facehex {

namespace {

int vtk_cell_type(CellType type) {
  if (type == CellType::Tet) return VTK_TETRA;
  if (type == CellType::Wedge) return VTK_WEDGE;
  return VTK_HEXAHEDRON;
}

}  // namespace

vtkSmartPointer<vtkUnstructuredGrid> to_vtk_grid(const VolumeMesh& mesh) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.num_vertices());
  for (int v = 0; v < mesh.num_vertices(); ++v) points->SetPoint(v, mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2));

  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->AllocateEstimate(mesh.num_cells(), 8);
  vtkIdType ids[8];
  for (int c = 0; c < mesh.num_cells(); ++c) {
    const int n = node_count(mesh.types[c]);
    for (int i = 0; i < n; ++i) ids[i] = mesh.C(c, i);
    grid->InsertNextCell(vtk_cell_type(mesh.types[c]), n, ids);
  }
  return grid;
}

}  // namespace facehex
