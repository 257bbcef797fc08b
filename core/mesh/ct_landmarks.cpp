#include "core/mesh/ct_landmarks.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/util/error.h"

namespace facehex {
namespace {

constexpr int kRows = static_cast<int>(kCtLandmarkNames.size());

// The rows in kCtLandmarkNames order (pointers to const members for a const CtLandmarks).
template <class Landmarks>
auto rows_of(Landmarks& l) {
  return std::array{&l.tragi[0],       &l.tragi[1],       &l.eye_corners[0], &l.eye_corners[1],
                    &l.eye_corners[2], &l.eye_corners[3], &l.stomion};
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
                            std::to_string(kRows) + " x 4: x, y, z mm and 1 if estimated) " + problem + ": " +
                            given.str() + "; remove it to have them left out");
  };
  if (t.rows() != kRows || t.cols() != 4)
    malformed("is " + std::to_string(t.rows()) + " x " + std::to_string(t.cols()));
  CtLandmarks out;
  const auto rows = rows_of(out);
  for (int r = 0; r < kRows; ++r) {
    if (t.row(r).array().isNaN().all()) continue;
    if (!t.row(r).allFinite()) malformed("has a row with numbers that are not finite");
    if (t(r, 3) != 0 && t(r, 3) != 1) malformed("has a status that is neither 0 nor 1");
    *rows[r] = CtLandmark{t.row(r).head<3>().transpose(), t(r, 3) == 1};
  }
  return out;
}

void set_ct_landmarks(VolumeMesh& mesh, const CtLandmarks& landmarks) {
  Eigen::MatrixXd t = Eigen::MatrixXd::Constant(kRows, 4, std::numeric_limits<double>::quiet_NaN());
  const auto rows = rows_of(landmarks);
  for (int r = 0; r < kRows; ++r)
    if (*rows[r]) t.row(r) << (*rows[r])->point.transpose(), (*rows[r])->estimated ? 1.0 : 0.0;
  mesh.field_data[kCtLandmarksField] = t;
}

}  // namespace facehex
