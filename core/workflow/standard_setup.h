#pragma once
// The standard as both front ends take it: a bundled standard by name or a hex-dominant mesh file, its constraint
// set, the tet domain it is parameterized on, and its parameterization from the cache kept beside it when that
// cache fits (paper 3.4: the standard's side is computed once).
#include <optional>
#include <string>

#include "core/fields/constraint_set.h"
#include "core/fields/parameterization.h"
#include "core/fields/tet_domain.h"
#include "core/mesh/mesh.h"

namespace facehex {

struct StandardSetup {
  std::string name;  // the bundled name, or the file's stem
  std::string path;  // the mesh file
  VolumeMesh mesh;   // hex-dominant, point data "side_mask"
  ConstraintSet constraints;
  std::string constraints_path;  // the file the constraints came from
  TetDomain domain;              // standard_domain(mesh, kind)

  // What error messages about this standard name: its constraint file.
  std::string source() const { return constraints_path; }
};

// The tet domain a hex standard is parameterized on: "closed" (its openings filled, core/standard/closed_domain.h)
// or "auxiliary" (the paper's: its cells split into tets). Throws facehex::Error("--standard-domain", ...) otherwise.
TetDomain standard_domain(const VolumeMesh& hex, const std::string& kind);
// Throws the same facehex::Error as standard_domain for a kind it does not know, without building a domain.
void check_standard_domain_kind(const std::string& kind);

// constraints_file: the standard's constraint set made by the rules of a patient's (core/standard/own_constraints.h).
constexpr const char* kOwnAutomaticConstraints = "automatic";

// A bundled standard by name or a mesh file (core/util/resources.h find_standard), with `constraints_file` (a file,
// or kOwnAutomaticConstraints) or else the constraint set bundled with it, on the `domain_kind` domain. Throws
// facehex::Error naming the file when the mesh is no hex-dominant mesh with side labels or a file cannot be read.
StandardSetup load_standard(const std::string& name_or_path, const std::string& constraints_file = "",
                            const std::string& domain_kind = "closed");

// The parameterization cached beside a model's mesh file (core/standard/parameterization_cache.h; the bundled
// standards have one) when it was made from this domain, constraint set and options; else nullopt, and *note (when
// given) says why when a cache exists but does not fit (it is then computed instead).
std::optional<ModelParameterization> cached_parameterization(const std::string& mesh_path, const TetDomain& domain,
                                                             const ConstraintSet& constraints,
                                                             const HarmonicFieldsOptions& options,
                                                             std::string* note = nullptr);

}  // namespace facehex
