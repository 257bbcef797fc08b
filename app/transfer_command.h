#pragma once
// The harmonic transfer as the `run` and `map` commands do it (app/commands.cpp), shared with `compare`: the standard
// and its constraint set, the patient (a CT is segmented first) with its constraint set or automatic constraints
// (six sides + features at its landmarks), the transfer, and the quality of the result.
#include <optional>
#include <string>

#include "app/cli_args.h"
#include "app/report.h"
#include "core/fields/tet_domain.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/mesh.h"
#include "core/quality/surface_distance.h"
#include "core/segment/soft_tissue.h"

namespace facehex::cli {

struct TransferOutputs {
  VolumeMesh standard, patient;
  TransferRun run;
  MeshQualityReport standard_quality, plain_mapping_quality, patient_quality;  // plain: before relaxation, repair
  DistanceSummary distance;
};

// The standard's parameterization from its cache file (core/io/parameterization_cache.h), or nullopt; a cache that
// exists but does not fit is reported on stderr (it is then recomputed).
std::optional<ModelParameterization> cached_standard_parameterization(const std::string& cache, const TetDomain& domain,
                                                                      const ConstraintSet& set,
                                                                      const HarmonicFieldsOptions& options);

// The options execute_transfer reads: --standard, --standard-constraints, --standard-domain, the field and the
// segmentation options.
void add_transfer_options(Args& args);

// The field options of add_transfer_options (--iterations, --order).
HarmonicFieldsOptions field_options(const Args& args);

// The tet domain a hex standard is parameterized on (--standard-domain): "closed" (openings filled) or "auxiliary"
// (the paper's: its cells split into tets).
TetDomain standard_domain(const VolumeMesh& hex, const std::string& kind);

// The segmentation options of add_transfer_options (--edge-length, --skin, --bone, --anterior, --superior, the cut
// planes and their automatic distances). Throws facehex::Error naming the option for a non-finite cut, a negative
// distance or a zero face height.
SegmentOptions segment_options(const Args& args);

// The patient model of a CT (segmented, its steps shown on the terminal), tet mesh or closed surface
// (core/segment/patient_input.h), with notes on stderr.
VolumeMesh load_tet_model(const std::string& path, const SegmentOptions& options);

// patient_constraints: a constraint-set file, or empty for the automatic constraints.
TransferOutputs execute_transfer(const Args& args, const std::string& patient, const std::string& patient_constraints);

}  // namespace facehex::cli
