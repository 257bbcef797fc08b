#include "core/workflow/standard_setup.h"

#include "core/face/automatic_constraints.h"
#include "core/io/mesh_io.h"
#include "core/segment/soft_tissue.h"
#include "core/standard/closed_domain.h"
#include "core/standard/own_constraints.h"
#include "core/standard/parameterization_cache.h"
#include "core/util/error.h"
#include "core/util/resources.h"

namespace facehex {

void check_standard_domain_kind(const std::string& kind) {
  if (kind != "closed" && kind != "auxiliary")
    throw Error("--standard-domain", "expects closed or auxiliary, got '" + kind + "'");
}

TetDomain standard_domain(const VolumeMesh& hex, const std::string& kind) {
  check_standard_domain_kind(kind);
  return kind == "closed" ? closed_domain(hex) : auxiliary_domain(hex);
}

StandardSetup load_standard(const std::string& name_or_path, const std::string& constraints_file,
                            const std::string& domain_kind) {
  const BundledModel files = find_standard(name_or_path);
  StandardSetup s;
  s.name = files.name;
  s.path = files.mesh;
  s.mesh = read_volume_mesh(files.mesh);
  if (s.mesh.count(CellType::Hex) == 0)
    throw Error(files.mesh, "has no hexahedra: a standard is a hex-dominant mesh (a tet model is a patient)");
  if (constraints_file == kOwnAutomaticConstraints) {
    s.constraints_path = files.mesh + " (automatic constraints)";
    s.constraints =
        own_automatic_constraints(s.mesh, s.constraints_path, kFeatureBand, SegmentOptions().tets.target_edge_length);
  } else {
    s.constraints_path = constraints_file.empty() ? files.constraints : constraints_file;
    s.constraints = read_constraint_set(s.constraints_path);
  }
  s.domain = standard_domain(s.mesh, domain_kind);
  return s;
}

std::optional<ModelParameterization> cached_parameterization(const std::string& mesh_path, const TetDomain& domain,
                                                             const ConstraintSet& constraints,
                                                             const HarmonicFieldsOptions& options, std::string* note) {
  std::string why_not;
  std::optional<ModelParameterization> cached =
      read_parameterization_cache(parameterization_cache_path(mesh_path), domain, constraints, options, &why_not);
  if (note) *note = why_not;
  return cached;
}

}  // namespace facehex
