#pragma once
// Element quality of hex-dominant meshes (paper section 4) and the dihedral-angle distortion of a mapped mesh
// against its standard (paper Table 1).
//
// Measures per cell:
//  - shape: Verdict hex "shape" (Knupp), via vtkMeshQuality (measure set explicitly). For wedges, VTK 9.1's
//    Verdict has no wedge shape; we use the same definition on the wedge's corners (3 / mean of the corner
//    condition numbers of the corner Jacobians normalized to the ideal wedge), documented in hex_quality.cpp.
//  - scaled_jacobian: minimum over corners of the corner Jacobian determinant divided by the product of the three
//    edge lengths at that corner (hexes: Verdict via vtkMeshQuality; wedges: corner_jacobian.h).
//  - inverted: any corner Jacobian <= 0.
#include "core/mesh.h"

#include <Eigen/Core>
#include <array>
#include <string>

namespace facehex {

struct ElementQuality {
  Eigen::VectorXd shape;            // #C
  Eigen::VectorXd scaled_jacobian;  // #C, in [-1, 1]
};

ElementQuality element_quality(const VolumeMesh& mesh);

struct QualitySummary {
  int cells = 0, hexes = 0, wedges = 0;
  int inverted = 0;                  // cells with a corner Jacobian <= 0
  double shape_min = 0, shape_mean = 0;
  double scaled_jacobian_min = 0, scaled_jacobian_mean = 0;
  double fraction_scaled_jacobian_below_0_3 = 0;
};

QualitySummary summarize(const VolumeMesh& mesh, const ElementQuality& quality);

// Dihedral angles of every cell edge (12 per hex, 9 per wedge, 6 per tet) compared between a reference mesh and a
// mesh with the same connectivity. Bins exactly as the paper's Table 1: [0,4), [4,16), [16,25), [25,36), [36,49),
// [49, inf) degrees of absolute change.
struct DihedralDistortion {
  static constexpr std::array<double, 6> kBinLower = {0, 4, 16, 25, 36, 49};
  std::array<double, 6> percent{};  // share of all edges in each bin, in %
  double max_deg = 0, mean_deg = 0;
  long angles = 0;
};

// Throws facehex::Error if the meshes do not have the same connectivity.
DihedralDistortion dihedral_distortion(const VolumeMesh& reference, const VolumeMesh& mapped);

}  // namespace facehex
