#pragma once
// One transfer as both front ends run it: the standard's parameterization (from its cache when it fits), the
// patient's, the mapping, relaxation and repair (core/mapping/transfer_pipeline.h), then the result decorated with
// every array the outputs carry and its quality against the standard.
#include <optional>
#include <string>
#include <vector>

#include "core/correspondence/registered_sides.h"
#include "core/io/mesh_io.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/mesh.h"
#include "core/quality/surface_distance.h"
#include "core/util/progress.h"
#include "core/workflow/feature_landing.h"
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
  // SkinCorrespondence::registered: the registration's conditions and figures, and the feature constraints it left out.
  std::optional<RegisteredSides> registration;
  std::vector<std::string> left_out_constraints;
  // Why the registered skin was asked for but the feature constraints were used (its error), or empty.
  std::string registered_failure;
  // The patient model's openings closed as the standard's (transfer()), e.g. "3 of 4 openings closed by TetGen
  // plugs", or empty when it had none.
  std::string patient_openings;
  // Where the standard's landmarks landed against the patient's (feature_landing.h); empty when the patient has no
  // landmarks or the standard's own are not found.
  std::vector<FeatureLanding> landing;
};

// With options.skin_correspondence registered, the sides are registered first (core/correspondence/
// registered_sides.h): the patient's constraints from a file are kept whole; of those placed by the constraint
// policy, the feature constraints are left out (the registration places the skin; user-given landmarks, and with
// options.pull_found_landmarks the found and estimated ones, pull it as landmark pairs, and the shape relaxation and
// the repair keep the standard's landmark vertices where the mapping put them). When that transfer fails (the
// registration left the skins apart and the fields fold beyond options.max_inverted_fraction, even with
// allow_inverted_parameterization, or the repair diverged), it runs again with the feature constraints, and
// registered_failure says why; when the policy could not place them either (patient.features_problem), that is an error
// naming both. When the standard's domain has openings closed by plugs (core/standard/closed_domain.h), a patient model
// with openings (walls on no side: open eyes, nostrils or a mouth) is parameterized with them closed the same way
// (close_openings): harmonic fields bend around an open rim where the standard's do not, and the two
// parameterizations would not correspond there. A segmented CT's model has none.
// Throws facehex::Error naming the file or stage; facehex::Cancelled when `progress` asks to stop.
TransferResult transfer(const StandardSetup& standard, const PatientSetup& patient, const TransferOptions& options,
                        const ProgressCallback& progress = {});

// The result's hex mesh with its arrays: cell data "shape", "scaled_jacobian" (element quality), "dihedral_change"
// (mean dihedral-angle change per cell against the standard, degrees); point data "moved_from_mapping" (mm the
// relaxation and repair moved each vertex), "uvw" (the standard's parameters), "side_mask" (the standard's), and the
// FE sets and material frames (core/io/fe_sets.h attach_fe_arrays).
VolumeMesh decorate_patient_hex(const TransferRun& run, const VolumeMesh& standard);

// report.json's "skin_correspondence": {"mode": "features" or "registered"}, with "registered_failure" (empty, or why
// the registered skin asked for was not used) for the features, and for a registered skin "vertices"
// (patient skin vertices given the standard's (u, v)), "too_far" (left free: farther than the bound from the
// registered standard), "distance_mm" {mean, p95, max} (every skin vertex from the registered standard),
// "left_out_constraints" and "seconds". skin_correspondence_text: the same in one line for people.
nlohmann::json skin_correspondence_json(const TransferResult& result);
std::string skin_correspondence_text(const TransferResult& result);

// `mesh` with its element quality: cell data "shape" and "scaled_jacobian".
VolumeMesh with_quality(VolumeMesh mesh);

// The standard with its fields at its vertices (point data u, v, w, uvw, uvw_initial, fixed_uvw) and its quality.
VolumeMesh standard_with_fields(const VolumeMesh& standard, const ModelParameterization& p);

// A parameterized tet model (the patient's) with its fields and per-tet gradients before and after the
// orthogonality improvement (cell data grad_u, grad_u_initial, ...); `source`'s point data and field data (the
// landmarks a segmentation read in the CT: ct_landmarks.h) are kept when its vertices are the first of the model's
// (all of them, or all but the inner vertices of the plugs transfer() closed its openings with, whose rows are 0: on
// no side), so that the written model, run again, finds the same landmarks. Write it with
// parameterized_model_writing().
VolumeMesh parameterized_tet_mesh(const ModelParameterization& p, const VolumeMesh* source);

// The writing options of a parameterized tet model: its gradients as 32-bit floats (they are for display).
MeshWriteOptions parameterized_model_writing();

// The exit-code policy of every command that writes a mesh: 0 when no cell is inverted or flat, else 3 (the mesh
// is written and the report says where).
constexpr int kExitUnusableCells = 3;
int exit_code(const QualitySummary& result);

}  // namespace facehex
