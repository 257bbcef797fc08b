#pragma once
// The cross-parameterization mapping f = phi_P o phi_S^-1 applied to the vertices of the standard hex mesh
// (paper 3.4): each standard vertex's (u,v,w) is located in the patient's parametric tets and its patient position
// interpolated with the barycentric coordinates. The connectivity of the standard is kept as is.
//
// Boundary exactness: a standard vertex with a coordinate exactly 0 or 1 (it lies on a shape-end side) is placed on
// the patient's side with the same value: barycentric weights of patient tet vertices off that side are zeroed (they
// are zero up to round-off anyway), so it lands exactly on a boundary triangle of the patient model.
#include "core/mesh.h"
#include "core/progress.h"

#include <Eigen/Core>

namespace facehex {

struct TransferStatistics {
  int vertices = 0;
  int located_inside = 0;       // found inside a parametric tet
  int located_nearest = 0;      // outside every tet: nearest tet, clamped weights
  double max_violation = 0;     // largest -min(barycentric) among the nearest-tet placements
  int snapped_to_boundary = 0;  // placed exactly on a patient side
  int snap_failures = 0;        // on a side, but the tet found has no vertex on it (kept inside)
  int walk_hits = 0;            // located by walking from the previous hit
  Eigen::VectorXi tet;          // #Vs, the patient tet each standard vertex was placed in
  double seconds_locator_build = 0, seconds_mapping = 0;
};

// standard: hex-dominant mesh (#Vs vertices); standard_uvw: #Vs x 3; patient_V: #Vp x 3; patient_T: #Tp x 4;
// patient_uvw: #Vp x 3. Returns the standard's cells on the mapped vertices (point and cell data dropped).
VolumeMesh transfer_hex_mesh(const VolumeMesh& standard, const Eigen::MatrixXd& standard_uvw,
                             const Eigen::MatrixXd& patient_V, const Eigen::MatrixXi& patient_T,
                             const Eigen::MatrixXd& patient_uvw, TransferStatistics* statistics = nullptr,
                             const ProgressCallback& progress = {});

}  // namespace facehex
