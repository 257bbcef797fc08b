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

int clear_opposite_sides(Eigen::VectorXi& side_mask) {
  int cleared = 0;
  for (Eigen::Index v = 0; v < side_mask.size(); ++v)
    for (int field = 0; field < 3; ++field) {
      const int both = side_bit(static_cast<Side>(2 * field)) | side_bit(static_cast<Side>(2 * field + 1));
      if ((side_mask(v) & both) == both) {
        side_mask(v) &= ~both;
        ++cleared;
      }
    }
  return cleared;
}

}  // namespace facehex
