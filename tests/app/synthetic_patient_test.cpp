// The bundled standard mapped onto a synthetic face-like shell patient (TetGen): the whole method end to end.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>

#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/corner_jacobian.h"
#include "core/quality/hex_quality.h"
#include "core/standard/closed_domain.h"
#include "core/util/resources.h"
#include "core/workflow/patient_setup.h"

namespace facehex {
namespace {

TEST(SyntheticPatient, BundledStandardTransfersWithNoInvertedElement) {
  const BundledModel files = default_standard();
  const VolumeMesh standard = read_volume_mesh(files.mesh);
  const VolumeMesh patient = synthetic_shell_patient(6.0);
  // Both with the same semantics: the six sides only (the shell has no lips or brows to place features on).
  const TransferRun run = run_transfer(standard, closed_domain(standard), side_constraints(), files.constraints,
                                       patient, side_constraints(), "shell", TransferOptions{});
  EXPECT_TRUE(run.patient.health.ok());
  EXPECT_EQ(run.transfer.snap_failures, 0);
  const QualitySummary q = summarize(run.patient_hex, element_quality(run.patient_hex));
  std::printf("shell patient: %d tets; mapped: %d inverted before repair, %d after; shape mean %.3f, min SJ %.3f\n",
              patient.num_cells(), run.untangle.inverted_before, run.untangle.inverted_after, q.shape_mean,
              q.scaled_jacobian_min);
  if (const char* dump = std::getenv("FACEHEX_TEST_DUMP")) write_volume_mesh(dump, run.patient_hex);
  EXPECT_EQ(q.inverted, 0);
  EXPECT_TRUE(check_corner_jacobians(run.patient_hex).inverted.empty());
}

}  // namespace
}  // namespace facehex
