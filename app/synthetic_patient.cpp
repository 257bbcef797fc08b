#include "app/synthetic_patient.h"

#include "core/mesh/synthetic_shell.h"
#include "core/tetgen/tetrahedralize.h"

namespace facehex::cli {

VolumeMesh synthetic_shell_patient(double edge_length) {
  SyntheticShellOptions shell;
  shell.edge_length = edge_length;
  TetrahedralizeOptions options;
  options.target_edge_length = edge_length;
  return tetrahedralize_with_sides(synthetic_shell_surface(shell), options).mesh;
}

}  // namespace facehex::cli
