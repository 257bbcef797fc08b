#include "core/mesh/scan_frame.h"

#include <iomanip>
#include <sstream>

#include "core/util/error.h"

namespace facehex {

ScanFrame ScanFrame::after_model_change(const Eigen::Matrix3d& A, const Eigen::Vector3d& b) const {
  // p_scan = R p_old + t and p_old = A^T (p_new - b).
  ScanFrame f;
  f.rotation = rotation * A.transpose();
  f.translation = translation - f.rotation * b;
  return f;
}

ScanFrame scan_frame(const VolumeMesh& mesh, const std::string& source) {
  const auto field = mesh.field_data.find(kScanFrameField);
  if (field == mesh.field_data.end()) return {};
  const Eigen::MatrixXd& m = field->second;
  const bool shaped = m.rows() == 3 && m.cols() == 4 && m.allFinite();
  if (!shaped || !(m.leftCols<3>().transpose() * m.leftCols<3>()).isApprox(Eigen::Matrix3d::Identity(), 1e-6))
    throw Error(source, std::string("the field data '") + kScanFrameField +
                            "' (where the model lies in its scan: a 3 x 4 matrix [R | t] with R orthogonal) is not "
                            "that; remove it to take the model's own frame as the scan's");
  ScanFrame f;
  f.rotation = m.leftCols<3>();
  f.translation = m.col(3);
  return f;
}

void set_scan_frame(VolumeMesh& mesh, const ScanFrame& frame) {
  Eigen::MatrixXd m(3, 4);
  m << frame.rotation, frame.translation;
  mesh.field_data[kScanFrameField] = m;
}

std::string scan_frame_text(const ScanFrame& frame) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(1) << "the patient's left at " << (frame.left_at_minus_x() ? "-x" : "+x")
    << " of the model; ";
  const Eigen::Matrix3d& R = frame.rotation;
  const bool permutation = ((R.array().abs() - 1).abs() < 1e-9 || R.array().abs() < 1e-9).all();
  if (permutation) {
    s << "model (x, y, z) at scan (";
    for (int r = 0; r < 3; ++r) {
      int c = 0;
      R.row(r).cwiseAbs().maxCoeff(&c);
      const double t = frame.translation(r);
      s << (r ? ", " : "") << (R(r, c) < 0 ? "-" : "") << char('x' + c);
      if (t != 0) s << (t < 0 ? " - " : " + ") << std::abs(t);
    }
    s << ") mm (LPS)";
  } else {
    s << std::setprecision(3) << "scan (LPS) = R model + t, R rows";
    for (int r = 0; r < 3; ++r) s << " (" << R(r, 0) << ", " << R(r, 1) << ", " << R(r, 2) << ")";
    s << std::setprecision(1) << ", t (" << frame.translation.x() << ", " << frame.translation.y() << ", "
      << frame.translation.z() << ") mm";
  }
  return s.str();
}

int named_side(const std::string& name) {
  const auto ends_with = [&name](const std::string& suffix) {
    return name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  return ends_with(" left") ? 1 : ends_with(" right") ? -1 : 0;
}

std::string other_side_name(const std::string& name) {
  switch (named_side(name)) {
    case 1:
      return name.substr(0, name.size() - 5) + " right";
    case -1:
      return name.substr(0, name.size() - 6) + " left";
    default:
      return name;
  }
}

std::string patient_side_name(const std::string& name, const ScanFrame& frame) {
  return frame.left_at_minus_x() ? other_side_name(name) : name;
}

}  // namespace facehex
