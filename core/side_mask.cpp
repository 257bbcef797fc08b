#include "core/side_mask.h"

#include "core/sides.h"

namespace facehex {

Eigen::VectorXi side_mask_from_faces(int num_vertices, const Eigen::MatrixXi& F, const Eigen::VectorXi& side) {
  Eigen::VectorXi mask = Eigen::VectorXi::Zero(num_vertices);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (side(f) < 0) continue;
    for (Eigen::Index k = 0; k < F.cols(); ++k)
      if (F(f, k) >= 0) mask(F(f, k)) |= side_bit(static_cast<Side>(side(f)));
  }
  return mask;
}

}  // namespace facehex
