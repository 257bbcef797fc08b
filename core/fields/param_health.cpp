#include "core/fields/param_health.h"

#include <Eigen/Geometry>
#include <cmath>

namespace facehex {

ParamHealth parameterization_health(const Eigen::MatrixXi& T, const Eigen::MatrixXd& uvw,
                                    const Eigen::MatrixXi& fixed) {
  ParamHealth h;
  h.tets = static_cast<int>(T.rows());
  Eigen::VectorXd vol(T.rows());
  for (int t = 0; t < T.rows(); ++t) {
    const Eigen::Vector3d p0 = uvw.row(T(t, 0)).transpose(), p1 = uvw.row(T(t, 1)).transpose(),
                          p2 = uvw.row(T(t, 2)).transpose(), p3 = uvw.row(T(t, 3)).transpose();
    vol(t) = (p1 - p0).dot((p2 - p0).cross(p3 - p0)) / 6.0;
  }
  const double tiny = 1e-12 * vol.cwiseAbs().mean();
  const long positive = (vol.array() > tiny).count(), negative = (vol.array() < -tiny).count();
  h.orientation = positive >= negative ? 1 : -1;
  for (int t = 0; t < T.rows(); ++t) {
    if (std::abs(vol(t)) <= tiny) {
      ++h.degenerate;
      bool by_constraint = false;
      for (int f = 0; f < 3 && fixed.size() > 0 && !by_constraint; ++f) {
        bool all_fixed_equal = true;
        for (int i = 0; i < 4; ++i)
          all_fixed_equal = all_fixed_equal && fixed(T(t, i), f) != 0 && uvw(T(t, i), f) == uvw(T(t, 0), f);
        by_constraint = all_fixed_equal;
      }
      h.flat_by_constraint += by_constraint;
      if (!by_constraint) h.folded_tets.push_back(t);
    } else if (vol(t) * h.orientation < 0) {
      ++h.inverted;
      if (h.inverted_tets.size() < 100) h.inverted_tets.push_back(t);
      h.folded_tets.push_back(t);
    }
  }
  for (Eigen::Index v = 0; v < uvw.rows(); ++v)
    h.outside_cube += (uvw.row(v).array() < -1e-9).any() || (uvw.row(v).array() > 1 + 1e-9).any();
  return h;
}

}  // namespace facehex
