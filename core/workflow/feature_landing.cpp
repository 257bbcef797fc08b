#include "core/workflow/feature_landing.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/mesh/head_turn.h"

namespace facehex {

std::vector<FeatureLanding> feature_landing(const StandardFeatures& standard, const Eigen::MatrixXd& transferred,
                                            const FaceLandmarks& patient, const std::vector<std::string>& pulled) {
  std::vector<FeatureLanding> out;
  const HeadTurn frame = head_turn_of(patient.plane);
  for (const NamedLandmark& l : named_landmarks(patient)) {
    const auto vertex = standard.landmark_vertices.find(l.name);
    if (vertex == standard.landmark_vertices.end() || vertex->second >= transferred.rows()) continue;
    const Eigen::Vector3d landed = transferred.row(vertex->second).transpose();
    const Eigen::Vector3d apart = frame.to_head(landed) - frame.to_head(l.position);
    const bool pulled_it = std::find(pulled.begin(), pulled.end(), l.name) != pulled.end();
    out.push_back({patient_side_name(l.name, patient.scan_frame), std::hypot(apart.x(), apart.z()), l.status, landed,
                   l.position, pulled_it});
  }
  return out;
}

namespace {

struct Totals {
  double mean = 0, max = 0, found_mean = 0;
  int found = 0;
  const FeatureLanding* farthest = nullptr;
};

Totals totals(const std::vector<FeatureLanding>& landing) {
  Totals t;
  for (const FeatureLanding& l : landing) {
    t.mean += l.distance / static_cast<double>(landing.size());
    if (!t.farthest || l.distance > t.farthest->distance) t.farthest = &l;
    if (l.patient_status != LandmarkStatus::estimated) t.found_mean += l.distance, ++t.found;
  }
  if (t.found > 0) t.found_mean /= t.found;
  if (t.farthest) t.max = t.farthest->distance;
  return t;
}

}  // namespace

nlohmann::json feature_landing_json(const std::vector<FeatureLanding>& landing) {
  if (landing.empty()) return nullptr;
  const Totals t = totals(landing);
  nlohmann::json list = nlohmann::json::array();
  for (const FeatureLanding& l : landing)
    list.push_back({{"name", l.name},
                    {"mm", l.distance},
                    {"patient", status_name(l.patient_status)},
                    {"pulled", l.pulled},
                    {"landed", {l.landed.x(), l.landed.y(), l.landed.z()}},
                    {"patient_at", {l.patient.x(), l.patient.y(), l.patient.z()}}});
  return {{"mean_mm", t.mean}, {"max_mm", t.max}, {"landmarks", list}};
}

std::string feature_landing_text(const std::vector<FeatureLanding>& landing) {
  if (landing.empty()) return "";
  const Totals t = totals(landing);
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << "anatomy: the standard's " << landing.size() << " landmarks land " << t.mean
    << " mm across the face from the patient's on average";
  if (t.found > 0 && t.found < static_cast<int>(landing.size()))
    s << " (" << t.found_mean << " mm at the " << t.found << " not estimated)";
  s << ", farthest " << t.farthest->name << " " << t.max << " mm";
  std::string not_pulled;
  bool any_pulled = false;
  for (const FeatureLanding& l : landing) {
    any_pulled = any_pulled || l.pulled;
    if (!l.pulled) not_pulled += (not_pulled.empty() ? "" : ", ") + l.name;
  }
  if (any_pulled && !not_pulled.empty()) s << "; not pulled: " << not_pulled;
  s << "\n";
  return s.str();
}

}  // namespace facehex
