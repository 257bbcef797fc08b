#include "core/face/mouth_corners.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/face/millimetre_bins.h"

namespace facehex {
namespace {

constexpr double kSigma = 1.0;            // mm, the height field's Gaussian
constexpr double kColumnHalfHeight = 30;  // mm above and below the stomion sampled in each column
constexpr int kMedianHalfWindow = 12;     // samples (mm) either side of the line for the column's median slope
constexpr int kTrackReach = 2;            // samples (mm) in z the line moves between neighbouring columns
constexpr double kMaxHalfWidth = 50;      // mm from the plane: beyond the widest adult mouth's half
constexpr double kCornerContrast = 0.7;   // the line's slope above the column's median at the corner
constexpr double kFadedContrast = 0.2;    // below this the line has faded into the cheek

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The most anterior skin vertex of each 1 mm cell of (x, z), and the Gaussian-weighted depth between them.
class FrontHeightField {
 public:
  FrontHeightField(const Eigen::MatrixXd& V, const std::vector<int>& skin) {
    for (const int v : skin) {
      const std::pair<int, int> cell{millimetre_bin(V(v, 0)), millimetre_bin(V(v, 2))};
      const auto it = front_.find(cell);
      if (it == front_.end() || V(v, 1) > it->second.y()) front_[cell] = V.row(v).transpose();
    }
  }

  // The depth y at (x, z), NaN where no cell's vertex lies within 3 sigma.
  double depth(double x, double z) const {
    const int reach = static_cast<int>(std::ceil(3 * kSigma));
    const int cx = static_cast<int>(std::floor(x)), cz = static_cast<int>(std::floor(z));
    double weights = 0, sum = 0;
    for (int i = cx - reach; i <= cx + reach; ++i)
      for (int k = cz - reach; k <= cz + reach; ++k) {
        const auto it = front_.find({i, k});
        if (it == front_.end()) continue;
        const double d2 = (it->second.x() - x) * (it->second.x() - x) + (it->second.z() - z) * (it->second.z() - z);
        if (d2 > 9 * kSigma * kSigma) continue;
        const double w = std::exp(-d2 / (2 * kSigma * kSigma));
        weights += w, sum += w * it->second.y();
      }
    return weights > 1e-3 ? sum / weights : kNaN;
  }

 private:
  std::map<std::pair<int, int>, Eigen::Vector3d> front_;
};

// One column x of the height field, sampled every 1 mm in z from z0: depth and slope (central differences).
struct Column {
  double x, z0;
  std::vector<double> y, slope;

  Column(const FrontHeightField& field, double x_, double z0_, int samples) : x(x_), z0(z0_) {
    for (int j = 0; j < samples; ++j) y.push_back(field.depth(x, z0 + j));
    slope.assign(y.size(), kNaN);
    for (size_t j = 1; j + 1 < y.size(); ++j) slope[j] = 0.5 * (y[j + 1] - y[j - 1]);  // NaN where a y is
  }

  // The sample of the steepest slope in [lo, hi] whose own depth is known (a coarse mesh's height field can have a
  // hole between samples that have one), or -1 where there is none.
  int steepest(int lo, int hi) const {
    int best = -1;
    for (int j = std::max(lo, 0); j <= std::min(hi, static_cast<int>(slope.size()) - 1); ++j)
      if (!std::isnan(slope[j]) && !std::isnan(y[j]) && (best < 0 || slope[j] > slope[best])) best = j;
    return best;
  }

  // The slope at j above the median of the column's slopes within kMedianHalfWindow of it.
  double contrast(int j) const {
    std::vector<double> around;
    for (int i = std::max(j - kMedianHalfWindow, 0);
         i <= std::min(j + kMedianHalfWindow, static_cast<int>(slope.size()) - 1); ++i)
      if (!std::isnan(slope[i])) around.push_back(slope[i]);
    std::nth_element(around.begin(), around.begin() + around.size() / 2, around.end());
    return slope[j] - around[around.size() / 2];
  }
};

// The corner on one side (direction -1: towards -x), or none.
std::optional<Eigen::Vector3d> corner(const FrontHeightField& field, double x_mid, double z0, int samples, int start,
                                      int direction) {
  std::optional<Eigen::Vector3d> found;
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();  // the last column's line point and its contrast
  double previous_contrast = 0;
  int line = start;
  for (double step = 0; step <= kMaxHalfWidth; step += 1) {
    const Column column(field, x_mid + direction * step, z0, samples);
    line = column.steepest(line - kTrackReach, line + kTrackReach);
    if (line < 0) break;  // the height field ends
    const double contrast = column.contrast(line);
    const Eigen::Vector3d at(column.x, column.y[line], z0 + line);
    if (contrast >= kCornerContrast)
      found = at;
    else if (previous_contrast >= kCornerContrast)
      found = previous + (previous_contrast - kCornerContrast) / (previous_contrast - contrast) * (at - previous);
    if (contrast < kFadedContrast) break;
    previous = at;
    previous_contrast = contrast;
  }
  return found;
}

}  // namespace

std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> mouth_corners(const Eigen::MatrixXd& V,
                                                                         const std::vector<int>& skin, double x_mid,
                                                                         const Eigen::Vector3d& stomion,
                                                                         const Eigen::Vector3d& labrale_superius) {
  const FrontHeightField field(V, skin);
  const double z0 = stomion.z() - kColumnHalfHeight;
  const int samples = static_cast<int>(2 * kColumnHalfHeight) + 1;
  const Column middle(field, x_mid, z0, samples);
  const int start = middle.steepest(static_cast<int>(std::ceil(stomion.z() - z0)),
                                    static_cast<int>(std::floor(labrale_superius.z() - z0)));
  if (start < 0) return std::nullopt;
  const std::optional<Eigen::Vector3d> right = corner(field, x_mid, z0, samples, start, -1);
  const std::optional<Eigen::Vector3d> left = corner(field, x_mid, z0, samples, start, +1);
  if (!right || !left) return std::nullopt;
  return std::pair{*right, *left};
}

}  // namespace facehex
