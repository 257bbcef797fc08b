#pragma once
// One transfer as both front ends run it: the standard's parameterization (from its cache when it fits), the
// patient's, the mapping, relaxation and repair (core/mapping/transfer_pipeline.h), then the result decorated with
// every array the outputs carry and its quality against the standard.
#include <string>

#include "core/io/mesh_io.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/mesh.h"
#include "core/quality/surface_distance.h"
#include "core/util/progress.h"
#include "core/workflow/patient_setup.h"
#include "core/workflow/report.h"
#include "core/workflow/standard_setup.h"

namespace facehex {

struct TransferResult {
  TransferRun run;         // the engine's record: parameterizations, mapping, relaxation, repair, timings
  VolumeMesh patient_hex;  // decorate_patient_hex(run.patient_hex): what every front end writes and shows
  MeshQualityReport standard_quality, plain_mapping_quality, patient_quality;  // plain: before relaxation and repair
  DistanceSummary distance;  // the standard's side vertices from the patient's surface
  std::string cache_note;    // why the standard's cache was not used, when it exists but does not fit
};

// Throws facehex::Error naming the file or stage; facehex::Cancelled when `progress` asks to stop.
TransferResult transfer(const StandardSetup& standard, const PatientSetup& patient, const TransferOptions& options,
                        const ProgressCallback& progress = {});

// The result's hex mesh with its arrays: cell data "shape", "scaled_jacobian" (element quality), "dihedral_change"
// (mean dihedral-angle change per cell against the standard, degrees); point data "moved_from_mapping" (mm the
// relaxation and repair moved each vertex), "uvw" (the standard's parameters), "side_mask" (the standard's), and the
// FE sets and material frames (core/io/fe_sets.h attach_fe_arrays).
VolumeMesh decorate_patient_hex(const TransferRun& run, const VolumeMesh& standard);

// `mesh` with its element quality: cell data "shape" and "scaled_jacobian".
VolumeMesh with_quality(VolumeMesh mesh);

// The standard with its fields at its vertices (point data u, v, w, uvw, uvw_initial, fixed_uvw) and its quality.
VolumeMesh standard_with_fields(const VolumeMesh& standard, const ModelParameterization& p);

// A parameterized tet model (the patient's) with its fields and per-tet gradients before and after the
// orthogonality improvement (cell data grad_u, grad_u_initial, ...); `source`'s point data is kept when it has the
// same vertices. Write it with parameterized_model_writing().
VolumeMesh parameterized_tet_mesh(const ModelParameterization& p, const VolumeMesh* source);

// The writing options of a parameterized tet model: its gradients as 32-bit floats (they are for display).
MeshWriteOptions parameterized_model_writing();

// The exit-code policy of every command that writes a mesh: 0 when no cell is inverted or flat, else 3 (the mesh
// is written and the report says where).
constexpr int kExitUnusableCells = 3;
int exit_code(const QualitySummary& result);

}  // namespace facehex
