#include "core/face_landmarks.h"

#include "core/error.h"
#include "core/sides.h"

#include <cmath>
#include <limits>
#include <optional>

namespace facehex {
namespace {

// Most anterior skin point per 1 mm bin of z near the plane x = x_mid.
struct Profile {
  double z0 = 0;
  std::vector<std::optional<Eigen::Vector3d>> bins;

  // The most (max = true) or least anterior point with z in [lo, hi].
  std::optional<Eigen::Vector3d> extreme(double lo, double hi, bool max) const {
    std::optional<Eigen::Vector3d> best;
    for (size_t b = 0; b < bins.size(); ++b) {
      const double z = z0 + static_cast<double>(b) + 0.5;
      if (z < lo || z > hi || !bins[b]) continue;
      if (!best || (max ? bins[b]->y() > best->y() : bins[b]->y() < best->y())) best = bins[b];
    }
    return best;
  }
};

Profile skin_profile(const Eigen::MatrixXd& V, const std::vector<int>& skin, double x_mid, double band) {
  Profile p;
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (int v : skin) {
    zmin = std::min(zmin, V(v, 2));
    zmax = std::max(zmax, V(v, 2));
  }
  p.z0 = std::floor(zmin);
  p.bins.resize(static_cast<size_t>(std::ceil(zmax) - p.z0) + 1);
  for (int v : skin) {
    if (std::abs(V(v, 0) - x_mid) > band) continue;
    auto& bin = p.bins[static_cast<size_t>(V(v, 2) - p.z0)];
    if (!bin || V(v, 1) > bin->y()) bin = V.row(v).transpose();
  }
  return p;
}

Eigen::Vector3d require(const std::optional<Eigen::Vector3d>& p, const std::string& name) {
  if (!p) throw Error("landmarks", "cannot find the " + name + " on the mid-sagittal skin profile (is the face "
                                   "looking to +y with +z up? see --orientation)");
  return *p;
}

}  // namespace

FaceLandmarks find_face_landmarks(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                  const LandmarkOptions& options) {
  if (side_mask.size() != V.rows()) throw Error("landmarks", "the model has no side labels (side_mask)");
  std::vector<int> skin;
  for (int v = 0; v < V.rows(); ++v)
    if (side_mask(v) & side_bit(W1)) skin.push_back(v);
  if (skin.empty()) throw Error("landmarks", "the model has no skin side (w1)");
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, zmin = xmin, zmax = -xmin;
  for (int v : skin) {
    xmin = std::min(xmin, V(v, 0));
    xmax = std::max(xmax, V(v, 0));
    zmin = std::min(zmin, V(v, 2));
    zmax = std::max(zmax, V(v, 2));
  }
  FaceLandmarks l;
  l.x_mid = 0.5 * (xmin + xmax);
  const double height = zmax - zmin;
  // The nose tip near the middle, then the plane through it.
  const auto first = skin_profile(V, skin, l.x_mid, 20.0).extreme(zmin + 0.1 * height, zmax - 0.1 * height, true);
  l.x_mid = require(first, "nose tip").x();
  const Profile profile = skin_profile(V, skin, l.x_mid, options.profile_band);
  const Eigen::Vector3d prn = require(profile.extreme(zmin + 0.1 * height, zmax - 0.1 * height, true), "nose tip");
  const Eigen::Vector3d sn = require(profile.extreme(prn.z() - 25, prn.z() - 3, false), "subnasale");
  const Eigen::Vector3d n = require(profile.extreme(prn.z() + 10, prn.z() + 45, false), "nasion");
  const Eigen::Vector3d g = require(profile.extreme(n.z() + 3, n.z() + 25, true), "glabella");
  // The lips: the upper lip's most anterior point, the lower lip's, and the least anterior point between them.
  const Eigen::Vector3d ls = require(profile.extreme(sn.z() - 20, sn.z() - 3, true), "upper lip");
  const Eigen::Vector3d li = require(profile.extreme(ls.z() - 30, ls.z() - 6, true), "lower lip");
  const Eigen::Vector3d st = require(profile.extreme(li.z() + 1, ls.z() - 1, false), "stomion");
  l.points = {{"pronasale", prn}, {"subnasale", sn}, {"nasion", n},          {"glabella", g},
              {"labrale superius", ls}, {"labrale inferius", li}, {"stomion", st}};
  return l;
}

const std::vector<FeatureSpec>& feature_specs() {
  static const std::vector<FeatureSpec> specs = {{"mid-sagittal line", "pronasale", 0, 0.0},
                                                 {"eyebrow line", "glabella", 1, 35.0},
                                                 {"below-nose line", "subnasale", 1, 15.0},
                                                 {"middle lip line", "stomion", 1, 25.0}};
  return specs;
}

ConstraintSet feature_constraints(const FaceLandmarks& landmarks, const std::map<std::string, double>& values,
                                  double band) {
  ConstraintSet set;
  for (const FeatureSpec& spec : feature_specs()) {
    Constraint c;
    c.name = spec.name;
    c.field = spec.field;
    const auto value = values.find(spec.name);
    if (value == values.end() && spec.field != 0)
      throw Error("feature constraints", "no value for the " + spec.name + " (take it from the standard's set)");
    c.value = value == values.end() ? 0.5 : value->second;
    PlaneSelection p;
    p.band = band;
    p.exclude_sides = side_bit(static_cast<Side>(2 * spec.field)) | side_bit(static_cast<Side>(2 * spec.field + 1));
    const Eigen::Vector3d at = landmarks.points.at(spec.landmark);
    if (spec.field == 0) {
      p.point = Eigen::Vector3d(landmarks.x_mid, 0, 0);
      p.normal = Eigen::Vector3d::UnitX();
      p.region = "volume";
    } else {
      p.point = at;
      p.normal = Eigen::Vector3d::UnitZ();
      p.region = "boundary";
      p.within_center = at;
      p.within_radius = spec.radius;
    }
    c.select.plane = p;
    set.constraints.push_back(c);
  }
  return set;
}

}  // namespace facehex
