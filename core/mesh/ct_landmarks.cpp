#include "core/mesh/ct_landmarks.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/util/error.h"

namespace facehex {
namespace {

constexpr int kRows = static_cast<int>(kCtLandmarkNames.size());
constexpr int kFewestRows = 7;  // the tragi, the eye corners and the stomion

// The rows in kCtLandmarkNames order (pointers to const members for a const CtLandmarks).
template <class Landmarks>
auto rows_of(Landmarks& l) {
  return std::array{&l.tragi[0],       &l.tragi[1], &l.eye_corners[0],   &l.eye_corners[1],   &l.eye_corners[2],
                    &l.eye_corners[3], &l.stomion,  &l.mouth_corners[0], &l.mouth_corners[1], &l.bony_menton};
}

}  // namespace

std::optional<CtLandmarks> ct_landmarks(const VolumeMesh& mesh, const std::string& source) {
  const auto field = mesh.field_data.find(kCtLandmarksField);
  if (field == mesh.field_data.end()) return std::nullopt;
  const Eigen::MatrixXd& t = field->second;
  const auto malformed = [&](const std::string& problem) {
    std::ostringstream given;
    given << t.format(Eigen::IOFormat(Eigen::StreamPrecision, Eigen::DontAlignCols, " ", "; "));
    throw Error(source, std::string("the field data '") + kCtLandmarksField + "' (the landmarks found in the CT, " +
                            std::to_string(kFewestRows) + " to " + std::to_string(kRows) +
                            " rows x 4: x, y, z mm and 1 if estimated) " + problem + ": " + given.str() +
                            "; remove it to have them left out");
  };
  if (t.rows() < kFewestRows || t.rows() > kRows || t.cols() != 4)
    malformed("is " + std::to_string(t.rows()) + " x " + std::to_string(t.cols()));
  CtLandmarks out;
  const auto rows = rows_of(out);
  for (int r = 0; r < t.rows(); ++r) {
    if (t.row(r).array().isNaN().all()) continue;
    if (!t.row(r).allFinite()) malformed("has a row with numbers that are not finite");
    if (t(r, 3) != 0 && t(r, 3) != 1) malformed("has a status that is neither 0 nor 1");
    *rows[r] = CtLandmark{t.row(r).head<3>().transpose(), t(r, 3) == 1};
  }
  const auto objects = mesh.field_data.find(kSkinObjectsField);
  if (objects == mesh.field_data.end()) return out;
  const Eigen::MatrixXd& o = objects->second;
  const auto under = mesh.field_data.find(kSkinUnderObjectsField);
  const Eigen::MatrixXd skin = under == mesh.field_data.end() ? Eigen::MatrixXd(0, 3) : under->second;
  const auto refuse = [&](const char* name, const Eigen::MatrixXd& given, const std::string& shape) {
    std::ostringstream text;
    text << given.format(Eigen::IOFormat(Eigen::StreamPrecision, Eigen::DontAlignCols, " ", "; "));
    throw Error(source, std::string("the field data '") + name + "' (objects on the skin, " + shape +
                            ") is not so: " + text.str() + "; remove '" + kSkinObjectsField + "' and '" +
                            kSkinUnderObjectsField + "' to have them left out");
  };
  const std::string objects_shape = "#O x 4: z_low < z_high, the thicknesses there > 0, mm";
  const std::string skin_shape = "#S x 3: an object's row, z increasing, y; two rows at least per object";
  if (o.cols() != 4) refuse(kSkinObjectsField, o, objects_shape);
  if (skin.cols() != 3) refuse(kSkinUnderObjectsField, skin, skin_shape);
  for (Eigen::Index r = 0; r < o.rows(); ++r) {
    if (!o.row(r).allFinite() || !(o(r, 0) < o(r, 1)) || !(o(r, 2) > 0) || !(o(r, 3) > 0))
      refuse(kSkinObjectsField, o, objects_shape);
    out.skin_objects.push_back({o(r, 0), o(r, 1), o(r, 2), o(r, 3), {}});
  }
  for (Eigen::Index r = 0; r < skin.rows(); ++r) {
    const double object = skin(r, 0);
    if (!skin.row(r).allFinite() || object < 0 || object >= static_cast<double>(o.rows()) ||
        object != std::floor(object))
      refuse(kSkinUnderObjectsField, skin, skin_shape);
    auto& points = out.skin_objects[static_cast<size_t>(object)].skin;
    if (!points.empty() && !(skin(r, 1) > points.back().x())) refuse(kSkinUnderObjectsField, skin, skin_shape);
    points.emplace_back(skin(r, 1), skin(r, 2));
  }
  for (const SkinObject& object : out.skin_objects)
    if (object.skin.size() < 2) refuse(kSkinUnderObjectsField, skin, skin_shape);
  return out;
}

void set_ct_landmarks(VolumeMesh& mesh, const CtLandmarks& landmarks) {
  Eigen::MatrixXd t = Eigen::MatrixXd::Constant(kRows, 4, std::numeric_limits<double>::quiet_NaN());
  const auto rows = rows_of(landmarks);
  for (int r = 0; r < kRows; ++r)
    if (*rows[r]) t.row(r) << (*rows[r])->point.transpose(), (*rows[r])->estimated ? 1.0 : 0.0;
  mesh.field_data[kCtLandmarksField] = t;
  mesh.field_data.erase(kSkinObjectsField);
  mesh.field_data.erase(kSkinUnderObjectsField);
  if (landmarks.skin_objects.empty()) return;
  Eigen::MatrixXd o(static_cast<Eigen::Index>(landmarks.skin_objects.size()), 4);
  std::vector<Eigen::RowVector3d> skin;
  for (size_t i = 0; i < landmarks.skin_objects.size(); ++i) {
    const SkinObject& s = landmarks.skin_objects[i];
    o.row(static_cast<Eigen::Index>(i)) << s.z_low, s.z_high, s.thickness_low, s.thickness_high;
    for (const Eigen::Vector2d& p : s.skin) skin.emplace_back(static_cast<double>(i), p.x(), p.y());
  }
  Eigen::MatrixXd under(static_cast<Eigen::Index>(skin.size()), 3);
  for (size_t r = 0; r < skin.size(); ++r) under.row(static_cast<Eigen::Index>(r)) = skin[r];
  mesh.field_data[kSkinObjectsField] = o;
  mesh.field_data[kSkinUnderObjectsField] = under;
}

}  // namespace facehex
