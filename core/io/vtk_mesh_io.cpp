#include "core/io/vtk_mesh_io.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCellTypes.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <functional>

#include "core/io/io_util.h"
#include "core/io/mesh_bytes.h"
#include "core/io/vtk_util.h"
#include "core/util/child_process.h"
#include "core/util/error.h"

namespace facehex::io {

namespace {

// The cell array's offsets must describe its connectivity (VTK's accessors trust them): one offset per cell and one
// more, from 0, never decreasing, ending at the connectivity's length; one type per cell.
void check_cell_array(const std::string& path, vtkUnstructuredGrid* grid) {
  vtkCellArray* cells = grid->GetCells();
  const vtkIdType nc = grid->GetNumberOfCells();
  if (nc == 0) return;
  vtkDataArray* offsets = cells ? cells->GetOffsetsArray() : nullptr;
  vtkDataArray* connectivity = cells ? cells->GetConnectivityArray() : nullptr;
  if (!offsets || !connectivity || offsets->GetNumberOfTuples() != nc + 1)
    throw Error(path, "the cell offsets do not match the number of cells (a damaged file)");
  if (!grid->GetCellTypesArray() || grid->GetCellTypesArray()->GetNumberOfTuples() != nc)
    throw Error(path, "the cell types do not match the number of cells (a damaged file)");
  double previous = 0;
  for (vtkIdType i = 0; i <= nc; ++i) {
    const double o = offsets->GetComponent(i, 0);
    if ((i == 0 && o != 0) || o < previous || o > static_cast<double>(connectivity->GetNumberOfTuples()))
      throw Error(path, "cell offset " + std::to_string(i) + " is out of order or range (a damaged file)");
    previous = o;
  }
  if (previous != static_cast<double>(connectivity->GetNumberOfTuples()))
    throw Error(path, "the cell offsets do not cover the connectivity (a damaged file)");
}

// VolumeMesh stores cells in VTK order already: conversion is a copy, no reordering.
VolumeMesh from_grid(const std::string& path, vtkUnstructuredGrid* grid) {
  if (!grid || grid->GetNumberOfPoints() == 0) throw Error(path, "file holds no points (empty or not a mesh)");
  check_cell_array(path, grid);
  VolumeMesh mesh;
  const vtkIdType nv = grid->GetNumberOfPoints();
  mesh.V.resize(nv, 3);
  for (vtkIdType i = 0; i < nv; ++i) {
    double p[3];
    grid->GetPoint(i, p);
    mesh.V.row(i) << p[0], p[1], p[2];
  }
  CellBuilder cells;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    const int vtk_type = grid->GetCellType(c);
    CellType type;
    switch (vtk_type) {
      case VTK_TETRA:
        type = CellType::Tet;
        break;
      case VTK_WEDGE:
        type = CellType::Wedge;
        break;
      case VTK_HEXAHEDRON:
        type = CellType::Hex;
        break;
      default:
        throw Error(path, "cell " + std::to_string(c) + " has unsupported type " +
                              vtkCellTypes::GetClassNameFromTypeId(vtk_type) + " (VTK type " +
                              std::to_string(vtk_type) + "); only tetra, wedge and hexahedron cells are supported");
    }
    grid->GetCellPoints(c, ids);
    if (ids->GetNumberOfIds() != node_count(type)) {
      throw Error(path, "cell " + std::to_string(c) + " has " + std::to_string(ids->GetNumberOfIds()) + " nodes");
    }
    int nodes[8];
    for (int k = 0; k < node_count(type); ++k) {
      const vtkIdType id = ids->GetId(k);  // 64-bit: an index past 2^31 must not wrap into a valid one
      if (id < 0 || id >= nv)
        throw Error(
            path, "cell " + std::to_string(c) + " refers to point " + std::to_string(id) + " of " + std::to_string(nv));
      nodes[k] = static_cast<int>(id);
    }
    cells.add(type, nodes);
  }
  cells.finish(&mesh);
  vtk_arrays_to_matrices(path, grid->GetPointData(), mesh.num_vertices(), &mesh.point_data);
  vtk_arrays_to_matrices(path, grid->GetCellData(), mesh.num_cells(), &mesh.cell_data);
  vtk_arrays_to_matrices(path, grid->GetFieldData(), -1, &mesh.field_data);
  check_volume_mesh(path, mesh);
  return mesh;
}

vtkSmartPointer<vtkUnstructuredGrid> to_grid(const VolumeMesh& mesh, const std::set<std::string>& single_precision) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();  // full precision in the file
  points->SetNumberOfPoints(mesh.num_vertices());
  for (int i = 0; i < mesh.num_vertices(); ++i) points->SetPoint(i, mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2));
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  grid->Allocate(mesh.num_cells());
  for (int c = 0; c < mesh.num_cells(); ++c) {
    const int vtk_type = mesh.types[c] == CellType::Tet     ? VTK_TETRA
                         : mesh.types[c] == CellType::Wedge ? VTK_WEDGE
                                                            : VTK_HEXAHEDRON;
    vtkIdType ids[8];
    for (int k = 0; k < node_count(mesh.types[c]); ++k) ids[k] = mesh.C(c, k);
    grid->InsertNextCell(vtk_type, node_count(mesh.types[c]), ids);
  }
  matrices_to_vtk_arrays(mesh.point_data, grid->GetPointData(), single_precision);
  matrices_to_vtk_arrays(mesh.cell_data, grid->GetCellData(), single_precision);
  matrices_to_vtk_arrays(mesh.field_data, grid->GetFieldData(), {});
  return grid;
}

