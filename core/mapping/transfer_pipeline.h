#pragma once
// The whole method on in-memory data, shared by the CLI and the GUI: parameterize the standard (through its
// auxiliary tet mesh) and the patient, check both parameterizations, and map the standard hex mesh onto the patient.
#include <map>
#include <string>

#include "core/fields/constraint_set.h"
#include "core/fields/harmonic_fields.h"
#include "core/fields/parameterization.h"
#include "core/fields/tet_domain.h"
#include "core/mapping/hex_transfer.h"
#include "core/mesh/mesh.h"
#include "core/shape/untangle.h"
#include "core/util/progress.h"

namespace facehex {

// How the standard's skin finds its place on the patient's (core/workflow/transfer.h):
//  - registered: the two models' sides are registered (core/correspondence/registered_sides.h) and the patient's
//    skin gets the standard's (u, v) at its correspondents; automatically placed feature constraints are left out
//    (the registration places the whole skin); where that gives no usable map, the feature constraints are used;
//  - features: the paper's: the fields are free on the skin but for the feature constraints at the landmarks.
// docs/results.md compares the two.
enum class SkinCorrespondence { registered, features };

struct TransferOptions {
  HarmonicFieldsOptions fields;
  SkinCorrespondence skin_correspondence = SkinCorrespondence::registered;
  // With the registered skin: the shape relaxation holds the standard's skin vertices at their registered
  // correspondents (correspondence before cell shape) instead of sliding them along the skin with the rest.
  bool hold_registered_skin = false;
  // With the registered skin: the patient's found and estimated landmarks pull the registration towards the
  // standard's of the same names, as given landmarks always do (core/workflow/transfer.h): the registration of the
  // whole skin alone follows its shape, not its features, and leaves a mouth or eyes of other proportions than the
  // standard's several millimetres off (docs/results.md).
  bool pull_found_landmarks = true;
  // Landmarks (landmark_file.h names, left and right the patient's) that pull the registration in no case, found,
  // estimated or given: one the user does not trust on this face (a flat forehead's glabella reads millimetres up or
  // down it, docs/results.md).
  std::vector<std::string> landmarks_not_pulled;
  // A parameterization with inverted tets is not a bijection. Local folds (at most max_inverted_fraction of the
  // patient's tets) are reported and their effect on the hex mesh repaired by the untangler; more stop the run with
  // an error, unless allow_inverted_parameterization.
  double max_inverted_fraction = 0.01;
  bool allow_inverted_parameterization = false;
  // After the mapping, cells that are inverted or below untangle_options.min_scaled_jacobian are repaired by moving
  // nearby vertices that are on no side and no feature (untangle.h).
  bool repair_folds = true;
  UntangleOptions untangle_options;
  // Before the repair, every vertex moves through its (u, v, w) (pinned coordinates stay: side and feature vertices
  // only slide along their side or feature) to bring each corner back to the standard's shape (untangle.h with the
  // standard as target): the harmonic map puts vertices at the right place on the patient but shears the cells in
  // between; this keeps the correspondence of sides and features and the standard's angles.
  bool shape_relaxation = true;
  // The relaxation's target corners: the standard's, moved towards the ideal cell's by this fraction of their
  // distortion in the mapped mesh (UntangleOptions::target_towards_ideal): 0 keeps the standard's angles best but
  // leaves cells less well shaped than the standard's; 1 shapes them better at some cost in angles (the trade-off is
  // measured in docs/benchmarks.md).
  double relaxation_towards_ideal = 1;
  // The relaxation (and the repair after it) holds each vertex near where the mapping put it, where the registered
  // skin and the landmarks' pull made the correspondence (UntangleOptions::tether_weight: a slide of one edge length
  // costs this much): sliding freely, vertices move millimetres along the skin for shapes the tethered relaxation
  // nearly matches (the trade-off is measured in docs/results.md). 0: they slide freely.
  double relaxation_tether = 0.2;
  // The relaxation (and the repair after it) aims at the ideal cells instead of the standard's: for a template grid,
  // whose cells in parameter space are no shape to keep.
  bool ideal_cell_targets = false;
  // The repair's last polish of the cells still below their bound moves side and feature vertices too, in space, off
  // the patient's surfaces: for a template, which may cut a corner of its reference where no cell there can reach the
  // bound (template_mesh.h).
  bool polish_moves_sides = false;
};

// Dirichlet conditions on whole sides of the patient (the dense correspondence of core/correspondence/
// registered_sides.h): added to the patient's constraints at the vertices they leave free in each field. The
// standard's vertices flagged in `held` (#V of its domain, or empty) then keep their (u, v) through the shape
// relaxation, as feature vertices do, so that the relaxation does not slide them away from their correspondents.
struct SideConditions {
  FieldConditions fields;
  std::vector<char> held;
};

struct TransferRun {
  ModelParameterization standard, patient;   // standard: on its domain; its first #Vs rows are the hex vertices
  std::string standard_domain;               // how the standard's tet domain was built
  std::string patient_domain;                // the patient's (its own tets; its openings closed: workflow/transfer.h)
  int standard_domain_non_positive = 0;      // domain tets with non-positive volume (badly shaped standard cells)
  int standard_relaxed_corner_vertices = 0;  // side labels dropped at the standard's shell corners
  std::string standard_parameterization_source = "computed";  // or where it was read from (a cache)
  VolumeMesh mapped_hex;                                      // the mapping's result, before relaxation and repair
  VolumeMesh patient_hex;                                     // the result
  TransferStatistics transfer;
  UntangleReport relaxation;  // shape relaxation (TransferOptions::shape_relaxation)
  UntangleReport untangle;
  std::map<std::string, double> seconds;  // stage timings
};

// standard: hex-dominant mesh with its constraint set, parameterized on `domain` (see standard_domain.h); patient:
// checked tet model (see mesh_check.h) with its set. Sources name the files in error messages.
// standard_parameterization: the standard's parameterization on `domain` made beforehand (a cache,
// core/io/parameterization_cache.h), or null to compute it here. side_conditions: see SideConditions, or null.
TransferRun run_transfer(const VolumeMesh& standard, const TetDomain& domain, const ConstraintSet& standard_constraints,
                         const std::string& standard_source, const VolumeMesh& patient,
                         const ConstraintSet& patient_constraints, const std::string& patient_source,
                         const TransferOptions& options, const ProgressCallback& progress = {},
                         const ModelParameterization* standard_parameterization = nullptr,
                         const SideConditions* side_conditions = nullptr);

// The mapping and the repair alone, on parameterizations made beforehand (run.standard on the standard's domain,
// whose first rows are the hex vertices; run.patient on the patient's tets): checks the patient's health and
// handedness against the standard's, maps the standard and repairs the result (run_transfer's second half).
void map_parameterized(TransferRun& run, const VolumeMesh& standard, const std::string& patient_source,
                       const TransferOptions& options, const ProgressCallback& progress = {});

// How far the shape relaxation and the repair moved each standard vertex from where the mapping put it (#Vs, mm).
Eigen::VectorXd moved_from_mapping(const TransferRun& run);

// The standard's (u,v,w) at its hex vertices: the first rows of its domain's parameterization (#Vs x 3).
Eigen::MatrixXd hex_vertex_uvw(const TransferRun& run, int hex_vertices);

}  // namespace facehex
