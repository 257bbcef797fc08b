#pragma once
// Health of a parameterization: is the map from the tet model to the unit cube locally injective?
// A tet's parametric image is the tet with corners uvw(T(t, i)). Its signed volume must have the same sign for all
// tets (the common sign is +1 or -1 depending on the handedness of the model frame against (u, v, w)).
#include <Eigen/Core>
#include <vector>

namespace facehex {

struct ParamHealth {
  int tets = 0;
  int orientation = 0;             // +1 or -1: the sign of the majority of the parametric volumes
  int inverted = 0;                // parametric volume of the opposite sign
  int degenerate = 0;              // |parametric volume| below 1e-12 of the mean (all corners on one plane/line)
  int flat_by_constraint = 0;      // degenerate because all four corners are pinned to one value of a field
  int outside_cube = 0;            // vertices with a coordinate outside [0, 1] by more than 1e-9
  std::vector<int> inverted_tets;  // ids of the first inverted tets (at most 100)
  std::vector<int> folded_tets;    // ids of every inverted tet and every degenerate one not flat by a constraint
  bool ok() const { return inverted == 0 && degenerate == flat_by_constraint; }
};

// T is #T x 4, uvw #V x 3. fixed (#V x 3, or empty) marks
// Dirichlet vertices per field (nonzero = fixed), to tell constraint-made flat tets from accidental ones.
ParamHealth parameterization_health(const Eigen::MatrixXi& T, const Eigen::MatrixXd& uvw,
                                    const Eigen::MatrixXi& fixed = Eigen::MatrixXi());

}  // namespace facehex
