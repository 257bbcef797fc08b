#include "core/segment/palate_pitch.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

namespace facehex {
namespace {

constexpr double kPlateBone = 0.4;    // bone fraction of the plate (within 1 mm of the line)
constexpr double kBelowBone = 0.10;   // mean bone fraction 4-15 mm below it (the tongue)
constexpr double kAboveBone = 0.30;   // mean bone fraction 4-8 mm above it (the nasal floor)
constexpr double kInside = 0.97;      // mean "inside" 1-20 mm above and below it
constexpr int kMaxGap = 4;            // mm of a run without palate that still joins its two parts
constexpr double kFrontReach = 45.0;  // mm: the run ends at most this far behind the face's front
constexpr double kAngleRange = 50.0;  // degrees either way, searched every kAngleStep
constexpr double kAngleStep = 2.0;

// A map over the sagittal plane: rows of z, columns of y, at the grid's spacing.
struct SagittalMap {
  int nz = 0, ny = 0;
  double spacing = 1;
  std::vector<float> value;
  float at(int k, int j) const { return value[static_cast<size_t>(k) * ny + j]; }
  // Bilinear at (z, y) mm from the grid's first voxel; 0 outside.
  double sample(double z, double y) const {
    const double fk = z / spacing, fj = y / spacing;
    const int k = static_cast<int>(std::floor(fk)), j = static_cast<int>(std::floor(fj));
    if (k < 0 || j < 0 || k >= nz - 1 || j >= ny - 1) return 0;
    const double tz = fk - k, ty = fj - j;
    return (1 - tz) * ((1 - ty) * at(k, j) + ty * at(k, j + 1)) +
           tz * ((1 - ty) * at(k + 1, j) + ty * at(k + 1, j + 1));
  }
};

struct Run {
  int length = 0, first = 0, last = 0;
};

// The longest run of true cells, joined over gaps of at most kMaxGap cells.
Run longest_run(const std::vector<char>& cells) {
  Run best, current;
  int previous = -1;
  for (int s = 0; s < static_cast<int>(cells.size()); ++s) {
    if (!cells[static_cast<size_t>(s)]) continue;
    if (previous < 0 || s - previous > kMaxGap + 1) current.first = s;
    current.last = s;
    current.length = s - current.first + 1;
    if (current.length > best.length) best = current;
    previous = s;
  }
  return best;
}

}  // namespace

std::optional<double> palate_pitch(const Mask& head, const Mask& bone, double centre_x) {
  const GridGeometry& g = head.geometry;
  const double h = g.spacing.x();
  std::vector<int> band;
  for (int i = 0; i < g.dims[0]; ++i) {
    const double d = std::abs(g.point(i, 0, 0).x() - centre_x);
    if (d >= kBandInner && d <= kBandOuter) band.push_back(i);
  }
  if (band.empty()) return std::nullopt;
  SagittalMap bone_fraction{g.dims[2], g.dims[1], h, {}}, inside = bone_fraction;
  bone_fraction.value.assign(static_cast<size_t>(g.dims[2]) * g.dims[1], 0.0f);
  inside.value = bone_fraction.value;
  for (int k = 0; k < g.dims[2]; ++k) {
    int first = -1, last = -1;
    for (int j = 0; j < g.dims[1]; ++j) {
      int in_bone = 0, in_head = 0;
      for (const int i : band) in_bone += bone(i, j, k), in_head += head(i, j, k);
      bone_fraction.value[static_cast<size_t>(k) * g.dims[1] + j] = static_cast<float>(in_bone) / band.size();
      if (2 * in_head > static_cast<int>(band.size())) {
        if (first < 0) first = j;
        last = j;
      }
    }
    for (int j = first; first >= 0 && j <= last; ++j) inside.value[static_cast<size_t>(k) * g.dims[1] + j] = 1.0f;
  }

  // Lines of the rotated frame: row r (mm above the map's centre, across the line) and position s along it (mm
  // towards the front), turned by t: z = cz + s sin t + r cos t, y = cy + s cos t - r sin t.
  const double cz = 0.5 * g.dims[2] * h, cy = 0.5 * g.dims[1] * h;
  const int R = static_cast<int>(std::ceil(0.5 * std::hypot(g.dims[2] * h, g.dims[1] * h)));
  const int n = 2 * R + 1;
  struct Best {
    int length = 0, r = 0;
    double degrees = 0;
    Run run;
  } best;
  std::vector<double> f(static_cast<size_t>(n) * n), in(f.size()), f_sum((static_cast<size_t>(n) + 1) * n),
      in_sum(f_sum.size());
  for (double degrees = -kAngleRange; degrees <= kAngleRange + 1e-9; degrees += kAngleStep) {
    const double t = degrees * M_PI / 180, c = std::cos(t), sn = std::sin(t);
    for (int r = 0; r < n; ++r)
      for (int s = 0; s < n; ++s) {
        const double rr = r - R, ss = s - R;
        const size_t at = static_cast<size_t>(r) * n + s;
        f[at] = bone_fraction.sample(cz + ss * sn + rr * c, cy + ss * c - rr * sn);
        in[at] = inside.sample(cz + ss * sn + rr * c, cy + ss * c - rr * sn);
      }
    // Column sums over rows, for the means of slabs of rows.
    for (int s = 0; s < n; ++s) f_sum[static_cast<size_t>(s)] = in_sum[static_cast<size_t>(s)] = 0;
    for (int r = 0; r < n; ++r)
      for (int s = 0; s < n; ++s) {
        const size_t next = static_cast<size_t>(r + 1) * n + s, here = static_cast<size_t>(r) * n + s;
        f_sum[next] = f_sum[here] + f[here];
        in_sum[next] = in_sum[here] + in[here];
      }
    const auto slab_mean = [&](const std::vector<double>& sum, int r, int s, int from, int to) {
      const int lo = std::clamp(r + from, 0, n), hi = std::clamp(r + to + 1, 0, n);
      return (sum[static_cast<size_t>(hi) * n + s] - sum[static_cast<size_t>(lo) * n + s]) / std::max(hi - lo, 1);
    };
    std::vector<char> palate(static_cast<size_t>(n));
    for (int r = 0; r < n; ++r) {
      int front = -1;
      for (int s = 0; s < n; ++s) {
        double plate = 0;
        for (int dr = -1; dr <= 1; ++dr)
          plate = std::max(plate, f[static_cast<size_t>(std::clamp(r + dr, 0, n - 1)) * n + s]);
        palate[static_cast<size_t>(s)] = plate >= kPlateBone && slab_mean(f_sum, r, s, -15, -4) <= kBelowBone &&
                                         slab_mean(f_sum, r, s, 4, 8) <= kAboveBone &&
                                         slab_mean(in_sum, r, s, 1, 20) >= kInside &&
                                         slab_mean(in_sum, r, s, -20, -1) >= kInside;
        if (in[static_cast<size_t>(r) * n + s] > 0.5) front = s;
      }
      const Run run = longest_run(palate);
      if (run.length > best.length && front >= 0 && front - run.last <= kFrontReach)
        best = Best{run.length, r, degrees, run};
    }
  }
  if (best.length < kMinPalateLength) return std::nullopt;

  // The plate's bone-weighted middle every millimetre along the run, and a line through them.
  const double t = best.degrees * M_PI / 180, c = std::cos(t), sn = std::sin(t);
  std::vector<Eigen::Vector3d> points;  // (s, r, weight)
  for (int s = best.run.first; s <= best.run.last; ++s) {
    const double ss = s - R;
    double weight = 0, moment = 0;
    for (double dr = -4; dr <= 4 + 1e-9; dr += 0.5) {
      const double rr = best.r - R + dr;
      const double w = bone_fraction.sample(cz + ss * sn + rr * c, cy + ss * c - rr * sn);
      weight += w, moment += w * rr;
    }
    if (weight > 0.5) points.emplace_back(ss, moment / weight, weight);
  }
  double slope = 0;
  for (int pass = 0; pass < 3 && points.size() >= 2; ++pass) {
    Eigen::MatrixXd A(points.size(), 2);
    Eigen::VectorXd b(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const double w = std::sqrt(points[i].z());
      A.row(static_cast<Eigen::Index>(i)) << w * points[i].x(), w;
      b(static_cast<Eigen::Index>(i)) = w * points[i].y();
    }
    const Eigen::Vector2d line = A.colPivHouseholderQr().solve(b);
    slope = line(0);
    std::vector<double> residual;
    for (const Eigen::Vector3d& p : points) residual.push_back(std::abs(p.y() - line(0) * p.x() - line(1)));
    std::vector<double> sorted = residual;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    const double bound = std::max(1.0, 2.5 * sorted[sorted.size() / 2]);
    std::vector<Eigen::Vector3d> kept;
    for (size_t i = 0; i < points.size(); ++i)
      if (residual[i] < bound) kept.push_back(points[i]);
    points = std::move(kept);
  }
  return best.degrees + std::atan(slope) * 180 / M_PI;
}

}  // namespace facehex
