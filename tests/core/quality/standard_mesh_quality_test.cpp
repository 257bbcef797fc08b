// The ArtiSynth reference face (the paper's standard hex mesh), as bundled: resources/standards/artisynth-refface
// holds it converted from its ANSYS files (the same nodes and cells, plus its side labels).
#include <gtest/gtest.h>

#include <iostream>

#include "core/io/mesh_io.h"
#include "core/mesh/corner_jacobian.h"
#include "core/quality/hex_quality.h"

namespace facehex {
namespace {

const std::string kStandard = FACEHEX_RESOURCE_DIR "/standards/artisynth-refface/standard.vtu";

// Mean and minimum of `values` over the cells of one type.
std::pair<double, double> mean_min(const VolumeMesh& mesh, const Eigen::VectorXd& values, CellType type) {
  double sum = 0, lowest = 1e300;
  for (int c = 0; c < mesh.num_cells(); ++c)
    if (mesh.types[c] == type) {
      sum += values(c);
      lowest = std::min(lowest, values(c));
    }
  return {sum / mesh.count(type), lowest};
}

TEST(StandardMesh, VerdictHexShapeAsPublishedAndNothingInverted) {
  const VolumeMesh mesh = read_volume_mesh(kStandard);
  ASSERT_EQ(mesh.count(CellType::Hex), 6024);
  ASSERT_EQ(mesh.count(CellType::Wedge), 318);

  // The wedges come from ANSYS collapsed bricks; read in VTK order they must be positively oriented like the hexes.
  EXPECT_TRUE(check_corner_jacobians(mesh).inverted.empty());
  const ElementQuality q = element_quality(mesh);
  const QualitySummary s = summarize(mesh, q);
  EXPECT_EQ(s.inverted, 0);
  const auto [hex_shape_mean, hex_shape_min] = mean_min(mesh, q.shape, CellType::Hex);
  EXPECT_NEAR(hex_shape_mean, 0.616, 0.0005);  // the published Verdict hex shape of this mesh
  EXPECT_NEAR(hex_shape_min, 0.039, 0.0005);

  // For the record (no published wedge values): the measured numbers per cell type.
  for (CellType type : {CellType::Hex, CellType::Wedge}) {
    const auto [shape_mean, shape_min] = mean_min(mesh, q.shape, type);
    const auto [sj_mean, sj_min] = mean_min(mesh, q.scaled_jacobian, type);
    std::cout << cell_type_name(type) << ": shape mean " << shape_mean << " min " << shape_min
              << ", scaled Jacobian mean " << sj_mean << " min " << sj_min << "\n";
  }
  std::cout << "all: " << 100 * s.fraction_scaled_jacobian_below_0_3 << "% scaled Jacobian below 0.3\n";
}

TEST(StandardMesh, DistortionAgainstItselfIsZero) {
  const VolumeMesh mesh = read_volume_mesh(kStandard);
  const DihedralDistortion d = dihedral_distortion(mesh, mesh);
  EXPECT_EQ(d.angles, 12L * 6024 + 9L * 318);
  EXPECT_EQ(d.percent[0], 100);
  EXPECT_EQ(d.max_deg, 0);
}

}  // namespace
}  // namespace facehex
