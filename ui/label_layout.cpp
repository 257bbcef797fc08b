#include "ui/label_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace facehex::gui {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Directions tried around a marker, in degrees from the outward side (0: straight out, 180: towards the centre):
// level first (a name reads best beside its marker), then leaning up or down, then above and below, then inwards.
constexpr double kDirections[] = {0, 30, -30, 60, -60, 90, -90, 150, -150, 120, -120, 180};

double overlap_1d(double a0, double a1, double b0, double b1) {
  return std::max(0.0, std::min(a1, b1) - std::max(a0, b0));
}

}  // namespace

double box_overlap(const Eigen::Vector2d& corner_a, const Eigen::Vector2d& size_a, const Eigen::Vector2d& corner_b,
                   const Eigen::Vector2d& size_b) {
  return overlap_1d(corner_a.x(), corner_a.x() + size_a.x(), corner_b.x(), corner_b.x() + size_b.x()) *
         overlap_1d(corner_a.y(), corner_a.y() + size_a.y(), corner_b.y(), corner_b.y() + size_b.y());
}

Eigen::MatrixX2d place_labels(const Eigen::MatrixX2d& anchors, const Eigen::MatrixX2d& sizes,
                              const LabelLayoutOptions& options) {
  const Eigen::Index n = anchors.rows();
  Eigen::MatrixX2d corners(n, 2);
  if (n == 0) return corners;
  const Eigen::RowVector2d centre = anchors.colwise().mean();
  // Outermost first; equal distances in the order of their positions, so that the input's order does not matter.
  std::vector<Eigen::Index> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
    const double da = (anchors.row(a) - centre).squaredNorm(), db = (anchors.row(b) - centre).squaredNorm();
    if (da != db) return da > db;
    if (anchors(a, 0) != anchors(b, 0)) return anchors(a, 0) < anchors(b, 0);
    if (anchors(a, 1) != anchors(b, 1)) return anchors(a, 1) < anchors(b, 1);
    return a < b;
  });
  // A marker's disc, as the square around it, is kept clear like a placed name.
  const Eigen::Vector2d marker_size = Eigen::Vector2d::Constant(2 * options.marker_radius);
  std::vector<Eigen::Index> placed;
  for (const Eigen::Index i : order) {
    const Eigen::Vector2d a = anchors.row(i).transpose(), size = sizes.row(i).transpose();
    const double outward = anchors(i, 0) >= centre.x() ? 0.0 : 180.0;
    const auto cost = [&](const Eigen::Vector2d& corner) {
      double c = 0;
      const Eigen::Vector2d spaced_corner = corner.array() - options.spacing,
                            spaced_size = size.array() + 2 * options.spacing;
      for (const Eigen::Index j : placed)
        c += box_overlap(spaced_corner, spaced_size, corners.row(j).transpose(), sizes.row(j).transpose());
      for (Eigen::Index j = 0; j < n; ++j)
        if (j != i) c += box_overlap(corner, size, anchors.row(j).transpose() - marker_size / 2, marker_size);
      if (options.viewport.x() > 0 && options.viewport.y() > 0)
        c += size.prod() - box_overlap(corner, size, Eigen::Vector2d::Zero(), options.viewport);
      return c;
    };
    double best_cost = std::numeric_limits<double>::infinity();
    Eigen::Vector2d best = a;
    for (int ring = 0; ring < std::max(1, options.rings) && best_cost > 0; ++ring) {
      const double d = options.marker_radius + options.gap + ring * size.y();
      for (const double degrees : kDirections) {
        const double angle = (outward + degrees) * kPi / 180;
        const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
        // The box's side (or corner) nearest the marker lies d from it along dir.
        const auto side = [](double c) { return std::abs(c) < 1e-9 ? 0.0 : (c > 0 ? 1.0 : -1.0); };
        const Eigen::Vector2d centre_of_box =
            a + d * dir + Eigen::Vector2d(side(dir.x()) * size.x() / 2, side(dir.y()) * size.y() / 2);
        const Eigen::Vector2d corner = centre_of_box - size / 2;
        const double c = cost(corner);
        if (c < best_cost) {
          best_cost = c;
          best = corner;
          if (c == 0) break;
        }
      }
    }
    corners.row(i) = best.transpose();
    placed.push_back(i);
  }
  return corners;
}

}  // namespace facehex::gui
