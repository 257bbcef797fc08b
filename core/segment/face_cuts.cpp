#include "core/segment/face_cuts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "core/util/error.h"

namespace facehex {
namespace {

constexpr double kChinHalfWidth = 15.0;     // mm either side of the mid-plane where the chin's bone is looked for
constexpr double kEarWidthTolerance = 5.0;  // mm: rows this close to the widest still belong to the ears

std::string mm(double v) {
  std::ostringstream s;
  s.precision(1);
  s << std::fixed << v << " mm";
  return s.str();
}

}  // namespace

std::vector<CutPlane> FaceCuts::planes() const {
  std::vector<CutPlane> p = {{Eigen::Vector3d(0, 0, 1), top_z, V1},
                             {Eigen::Vector3d(0, 0, -1), -bottom_z, V0},
                             {Eigen::Vector3d(0, -1, 0), -posterior_y, U0}};
  if (jaw_z > -std::numeric_limits<double>::infinity())
    p.push_back({Eigen::Vector3d(0, -1, -1) / std::sqrt(2.0), -(posterior_y + jaw_z) / std::sqrt(2.0), V0});
  return p;
}

FaceCuts find_face_cuts(const Mask& head, const Mask& bone, const FaceCutOptions& options) {
  const GridGeometry& g = head.geometry;
  const double lowest = std::numeric_limits<double>::lowest(), highest = std::numeric_limits<double>::max();

  // Per slice: anterior-most and posterior-most head voxel; over the head: mean x.
  std::vector<double> front(g.dims[2], lowest), back(g.dims[2], highest);
  double x_sum = 0, count = 0;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i)
        if (head(i, j, k)) {
          const Eigen::Vector3d p = g.point(i, j, k);
          front[k] = std::max(front[k], p.y());
          back[k] = std::min(back[k], p.y());
          x_sum += p.x(), count += 1;
        }
  if (count == 0) throw Error("segment", "the head mask is empty");

  FaceCuts cuts;
  cuts.centre_x = options.centre_x ? *options.centre_x : x_sum / count;

  const double z_min = g.lower(2) + options.border_margin, z_max = g.upper(2) - options.border_margin;
  if (options.bottom_z) {
    cuts.bottom_z = *options.bottom_z;
  } else {
    double menton = highest;
    for (int k = 0; k < g.dims[2] && menton == highest; ++k) {
      if (front[k] == lowest) continue;
      const double anterior_limit = front[k] - 0.25 * (front[k] - back[k]);
      for (int j = 0; j < g.dims[1] && menton == highest; ++j)
        for (int i = 0; i < g.dims[0]; ++i) {
          const Eigen::Vector3d p = g.point(i, j, k);
          if (bone(i, j, k) && p.y() >= anterior_limit && std::abs(p.x() - cuts.centre_x) <= kChinHalfWidth) {
            menton = p.z();
            break;
          }
        }
    }
    cuts.bottom_z = std::max(z_min, menton == highest ? z_min : menton - options.chin_clearance);
  }
  cuts.top_z = options.top_z ? *options.top_z : std::min(z_max, cuts.bottom_z + options.face_height);
  if (!(cuts.top_z > cuts.bottom_z + 10.0))
    throw Error("segment", "the top cut (z = " + mm(cuts.top_z) + ") must be well above the bottom cut (z = " +
                               mm(cuts.bottom_z) + "); check the cut options and the CT's superior axis");

  if (options.posterior_y) {
    cuts.posterior_y = *options.posterior_y;
  } else {
    const double z_lo = cuts.bottom_z + 0.4 * (cuts.top_z - cuts.bottom_z);
    double y_front = lowest, y_back = highest;
    for (int k = 0; k < g.dims[2]; ++k) {
      const double z = g.point(0, 0, k).z();
      if (z < z_lo || z > cuts.top_z || front[k] == lowest) continue;
      y_front = std::max(y_front, front[k]);
      y_back = std::min(y_back, back[k]);
    }
    if (y_front == lowest) throw Error("segment", "no head between the bottom and top cuts");
    const double depth = y_front - y_back;
    std::vector<double> width(g.dims[1], -1);  // widest section of each coronal row of voxels
    for (int j = 0; j < g.dims[1]; ++j) {
      const double y = g.point(0, j, 0).y();
      if (y < y_back + 0.25 * depth || y > y_front - 0.25 * depth) continue;
      for (int k = 0; k < g.dims[2]; ++k) {
        const double z = g.point(0, 0, k).z();
        if (z < z_lo || z > cuts.top_z) continue;
        int first = -1, last = -1;
        for (int i = 0; i < g.dims[0]; ++i)
          if (head(i, j, k)) {
            if (first < 0) first = i;
            last = i;
          }
        if (first >= 0) width[j] = std::max(width[j], (last - first) * g.spacing(0));
      }
    }
    // The ears span several rows; their front is the most anterior row nearly as wide as the widest.
    const double widest = *std::max_element(width.begin(), width.end());
    double ear_front = y_back + 0.5 * depth;
    for (int j = 0; j < g.dims[1]; ++j)
      if (widest > 0 && width[j] >= widest - kEarWidthTolerance) ear_front = g.point(0, j, 0).y();
    cuts.posterior_y = ear_front + options.ear_clearance;
  }
  return cuts;
}

void find_jaw_cut(const Mask& model, double clearance, FaceCuts& cuts) {
  const GridGeometry& g = model.geometry;
  const int j = static_cast<int>(std::lround((cuts.posterior_y - g.origin.y()) / g.spacing.y()));
  const double x_reach = g.spacing.x();
  if (j < 0 || j >= g.dims[1]) return;
  // Only the lower half of the face: higher up, tissue across the mid-plane is the scalp over the skull's vertex.
  const double z_limit = 0.5 * (cuts.bottom_z + cuts.top_z);
  for (int k = g.dims[2] - 1; k >= 0; --k) {
    if (g.point(0, 0, k).z() > z_limit) continue;
    for (int i = 0; i < g.dims[0]; ++i)
      if (model(i, j, k) && std::abs(g.point(i, j, k).x() - cuts.centre_x) <= x_reach) {
        cuts.jaw_z = g.point(i, j, k).z() + clearance;
        return;
      }
  }
}

}  // namespace facehex
