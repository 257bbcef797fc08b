#pragma once
// Orthogonality improvement of three per-tet gradient fields (paper 3.3).
//
// Gradients are #T x 3 matrices, one constant gradient per tet, in the order u, v, w. Per tet, the "basic" field's
// gradient is kept, the "second" one is projected onto the plane normal to it keeping its norm, and the "third"
// one is replaced by the cross product of the two, scaled to its own norm and signed to keep its orientation
// (positive dot product with the original third gradient). The result is a perfectly orthogonal frame per tet,
// which in general is not a gradient field: the harmonic solver recovers the closest fields (eq. 5-6).
#include <Eigen/Core>
#include <array>
#include <vector>

namespace facehex {

using GradientFields = std::array<Eigen::MatrixXd, 3>;  // u, v, w: each #T x 3

// order = {basic, second, third}, a permutation of {0, 1, 2}.
GradientFields orthogonal_targets(const GradientFields& gradients, const std::array<int, 3>& order);

// Angles between the gradient pairs (u,v), (v,w), (u,w) per tet, in degrees (#T x 3). Tets where a gradient
// vanishes get NaN and are left out of the statistics.
Eigen::MatrixXd gradient_angles(const GradientFields& gradients);

// The paper's Fig. 6: how close the fields are to mutually orthogonal.
struct AngleStatistics {
  static constexpr double kBinWidth = 10.0;  // degrees; bins [0,10), [10,20), ... [170,180]
  std::vector<long> histogram;               // 18 bins over all three pairs of all tets
  double mean_deviation_from_90 = 0;         // degrees
  double fraction_within_10_of_90 = 0;       // in [0, 1]
  long angles = 0;
};
AngleStatistics angle_statistics(const Eigen::MatrixXd& angles);

}  // namespace facehex
