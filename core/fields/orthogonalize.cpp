#include "core/fields/orthogonalize.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace facehex {

GradientFields orthogonal_targets(const GradientFields& gradients, const std::array<int, 3>& order) {
  // Plain variables, not a structured binding: OpenMP regions cannot capture bindings before C++20 (clang refuses).
  const int b = order[0], s = order[1], t = order[2];
  GradientFields out = gradients;
  const Eigen::Index n = gradients[0].rows();
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d gb = gradients[b].row(i), gs = gradients[s].row(i), gt = gradients[t].row(i);
    const double nb = gb.norm();
    if (nb == 0) continue;  // no direction to keep: leave this tet's targets as they are
    const Eigen::Vector3d eb = gb / nb;
    Eigen::Vector3d ps = gs - gs.dot(eb) * eb;
    const double nps = ps.norm();
    if (nps == 0) continue;  // second gradient parallel to the basic one: no plane to project into
    ps *= gs.norm() / nps;
    Eigen::Vector3d ct = eb.cross(ps / ps.norm());
    if (ct.dot(gt) < 0) ct = -ct;
    out[s].row(i) = ps.transpose();
    out[t].row(i) = (gt.norm() * ct).transpose();
  }
  return out;
}

Eigen::MatrixXd gradient_angles(const GradientFields& g) {
  const Eigen::Index n = g[0].rows();
  Eigen::MatrixXd angles(n, 3);
  constexpr int pairs[3][2] = {{0, 1}, {1, 2}, {0, 2}};
  for (Eigen::Index i = 0; i < n; ++i)
    for (int p = 0; p < 3; ++p) {
      const Eigen::Vector3d a = g[pairs[p][0]].row(i), b = g[pairs[p][1]].row(i);
      const double na = a.norm(), nb = b.norm();
      angles(i, p) =
          (na == 0 || nb == 0) ? std::nan("") : std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0)) * 180.0 / M_PI;
    }
  return angles;
}

AngleStatistics angle_statistics(const Eigen::MatrixXd& angles) {
  AngleStatistics s;
  s.histogram.assign(18, 0);
  double deviation = 0;
  long within = 0;
  for (Eigen::Index i = 0; i < angles.size(); ++i) {
    const double a = angles(i);
    if (std::isnan(a)) continue;
    ++s.histogram[std::min(17, static_cast<int>(a / AngleStatistics::kBinWidth))];
    deviation += std::abs(a - 90.0);
    within += std::abs(a - 90.0) <= 10.0;
    ++s.angles;
  }
  if (s.angles > 0) {
    s.mean_deviation_from_90 = deviation / static_cast<double>(s.angles);
    s.fraction_within_10_of_90 = static_cast<double>(within) / static_cast<double>(s.angles);
  }
  return s;
}

}  // namespace facehex
