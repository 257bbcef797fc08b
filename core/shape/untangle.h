#pragma once
// Untangling and local smoothing of a hex-dominant mesh (the "never an inverted element" guarantee).
//
// Energy: the corner energy of corner_energy.h summed over the corners of the cells around the moving vertices and
// the centre of each hex (with S = its Jacobian there), against the ideal cell's corners or a target mesh's
// (shape_options.h). delta is taken from the worst corner (Escobar et al.: delta^2 = eps (eps - sigma_min)) and is 0
// once nothing is inverted. A step is taken only if it makes no cell around the vertex unusable (inverted at a corner
// or an interior sample point, corner_jacobian.h, or flat), so the result is valid where solvers evaluate it.
//
// Only vertices near bad cells move (within `rings` vertex rings of a cell that is inverted or below its bound,
// cell_bounds.h); a step never makes a cell unusable (inverted or degenerate) that was not, so the rest of the mapped
// mesh keeps exactly the shape the mapping gave it. Vertices move through their parameters (vertex_placement.h): with
// the patient's inverse parameterization as placement, every vertex stays inside the patient and one whose u is
// pinned stays exactly on its side or feature surface. Each sweep visits the movable vertices and takes a Newton step
// (the exact Hessian of the vertex's energy, corner_energy.h) in the movable parameter directions with a
// backtracking line search (local Gauss-Seidel descent).
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/shape/shape_options.h"
#include "core/shape/vertex_placement.h"
#include "core/util/progress.h"

namespace facehex {

// mesh: modified in place (V only); placement.p follows the moves.
UntangleReport untangle(VolumeMesh& mesh, VertexPlacement& placement, const UntangleOptions& options = {});

}  // namespace facehex
