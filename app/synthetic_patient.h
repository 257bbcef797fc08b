#pragma once
// A synthetic face-like shell patient (core/synthetic_shell.h) tetrahedralized by TetGen with its six sides labelled:
// the patient of the benchmarks and of the end-to-end test on a known shape.
#include "core/mesh/mesh.h"

namespace facehex::cli {

VolumeMesh synthetic_shell_patient(double edge_length);

}  // namespace facehex::cli
