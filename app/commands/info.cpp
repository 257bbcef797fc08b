#include <iostream>
#include <optional>

#include "app/cli_args.h"
#include "app/commands/commands.h"
#include "core/face/face_landmarks.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mesh/corner_jacobian.h"
#include "core/mesh/ct_landmarks.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/mesh/scan_frame.h"
#include "core/mesh/sides.h"
#include "core/mesh/skin_points.h"

namespace facehex::cli {

int cmd_info(const Argv& argv) {
  Args args("info", "Prints sizes, cell types, bounding box, volume and side labels of a mesh.");
  args.positional("MESH", "mesh file");
  if (!args.parse(argv)) return 0;
  const std::string path = args.get("MESH");
  const VolumeMesh m = read_volume_mesh(path);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  std::cout << path << "\n  vertices " << m.num_vertices() << "\n  cells " << m.num_cells() << " (tet "
            << m.count(CellType::Tet) << ", wedge " << m.count(CellType::Wedge) << ", hex " << m.count(CellType::Hex)
            << ")\n  bounding box [" << lo << "] - [" << hi << "] mm\n";
  const Eigen::VectorXi mask = side_mask_of(m);
  if (mask.size() > 0) {
    std::cout << "  side vertices:";
    for (int s = 0; s < kNumSides; ++s)
      std::cout << " " << kSideNames[s] << " " << std::count_if(mask.data(), mask.data() + mask.size(), [&](int m) {
        return (m & side_bit(static_cast<Side>(s))) != 0;
      });
    std::cout << "\n";
  }
  // A mesh with inverted or flat cells reads fine but no solver or transfer can use it: say so.
  const CornerJacobianCheck cells = check_corner_jacobians(m);
  std::cout << "  inverted cells " << cells.inverted.size() << ", flat cells " << cells.degenerate.size() << "\n";
  if (const std::vector<int> unusable = cells.unusable(); !unusable.empty()) {
    std::cerr << "warning: " << path << ": " << cells.inverted.size() << " inverted and " << cells.degenerate.size()
              << " flat cells (first: cell " << unusable.front() << ", 0-based)\n";
  }
  std::cout << "  arrays:";
  for (const auto& [name, a] : m.point_data) std::cout << " " << name << "(point," << a.cols() << ")";
  for (const auto& [name, a] : m.cell_data) std::cout << " " << name << "(cell," << a.cols() << ")";
  for (const auto& [name, a] : m.field_data)
    std::cout << " " << name << "(field," << a.rows() << "x" << a.cols() << ")";
  std::cout << "\n";
  if (const std::optional<MidSagittalPlane> plane = mid_sagittal_plane(m, path))
    std::cout << "  mid-sagittal plane " << mid_sagittal_plane_text(*plane)
              << " (from the segmentation; the landmarks are found on it)\n";
  if (const std::optional<Eigen::MatrixXd> skin = skin_points(m, path))
    std::cout << "  skin points " << skin->rows()
              << " (the CT's skin at the segmentation's working spacing; the landmarks are found on them)\n";
  const ScanFrame frame = scan_frame(m, path);
  if (m.field_data.count(kScanFrameField)) std::cout << "  scan frame: " << scan_frame_text(frame) << "\n";
  if (const std::optional<CtLandmarks> found = ct_landmarks(m, path)) {
    const auto print = [&frame](const char* name, const std::optional<CtLandmark>& l) {
      std::cout << "    " << patient_side_name(name, frame) << " ";
      if (l)
        std::cout << "(" << l->point.x() << ", " << l->point.y() << ", " << l->point.z() << ") mm"
                  << (l->estimated ? " (estimated)" : "") << "\n";
      else
        std::cout << "unseen\n";
    };
    std::cout << "  landmarks found in the CT by the segmentation:\n";
    for (size_t side = 0; side < kTragusNames.size(); ++side) print(kTragusNames[side], found->tragi[side]);
    for (size_t c = 0; c < kEyeCornerNames.size(); ++c) print(kEyeCornerNames[c], found->eye_corners[c]);
    print(kStomionName, found->stomion);
    for (size_t c = 0; c < kMouthCornerNames.size(); ++c) print(kMouthCornerNames[c], found->mouth_corners[c]);
    print(kBonyMentonName, found->bony_menton);
    for (const SkinObject& object : found->skin_objects) std::cout << "    " << skin_object_text(object) << "\n";
  }
  return 0;
}

}  // namespace facehex::cli