// VTK's readers trust the sizes a file declares: a damaged file can make them crash, loop or allocate without bound.
// They run in a child process with a time and memory budget that grow with the file (core/util/child_process.h).
VolumeMesh read_in_child(const std::string& path, const std::string& what, const std::function<VolumeMesh()>& read) {
  return mesh_from_bytes(compute_in_child(
                             path, what, [&] { return to_bytes(read()); }, limits_for_reading(path)),
                         path);
}

}  // namespace

VolumeMesh read_vtu(const std::string& path) {
  check_readable_file(path);
  check_vtk_xml_sizes(path);
  return read_in_child(path, "reading VTK XML", [&] {
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    reader->SetFileName(path.c_str());
    run_vtk(path, "reading VTK XML", reader);
    return from_grid(path, reader->GetOutput());
  });
}

VolumeMesh read_legacy_vtk(const std::string& path) {
  check_readable_file(path);
  check_legacy_vtk_cells(path);
  return read_in_child(path, "reading legacy VTK", [&] {
    vtkNew<vtkUnstructuredGridReader> reader;
    reader->SetFileName(path.c_str());
    reader->ReadAllScalarsOn();  // legacy files may hold several arrays per kind; keep them all
    reader->ReadAllVectorsOn();
    reader->ReadAllTensorsOn();
    reader->ReadAllFieldsOn();
    run_vtk(path, "reading legacy VTK", reader);
    return from_grid(path, reader->GetOutput());
  });
}

void write_vtu(const std::string& file, const VolumeMesh& mesh, const std::set<std::string>& single_precision) {
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(to_grid(mesh, single_precision));
  writer->SetFileName(file.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw binary: smaller, and nothing is lost
  writer->SetCompressorTypeToZLib();
  // zlib's fastest level: floating-point fields compress little at any level, so higher levels cost write time for
  // hardly a smaller file.
  writer->SetCompressionLevel(1);
  writer->SetHeaderTypeToUInt64();  // no 4 GB limit per array
  run_vtk(file, "writing VTK XML", writer, [&] { return writer->Write(); });
}

void write_legacy_vtk(const std::string& file, const VolumeMesh& mesh, const std::set<std::string>& single_precision) {
  vtkNew<vtkUnstructuredGridWriter> writer;
  writer->SetInputData(to_grid(mesh, single_precision));
  writer->SetFileName(file.c_str());
  writer->SetFileTypeToBinary();
  run_vtk(file, "writing legacy VTK", writer, [&] { return writer->Write(); });
}

}  // namespace facehex::io
