#pragma once
// VTK plumbing shared by the volume (vtk_mesh_io.cpp) and surface (surface_io.cpp) formats and the segmentation's
// surface extraction.
//
// VTK readers and writers do not throw: they print to stderr and return empty or half-filled output. Every VTK
// pipeline call of core/io therefore goes through run_vtk(), which silences that output, collects the messages and
// turns any error into a facehex::Error naming the file.
#include <Eigen/Core>
#include <functional>
#include <map>
#include <set>
#include <string>

#include "core/mesh/mesh.h"

class vtkAlgorithm;
class vtkPolyData;
class vtkFieldData;
class vtkDataSetAttributes;

namespace facehex::io {

// Runs `action` (default: updating the algorithm; writers pass their Write(), which vtkWriter and vtkXMLWriter
// declare separately) with VTK's messages captured. Throws facehex::Error(path, "<what> failed: <first VTK error>")
// when the algorithm reported an error, its error code is set or the update / action returned 0.
void run_vtk(const std::string& path, const std::string& what, vtkAlgorithm* algorithm,
             const std::function<int()>& action = nullptr);

// Numeric arrays of `data` (one row per tuple) into `out`, by name; unnamed arrays become "array<i>", non-numeric
// arrays (strings) are skipped. Throws unless every array has `rows` tuples (any number when rows < 0: field data).
void vtk_arrays_to_matrices(const std::string& path, vtkFieldData* data, int rows,
                            std::map<std::string, Eigen::MatrixXd>* out);
// Each matrix as an array with as many components as columns: doubles, or 32-bit floats if its name is in
// `single_precision`.
void matrices_to_vtk_arrays(const std::map<std::string, Eigen::MatrixXd>& arrays, vtkFieldData* out,
                            const std::set<std::string>& single_precision = {});

// The points and triangles of a polydata (polygons must all be triangles: throws facehex::Error(subject, ...)
// otherwise). Labels are left empty.
SurfaceMesh triangles_of(const std::string& subject, vtkPolyData* poly);

}  // namespace facehex::io
