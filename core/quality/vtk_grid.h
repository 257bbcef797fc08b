#pragma once
// VolumeMesh -> vtkUnstructuredGrid, for the VTK filters of the quality module (and anything else that needs one).
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include "core/mesh/mesh.h"

namespace facehex {

// Points and cells only (point_data / cell_data are not copied). Cell i of the grid is cell i of the mesh, with
// VTK_TETRA / VTK_WEDGE / VTK_HEXAHEDRON and the node order unchanged (VolumeMesh already stores VTK order).
vtkSmartPointer<vtkUnstructuredGrid> to_vtk_grid(const VolumeMesh& mesh);

}  // namespace facehex
