#pragma once
// A synthetic "bent thin cuboid": the face-like shell segment between two coaxial elliptic cylinders, used as a
// phantom patient in tests and benchmarks. In the FaceHex frame (+x lateral, +y anterior, +z superior):
//   x = a(r) sin(t), y = b(r) cos(t), z,  with t in [-t_max, t_max], z in [z_min, z_max], r in [0, 1] from the
//   inner (w0) to the outer (w1) surface; t = -t_max is the u0 end, t = t_max the u1 end, z_min v0, z_max v1.
// A Gaussian bump on the outer surface at t = 0 plays the nose.
#include "core/mesh/mesh.h"

namespace facehex {

struct SyntheticShellOptions {
  double inner_a = 60, inner_b = 70;         // mm, semi-axes of the inner surface (x, y)
  double thickness = 12;                     // mm
  double t_max = 1.9;                        // rad, half the angular extent
  double z_min = -120, z_max = 0;            // mm
  double nose_height = 15, nose_width = 12;  // mm
  double edge_length = 4;                    // mm, triangle size of the surface
};

// A closed, outward-oriented triangle surface with SurfaceMesh::labels = side + 1 (Side of sides.h).
SurfaceMesh synthetic_shell_surface(const SyntheticShellOptions& options = {});

}  // namespace facehex
