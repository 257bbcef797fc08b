#pragma once
// A standard's constraint set made by the rules a patient's is (core/face/automatic_constraints.h): its six sides
// and the feature constraints at its landmarks, in slabs as wide as a patient's, valued by its own side-only fields
// (own_feature_values.h). The landmarks are found as on a patient from a CT: on the standard's skin with its openings
// closed (closed_domain.h), resampled to near-equilateral triangles of a patient's edge length (remesh.h), so that a
// patient's automatic constraints select the same anatomy with the same values, band and sampling.
#include <string>

#include "core/face/automatic_constraints.h"
#include "core/fields/constraint_set.h"
#include "core/mesh/mesh.h"

namespace facehex {

// standard: hex-dominant with side labels; skin_edge_length: mm, a patient surface's (SegmentOptions). Throws
// facehex::Error naming `source` when a landmark is not found or a feature selects no vertex.
ConstraintSet own_automatic_constraints(const VolumeMesh& standard, const std::string& source, double band,
                                        double skin_edge_length);

}  // namespace facehex
