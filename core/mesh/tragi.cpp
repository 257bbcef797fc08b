#include "core/mesh/tragi.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/util/error.h"

namespace facehex {

std::optional<Tragi> tragi(const VolumeMesh& mesh, const std::string& source) {
  const auto field = mesh.field_data.find(kTragiField);
  if (field == mesh.field_data.end()) return std::nullopt;
  const Eigen::MatrixXd& t = field->second;
  const auto malformed = [&](const std::string& problem) {
    std::ostringstream given;
    given << t.format(Eigen::IOFormat(Eigen::StreamPrecision, Eigen::DontAlignCols, " ", "; "));
    throw Error(source, std::string("the field data '") + kTragiField + "' (the tragi, 2 x 4: x, y, z mm and 1 if " +
                            "estimated) " + problem + ": " + given.str() + "; remove it to have the tragi left out");
  };
  if (t.rows() != 2 || t.cols() != 4) malformed("is " + std::to_string(t.rows()) + " x " + std::to_string(t.cols()));
  Tragi out;
  for (int side = 0; side < 2; ++side) {
    if (t.row(side).array().isNaN().all()) continue;
    if (!t.row(side).allFinite()) malformed("has a row with numbers that are not finite");
    if (t(side, 3) != 0 && t(side, 3) != 1) malformed("has a status that is neither 0 nor 1");
    out[side] = Tragus{t.row(side).head<3>().transpose(), t(side, 3) == 1};
  }
  return out;
}

void set_tragi(VolumeMesh& mesh, const Tragi& tragi) {
  Eigen::MatrixXd t = Eigen::MatrixXd::Constant(2, 4, std::numeric_limits<double>::quiet_NaN());
  for (int side = 0; side < 2; ++side)
    if (tragi[side]) t.row(side) << tragi[side]->point.transpose(), tragi[side]->estimated ? 1.0 : 0.0;
  mesh.field_data[kTragiField] = t;
}

}  // namespace facehex
