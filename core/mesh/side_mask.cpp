#include "core/mesh/side_mask.h"

#include <bitset>
#include <limits>

#include "core/mesh/cell_faces.h"
#include "core/mesh/sides.h"

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

int relax_corner_quads(const VolumeMesh& mesh, Eigen::VectorXi& side_mask) {
  // Decided on the labels as given, then applied, so the result does not depend on the order of the cells.
  Eigen::VectorXi drop = Eigen::VectorXi::Zero(side_mask.size());
  for (int c = 0; c < mesh.num_cells(); ++c)
    for (int f = 0; f < static_cast<int>(cell_faces(mesh.types[c]).size()); ++f) {
      const std::vector<int> q = face_vertices(mesh, c, f);
      if (q.size() != 4) continue;
      const int common = side_mask(q[0]) & side_mask(q[1]) & side_mask(q[2]) & side_mask(q[3]);
      for (int k = 0; k < 4; ++k) {
        const int shared = side_mask(q[(k + 3) % 4]) & side_mask(q[k]) & side_mask(q[(k + 1) % 4]);
        if (std::bitset<kNumSides>(shared).count() >= 2) drop(q[k]) |= shared & ~common;
      }
    }
  int relaxed = 0;
  for (Eigen::Index v = 0; v < side_mask.size(); ++v) {
    relaxed += (side_mask(v) & drop(v)) != 0;
    side_mask(v) &= ~drop(v);
  }
  return relaxed;
}

int closest_skin_vertex(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask, const Eigen::Vector3d& point) {
  int best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (Eigen::Index v = 0; v < side_mask.size(); ++v) {
    if (!(side_mask(v) & side_bit(W1))) continue;
    const double d2 = (V.row(v).transpose() - point).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = static_cast<int>(v);
  }
  return best;
}

}  // namespace facehex
