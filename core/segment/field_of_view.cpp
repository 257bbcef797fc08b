#include "core/segment/field_of_view.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <set>

namespace facehex {
namespace {

constexpr double kDiscTolerance = 2;      // voxels: border columns this close to the fitted circle lie on it
constexpr double kDiscInliers = 0.9;      // share of the border columns that must lie on the circle
constexpr double kDiscArcDegrees = 90;    // the border columns on the circle span at least this much of it
constexpr int kDiscRefits = 3;            // refits to the columns near the circle
constexpr double kFrontFacingDisc = 0.5;  // cos 60 degrees: a disc edge facing closer to the front is the face's
constexpr int kMinDiscBorderColumns = 20;

// A head-frame point in the model's frame (the CT's, where the box and the disc are).
Eigen::Vector3d model_point(const ScanSides& scan, const Eigen::Vector3d& head_point) {
  return scan.turn.turned() ? scan.turn.to_model(head_point) : head_point;
}

bool beyond_box(const ScanSides& scan, const Eigen::Vector2d& p) {
  return p.x() < scan.lo.x() || p.x() > scan.hi.x() || p.y() < scan.lo.y() || p.y() > scan.hi.y();
}

bool beyond_disc(const ScanSides& scan, const Eigen::Vector2d& p) {
  return scan.disc && (p - scan.disc->centre).norm() > scan.disc->radius;
}

// The least-squares (algebraic) circle through the points: centre and radius.
std::optional<ReconstructionDisc> fit_circle(const std::vector<Eigen::Vector2d>& points) {
  if (points.size() < 3) return std::nullopt;
  Eigen::MatrixXd A(points.size(), 3);
  Eigen::VectorXd b(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    A.row(i) << 2 * points[i].x(), 2 * points[i].y(), 1;
    b(i) = points[i].squaredNorm();
  }
  const Eigen::Vector3d x = A.colPivHouseholderQr().solve(b);
  const double r2 = x(2) + x.head<2>().squaredNorm();
  if (!(r2 > 0) || !x.allFinite()) return std::nullopt;
  return ReconstructionDisc{x.head<2>(), std::sqrt(r2)};
}

}  // namespace

std::optional<ReconstructionDisc> find_reconstruction_disc(const Field& intensity) {
  const GridGeometry& g = intensity.geometry;
  if (intensity.data.empty()) return std::nullopt;
  const float lowest = *std::min_element(intensity.data.begin(), intensity.data.end());
  const int nx = g.dims[0], ny = g.dims[1];
  const size_t slice = static_cast<size_t>(nx) * ny;
  std::vector<char> filled(slice, 1);
  for (size_t start = 0; start < intensity.data.size(); start += slice)
    for (size_t column = 0; column < slice; ++column) filled[column] &= intensity.data[start + column] == lowest;
  // The columns that hold the scan beside a filled one.
  std::vector<Eigen::Vector2d> border;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (filled[i + static_cast<size_t>(nx) * j]) continue;
      bool beside = false;
      for (const auto& [di, dj] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
        const int ni = i + di, nj = j + dj;
        beside |= ni >= 0 && nj >= 0 && ni < nx && nj < ny && filled[ni + static_cast<size_t>(nx) * nj];
      }
      if (beside) border.push_back(g.point(i, j, 0).head<2>());
    }
  if (static_cast<int>(border.size()) < kMinDiscBorderColumns) return std::nullopt;
  const double tolerance = kDiscTolerance * std::max(g.spacing.x(), g.spacing.y());
  std::optional<ReconstructionDisc> disc = fit_circle(border);
  std::vector<Eigen::Vector2d> on_circle;
  for (int refit = 0; refit <= kDiscRefits && disc; ++refit) {
    on_circle.clear();
    for (const Eigen::Vector2d& p : border)
      if (std::abs((p - disc->centre).norm() - disc->radius) <= tolerance) on_circle.push_back(p);
    if (refit < kDiscRefits) disc = fit_circle(on_circle);
  }
  if (!disc || on_circle.size() < kDiscInliers * border.size()) return std::nullopt;
  std::set<int> arcs;  // 10-degree arcs of the circle that hold a border column
  for (const Eigen::Vector2d& p : on_circle) {
    const Eigen::Vector2d d = p - disc->centre;
    arcs.insert(static_cast<int>(std::floor(std::atan2(d.y(), d.x()) * 180 / M_PI / 10)));
  }
  if (10.0 * arcs.size() < kDiscArcDegrees) return std::nullopt;
  return disc;
}

bool ScanSides::outside(const Eigen::Vector3d& head_point) const {
  const Eigen::Vector2d p = model_point(*this, head_point).head<2>();
  return beyond_box(*this, p) || beyond_disc(*this, p);
}

bool ScanSides::outside_disc_only(const Eigen::Vector3d& head_point) const {
  const Eigen::Vector2d p = model_point(*this, head_point).head<2>();
  return !beyond_box(*this, p) && beyond_disc(*this, p);
}

Eigen::Vector3d ScanSides::disc_normal(const Eigen::Vector3d& head_point) const {
  const Eigen::Vector3d p = model_point(*this, head_point);
  Eigen::Vector3d n(p.x() - disc->centre.x(), p.y() - disc->centre.y(), 0);
  n.normalize();
  return turn.turned() ? Eigen::Vector3d(turn.to_head(p + n) - turn.to_head(p)) : n;
}

std::vector<FieldOfViewContact> field_of_view_contacts(const Mask& body, const ScanSides& scan, double z_lo,
                                                       double z_hi) {
  const GridGeometry& g = body.geometry;
  constexpr std::array<std::array<int, 2>, 3> kSteps = {{{-1, 0}, {1, 0}, {0, -1}}};  // ScanEdge's order
  std::vector<FieldOfViewContact> contacts;
  for (int k = 0; k < g.dims[2]; ++k) {
    const double z = g.point(0, 0, k).z();
    if (z < z_lo || z > z_hi) continue;
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        if (!body(i, j, k)) continue;
        for (int e = 0; e < 3; ++e) {
          const int ni = i + kSteps[e][0], nj = j + kSteps[e][1];
          // A body neighbour lies in the scan (the CT shows tissue there); one beyond the grid or of air may not.
          if (g.contains(ni, nj, k) && body(ni, nj, k)) continue;
          const Eigen::Vector3d beyond = g.point(ni, nj, k);
          if (!scan.outside(beyond)) continue;
          const bool on_disc = scan.outside_disc_only(beyond);
          if (on_disc && scan.disc_normal(g.point(i, j, k)).y() > kFrontFacingDisc) continue;
          contacts.push_back({g.point(i, j, k), static_cast<ScanEdge>(e), on_disc});
          break;
        }
      }
  }
  return contacts;
}

std::array<bool, 6> cut_grid_faces(const Mask& body, const std::vector<FieldOfViewContact>& contacts) {
  const GridGeometry& g = body.geometry;
  std::array<bool, 6> cut = {false, false, false, false, false, false};
  for (const FieldOfViewContact& c : contacts) {
    const Eigen::Vector3d at = (c.point - g.origin).cwiseQuotient(g.spacing);
    if (c.edge == ScanEdge::MinusX && std::lround(at.x()) == 0) cut[0] = true;
    if (c.edge == ScanEdge::PlusX && std::lround(at.x()) == g.dims[0] - 1) cut[1] = true;
    if (c.edge == ScanEdge::MinusY && std::lround(at.y()) == 0) cut[2] = true;
  }
  return cut;
}

}  // namespace facehex
