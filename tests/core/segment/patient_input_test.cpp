#include "core/segment/patient_input.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

#include "core/io/mesh_io.h"
#include "core/segment/ct_volume.h"

namespace facehex {
namespace {
namespace fs = std::filesystem;

TEST(PatientInput, CtVolumesAreTheImageFormatsAndFolders) {
  for (const char* ct : {"head.mhd", "HEAD.MHA", "a/b/head.nii", "head.nii.gz", "head.nrrd", "head.nhdr"})
    EXPECT_TRUE(is_ct_input(ct)) << ct;
  for (const char* mesh : {"patient.vtu", "patient.vtk", "face.stl", "head.gz", ".mhd", "mhd"})
    EXPECT_FALSE(is_ct_input(mesh)) << mesh;
  EXPECT_TRUE(is_ct_input(fs::temp_directory_path().string()));  // a DICOM folder
}

TEST(PatientInput, AMeshFileIsReadCheckedAndOriented) {
  // Two tets sharing a face, both negatively oriented: flipped, and said so.
  VolumeMesh m = VolumeMesh::from_tets(
      (Eigen::MatrixXd(5, 3) << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -1).finished(),
      (Eigen::MatrixXi(2, 4) << 0, 2, 1, 3, 0, 1, 2, 4).finished());
  const fs::path path = fs::temp_directory_path() / ("facehex-patient-input-" + std::to_string(::getpid()) + ".vtu");
  write_volume_mesh(path.string(), m);
  const PatientTetModel p = load_patient_model(path.string());
  fs::remove(path);
  EXPECT_TRUE(p.check.reoriented);
  EXPECT_EQ(p.mesh.num_cells(), 2);
  EXPECT_NEAR(p.check.volume, 2.0 / 6.0, 1e-12);
}

}  // namespace
}  // namespace facehex
