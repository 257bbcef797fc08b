// Triangle surfaces (.stl, .obj, .ply, .vtp) through VTK's readers and writers: read_surface_mesh and
// write_surface_mesh of mesh_io.h.
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCleanPolyData.h>
#include <vtkDataArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkOBJWriter.h>
#include <vtkPLYReader.h>
#include <vtkPLYWriter.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSTLWriter.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include "core/io/io_util.h"
#include "core/io/mesh_bytes.h"
#include "core/io/mesh_io.h"
#include "core/io/surface_file_checks.h"
#include "core/io/vtk_util.h"
#include "core/util/atomic_file.h"
#include "core/util/child_process.h"
#include "core/util/error.h"

namespace facehex {

namespace {

// Name of the per-face label array in .vtp files (the only surface format here that can carry one).
constexpr const char* kLabels = "labels";

template <class Reader>
vtkSmartPointer<vtkAlgorithm> make_reader(const std::string& path) {
  auto reader = vtkSmartPointer<Reader>::New();
  reader->SetFileName(path.c_str());
  return reader;
}

// VTK's filters trust the readers' connectivity; a damaged file can refer to points that do not exist.
void check_point_ids(const std::string& path, vtkPolyData* poly) {
  if (!poly || poly->GetNumberOfPoints() == 0) {
    throw Error(path, "file holds no points (empty, damaged or not a surface)");
  }
  const vtkIdType n = poly->GetNumberOfPoints();
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < poly->GetNumberOfCells(); ++c) {
    poly->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
      if (ids->GetId(k) < 0 || ids->GetId(k) >= n) {
        throw Error(path, "cell " + std::to_string(c) + " refers to point " + std::to_string(ids->GetId(k)) +
                              ", but there are " + std::to_string(n));
      }
    }
  }
}

void check_surface(const std::string& subject, const SurfaceMesh& s) {
  if (s.V.rows() == 0 || s.V.cols() != 3) throw Error(subject, "surface has no points");
  if (!s.V.allFinite()) throw Error(subject, "surface has non-finite point coordinates");
  if (s.F.rows() == 0 || s.F.cols() != 3) throw Error(subject, "surface has no triangles");
  if (s.F.minCoeff() < 0 || s.F.maxCoeff() >= s.V.rows()) {
    throw Error(subject, "triangle refers to a point out of range 0.." + std::to_string(s.V.rows() - 1));
  }
  if (s.labels.size() != 0 && s.labels.size() != s.F.rows()) {
    throw Error(subject, "surface has " + std::to_string(s.labels.size()) + " labels for " +
                             std::to_string(s.F.rows()) + " triangles");
  }
}

// The surface through VTK's readers, triangulated, its exact duplicate points merged (in the reading child).
SurfaceMesh read_surface_here(const std::string& path, const std::string& ext) {
  vtkSmartPointer<vtkAlgorithm> reader;
  if (ext == ".stl") {
    reader = make_reader<vtkSTLReader>(path);
  } else if (ext == ".obj") {
    reader = make_reader<vtkOBJReader>(path);
  } else if (ext == ".ply") {
    reader = make_reader<vtkPLYReader>(path);
  } else {
    reader = make_reader<vtkXMLPolyDataReader>(path);
  }
  io::run_vtk(path, "reading the surface", reader);
  check_point_ids(path, vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0)));

  // Polygons -> triangles, then merge the per-triangle copies of each point that STL and some OBJ files have (exact
  // matches only: a tolerance would silently weld nearby points of a fine surface).
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputConnection(reader->GetOutputPort());
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(triangulate->GetOutputPort());
  clean->ToleranceIsAbsoluteOn();
  clean->SetAbsoluteTolerance(0.0);
  clean->ConvertPolysToLinesOff();  // drop triangles that collapse, rather than keep them as lines
  clean->ConvertLinesToPointsOff();
  io::run_vtk(path, "triangulating the surface", clean);
  vtkPolyData* poly = clean->GetOutput();

  SurfaceMesh s = io::triangles_of(path, poly);
  // Verts and lines were not passed, so cell i is triangle i.
  if (vtkDataArray* labels = poly->GetCellData()->GetArray(kLabels);
      labels && labels->GetNumberOfTuples() == s.F.rows() && labels->GetNumberOfComponents() == 1) {
    s.labels.resize(s.F.rows());
    for (int f = 0; f < s.F.rows(); ++f) s.labels[f] = static_cast<int>(labels->GetComponent(f, 0));
  }
  if (s.F.rows() == 0) throw Error(path, "file holds no triangles (empty, damaged or not a surface)");
  return s;
}

}  // namespace

