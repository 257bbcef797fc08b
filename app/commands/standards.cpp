#include <iostream>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "core/fields/parameterization.h"
#include "core/io/mesh_io.h"
#include "core/standard/closed_domain.h"
#include "core/standard/parameterization_cache.h"
#include "core/util/resources.h"

namespace facehex::cli {

int cmd_standards(const Argv& argv) {
  Args args("standards",
            "Lists the bundled standard hex meshes (use a name with --standard). With --write-cache, computes each "
            "one's parameterization (closed domain, default field options) and keeps it beside it as "
            "standard.param.vtu + .json, which transfers then read instead of computing it.");
  args.flag("write-cache", "write the parameterization cache of every bundled standard");
  if (!args.parse(argv)) return 0;
  for (const auto& s : bundled_standards()) {
    std::cout << s.name << "\t" << s.description << "\n\t" << s.mesh << "\n";
    if (!args.has("write-cache")) continue;
    const VolumeMesh mesh = read_volume_mesh(s.mesh);
    const ConstraintSet set = read_constraint_set(s.constraints);
    const TetDomain domain = closed_domain(mesh);
    const HarmonicFieldsOptions options;
    const ModelParameterization p =
        parameterize_model(domain.V, domain.T, domain.side_mask, set, s.constraints, options);
    const std::string cache = parameterization_cache_path(s.mesh);
    write_parameterization_cache(cache, domain, p, set, options);
    std::cout << "\twrote " << cache << " (" << p.T.rows() << " tets, " << p.health.inverted
              << " folded in parameter space)\n";
  }
  return 0;
}

}  // namespace facehex::cli
