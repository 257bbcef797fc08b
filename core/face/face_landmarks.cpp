#include "core/face/face_landmarks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "core/mesh/sides.h"
#include "core/util/error.h"

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

  // The longest run of bins at most `depth` mm behind `front` (one missing bin allowed), as (lowest z, highest z), if
  // it is at least `min_length` mm long: a flat plateau where the scan's field of view cut the face.
  std::optional<std::pair<double, double>> clipped_run(double front, double depth, double min_length) const {
    std::optional<std::pair<double, double>> best;
    bool in_run = false;
    std::pair<double, double> run{0.0, 0.0};
    int gap = 0;
    for (size_t b = 0; b < bins.size(); ++b) {
      const double z = z0 + static_cast<double>(b) + 0.5;
      if (bins[b] && bins[b]->y() >= front - depth) {
        run = in_run ? std::pair{run.first, z} : std::pair{z, z};
        in_run = true;
        gap = 0;
      } else if (in_run && ++gap > 1) {
        in_run = false;
      }
      if (in_run && (!best || run.second - run.first > best->second - best->first)) best = run;
    }
    if (best && best->second - best->first >= min_length) return best;
    return std::nullopt;
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
  if (!p)
    throw Error("landmarks", "cannot find the " + name +
                                 " on the mid-sagittal skin profile (is the face "
                                 "looking to +y with +z up? see --orientation)");
  return *p;
}

// Landmarks of a profile whose front was cut flat by the scan's field of view over z in [cut.first, cut.second]
// (from the nose down to the upper lip or nose): below the cut, the upper lip is the most anterior point, the
// subnasale the least anterior one between it and the cut, the stomion the least anterior one below the upper lip
// and the lower lip the most anterior one below that; the nose tip, nasion and glabella lie inside the cut and are
// placed above the subnasale by typical adult proportions (nose tip 15 mm, nasion 55 mm, glabella 67 mm), on the
// cut, below the top of the skin.
FaceLandmarks clipped_face_landmarks(const Profile& profile, const std::pair<double, double>& cut, double x_mid,
                                     double zmax) {
  FaceLandmarks l;
  l.x_mid = x_mid;
  l.clipped_from = cut.first;
  l.clipped_to = cut.second;
  const Eigen::Vector3d ls = require(profile.extreme(cut.first - 30, cut.first - 6, true), "upper lip");
  const Eigen::Vector3d sn = require(profile.extreme(ls.z() + 1, cut.first, false), "subnasale");
  const Eigen::Vector3d st = require(profile.extreme(ls.z() - 20, ls.z() - 3, false), "stomion");
  const Eigen::Vector3d li = require(profile.extreme(st.z() - 20, st.z() - 1, true), "lower lip");
  auto on_cut = [&](double z) {
    const std::optional<Eigen::Vector3d> p = profile.extreme(z - 1, z + 1, true);
    return Eigen::Vector3d(x_mid, p ? p->y() : profile.extreme(cut.first, cut.second, true)->y(), z);
  };
  const double prn = std::min(sn.z() + 15, zmax - 20), n = std::min(prn + 40, zmax - 13),
               g = std::min(n + 12, zmax - 1);
  l.points = {{"pronasale", on_cut(prn)}, {"subnasale", sn},        {"nasion", on_cut(n)}, {"glabella", on_cut(g)},
              {"labrale superius", ls},   {"labrale inferius", li}, {"stomion", st}};
  l.estimated = {"pronasale", "nasion", "glabella"};
  return l;
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
  const Eigen::Vector3d front = require(profile.extreme(zmin + 0.1 * height, zmax - 0.1 * height, true), "nose tip");
  const std::optional<std::pair<double, double>> cut =
      profile.clipped_run(front.y(), options.clipped_depth, options.clipped_length);
  if (cut) return clipped_face_landmarks(profile, *cut, l.x_mid, zmax);
  const Eigen::Vector3d prn = front;
  const Eigen::Vector3d sn = require(profile.extreme(prn.z() - 25, prn.z() - 3, false), "subnasale");
  const Eigen::Vector3d n = require(profile.extreme(prn.z() + 10, prn.z() + 45, false), "nasion");
  const Eigen::Vector3d g = require(profile.extreme(n.z() + 3, n.z() + 25, true), "glabella");
  // The lips: the upper lip's most anterior point, the lower lip's, and the least anterior point between them.
  const Eigen::Vector3d ls = require(profile.extreme(sn.z() - 20, sn.z() - 3, true), "upper lip");
  const Eigen::Vector3d li = require(profile.extreme(ls.z() - 30, ls.z() - 6, true), "lower lip");
  const Eigen::Vector3d st = require(profile.extreme(li.z() + 1, ls.z() - 1, false), "stomion");
  l.points = {{"pronasale", prn},       {"subnasale", sn},        {"nasion", n},  {"glabella", g},
              {"labrale superius", ls}, {"labrale inferius", li}, {"stomion", st}};
  return l;
}

std::string landmarks_text(const FaceLandmarks& l, const std::string& indent) {
  std::ostringstream os;
  if (!std::isnan(l.clipped_from))
    os << indent << "the scan's field of view cuts the face flat from z = " << l.clipped_from << " to " << l.clipped_to
       << " mm: landmarks inside the cut are estimated from typical proportions\n";
  for (const auto& [name, p] : l.points) {
    const bool estimated = std::find(l.estimated.begin(), l.estimated.end(), name) != l.estimated.end();
    os << indent << name << " at (" << p.x() << ", " << p.y() << ", " << p.z() << ") mm"
       << (estimated ? " (estimated)" : "") << "\n";
  }
  return os.str();
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
