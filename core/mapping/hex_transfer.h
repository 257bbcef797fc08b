#pragma once
// The cross-parameterization mapping f = phi_P o phi_S^-1 applied to the vertices of the standard hex mesh
// (paper 3.4): each standard vertex's (u,v,w) is located in the patient's parametric tets and its patient position
// interpolated with the barycentric coordinates. The connectivity of the standard is kept as is.
//
// Boundary exactness: a standard vertex with a coordinate exactly 0 or 1 (it lies on a shape-end side) is placed on
// the patient's side with the same value: barycentric weights of patient tet vertices off that side are zeroed (they
// are zero up to round-off anyway), so it lands exactly on a boundary triangle of the patient model.
#include <Eigen/Core>

#include "core/mapping/param_locator.h"
#include "core/mesh/mesh.h"
#include "core/util/progress.h"

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
  double seconds_mapping = 0;
};

// The patient's inverse parameterization phi_P: a point of the unit cube to its patient position.
class PatientMap {
 public:
  struct Placement {
    Eigen::Vector3d x;
    int tet = -1;
    double violation = 0;  // 0 when q lies in a parametric tet; else how far outside the nearest one
    bool snapped = false;  // q on a cube face, x placed exactly on the patient's side
    bool snap_failed = false;
  };

  // V (#V x 3), T (#T x 4), uvw (#V x 3) of the patient; kept by reference.
  PatientMap(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T, const Eigen::MatrixXd& uvw);

  // hint: a tet to start the search from (the previous hit), or -1.
  Placement place(const Eigen::Vector3d& q, int hint = -1) const;
  // dx/dq on tet t (the inverse of the matrix whose rows are the gradients of u, v, w there).
  Eigen::Matrix3d jacobian(int tet) const;
  const ParamLocator& locator() const { return locator_; }

 private:
  const Eigen::MatrixXd& V_;
  const Eigen::MatrixXi& T_;
  const Eigen::MatrixXd& uvw_;
  ParamLocator locator_;
};

// standard: hex-dominant mesh (#Vs vertices); standard_uvw: #Vs x 3; patient_V: #Vp x 3; patient_T: #Tp x 4;
// patient_uvw: #Vp x 3. Returns the standard's cells on the mapped vertices (point and cell data dropped).
VolumeMesh transfer_hex_mesh(const VolumeMesh& standard, const Eigen::MatrixXd& standard_uvw, const PatientMap& patient,
                             TransferStatistics* statistics = nullptr, const ProgressCallback& progress = {});

}  // namespace facehex