SurfaceMesh read_surface_mesh(const std::string& path) {
  const std::string ext = io::lower_extension(path);
  if (!is_surface_file(path)) {
    throw Error(path, "unknown surface file extension '" + ext + "' (readable: .stl, .obj, .ply, .vtp)");
  }
  io::check_readable_file(path);
  if (ext == ".stl") io::check_stl_file(path);
  if (ext == ".obj") io::check_obj_file(path);
  if (ext == ".ply") io::check_ply_file(path);
  if (ext == ".vtp") io::check_vtk_xml_sizes(path);
  // VTK's readers trust the sizes a file declares: they run in a child process with a time and memory budget that
  // grow with the file (core/util/child_process.h).
  SurfaceMesh s =
      io::surface_from_bytes(compute_in_child(
                                 path, "reading the surface",
                                 [&] { return io::to_bytes(read_surface_here(path, ext)); }, limits_for_reading(path)),
                             path);
  check_surface(path, s);
  return s;
}

void write_surface_mesh(const std::string& path, const SurfaceMesh& surface) {
  const std::string ext = io::lower_extension(path);
  if (ext != ".vtp" && ext != ".stl" && ext != ".ply" && ext != ".obj") {
    throw Error(path, "cannot write surfaces as '" + ext + "' (writable: .vtp, .stl, .ply, .obj)");
  }
  check_surface(path, surface);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(surface.V.rows());
  for (int i = 0; i < surface.V.rows(); ++i) points->SetPoint(i, surface.V(i, 0), surface.V(i, 1), surface.V(i, 2));
  vtkNew<vtkCellArray> triangles;
  for (int f = 0; f < surface.F.rows(); ++f) {
    const vtkIdType ids[3] = {surface.F(f, 0), surface.F(f, 1), surface.F(f, 2)};
    triangles->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetPolys(triangles);
  if (surface.labels.size() != 0) {
    vtkNew<vtkIntArray> labels;
    labels->SetName(kLabels);
    labels->SetNumberOfTuples(surface.labels.size());
    for (int f = 0; f < surface.labels.size(); ++f) labels->SetValue(f, surface.labels[f]);
    poly->GetCellData()->AddArray(labels);
  }

  write_atomically(path, [&](const std::string& tmp) {
    if (ext == ".vtp") {
      vtkNew<vtkXMLPolyDataWriter> writer;
      writer->SetInputData(poly);
      writer->SetFileName(tmp.c_str());
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOff();
      writer->SetCompressorTypeToZLib();
      io::run_vtk(tmp, "writing VTK XML", writer, [&] { return writer->Write(); });
    } else if (ext == ".stl") {
      vtkNew<vtkSTLWriter> writer;  // binary: STL stores floats either way, and binary is far smaller
      writer->SetInputData(poly);
      writer->SetFileName(tmp.c_str());
      writer->SetFileTypeToBinary();
      io::run_vtk(tmp, "writing STL", writer, [&] { return writer->Write(); });
    } else if (ext == ".ply") {
      vtkNew<vtkPLYWriter> writer;
      writer->SetInputData(poly);
      writer->SetFileName(tmp.c_str());
      writer->SetFileTypeToBinary();
      io::run_vtk(tmp, "writing PLY", writer, [&] { return writer->Write(); });
    } else {
      vtkNew<vtkOBJWriter> writer;
      writer->SetInputData(poly);
      writer->SetFileName(tmp.c_str());
      io::run_vtk(tmp, "writing OBJ", writer, [&] { return writer->Write(); });
    }
  });
}

}  // namespace facehex
