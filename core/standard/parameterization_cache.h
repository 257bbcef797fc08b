#pragma once
// A standard's parameterization computed once and kept beside its mesh (paper 3.4: "the calculations for the
// standard model need to be done only once"):
//   STANDARD.param.vtu   the parameterization domain's tets (standard_domain.h) with point data uvw, uvw_initial
//                        (#V x 3 each) and side_mask;
//   STANDARD.param.json  {"format": "facehex-parameterization-cache", "version": 1, "fingerprint": ..., ...}.
// The fingerprint hashes everything the fields depend on: the domain (vertices, tets, side labels, so the standard
// mesh and the way its domain was built), the constraint set and the field options. A cache whose fingerprint
// differs, or that cannot be read, is not used: the caller recomputes and says so (never a silent wrong result).
#include <optional>
#include <string>

#include "core/fields/constraint_set.h"
#include "core/fields/harmonic_fields.h"
#include "core/fields/parameterization.h"
#include "core/fields/tet_domain.h"

namespace facehex {

// STANDARD.vtu -> STANDARD.param.vtu (any extension of the standard is replaced).
std::string parameterization_cache_path(const std::string& standard_mesh);

// 16 hex digits (64-bit FNV-1a) over the domain, the set (as JSON) and the options.
std::string parameterization_fingerprint(const TetDomain& domain, const ConstraintSet& set,
                                         const HarmonicFieldsOptions& options);

// Writes both files (atomically each). p: parameterize_model(domain.V, domain.T, domain.side_mask, set, ...).
void write_parameterization_cache(const std::string& path, const TetDomain& domain, const ModelParameterization& p,
                                  const ConstraintSet& set, const HarmonicFieldsOptions& options);

// The cached parameterization, rebuilt as parameterize_model returns it (constraints resolved, gradients, angles and
// health recomputed from the cached fields), or nullopt with the reason in *why_not: empty when there is no cache,
// else a sentence naming the file (unreadable, or made from another domain, constraint set or options).
std::optional<ModelParameterization> read_parameterization_cache(const std::string& path, const TetDomain& domain,
                                                                 const ConstraintSet& set,
                                                                 const HarmonicFieldsOptions& options,
                                                                 std::string* why_not = nullptr);

}  // namespace facehex
