// DICOM series folders: written slice by slice with GDCM's writer here (CT Image Storage, explicit VR little
// endian), read back by the product: sorted by position, rescaled, oriented from ImageOrientationPatient; several
// series, uneven spacing and empty folders are errors naming the folder.
#include "core/segment/dicom_series.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "core/face/face_landmarks.h"
#include "core/face/landmark_file.h"
#include "core/io/mesh_io.h"
#include "core/mesh/side_mask.h"
#include "core/segment/ct_volume.h"
#include "core/segment/patient_input.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "tests/core/io/io_test_util.h"
#include "tests/core/segment/dicom_writer.h"

namespace facehex {
namespace {

namespace fs = std::filesystem;
using facehex::testing::SliceSpec;
using facehex::testing::write_bundled_series;
using facehex::testing::write_slice;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = test::program_scratch_dir() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Four 3 x 2 slices 2.5 mm apart, written in scrambled file order; raw value i + 10 j + 100 k (k: position order),
// slope 2, intercept -1000.
fs::path write_small_series(const std::string& name, const SliceSpec& base = {}) {
  const fs::path dir = fresh_dir(name);
  const char* files[4] = {"c.dcm", "a.dcm", "d.dcm", "b.dcm"};
  for (int k = 0; k < 4; ++k) {
    SliceSpec s = base;
    s.slope = 2;
    s.intercept = -1000;
    s.position = base.position + k * 2.5 * Eigen::Vector3d(0, 0, 1);
    std::vector<std::int16_t> raw;
    for (int j = 0; j < s.ny; ++j)
      for (int i = 0; i < s.nx; ++i) raw.push_back(static_cast<std::int16_t>(i + 10 * j + 100 * k));
    write_slice((dir / files[k]).string(), s, raw);
  }
  return dir;
}

TEST(DicomSeries, SlicesAreSortedByPositionRescaledAndOriented) {
  const fs::path dir = write_small_series("sorted");
  std::ofstream(dir / "README.txt") << "not DICOM";  // skipped
  const DicomVolume v = read_dicom_series(dir.string());
  const GridGeometry& g = v.intensity.geometry;
  EXPECT_EQ(g.dims, (std::array<int, 3>{3, 2, 4}));
  EXPECT_TRUE(g.spacing.isApprox(Eigen::Vector3d(0.5, 0.7, 2.5))) << g.spacing.transpose();
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) EXPECT_EQ(v.intensity(i, j, k), 2.0f * (i + 10 * j + 100 * k) - 1000) << i << j << k;
  EXPECT_EQ(v.anterior, "-y");  // LPS: columns run posterior
  EXPECT_EQ(v.superior, "+z");
  EXPECT_TRUE(g.origin.isApprox(Eigen::Vector3d::Zero())) << g.origin.transpose();  // the lowest slice's, not a.dcm's
  EXPECT_EQ(v.gantry_tilt_degrees, 0);

  // read_ct_volume takes that orientation unless told another.
  const CtVolume automatic = read_ct_volume(dir.string());
  const CtVolume stated = read_ct_volume(dir.string(), {"-y", "+z"});
  const CtVolume wrong = read_ct_volume(dir.string(), {"+y", "+z"});
  EXPECT_EQ(automatic.intensity.data, stated.intensity.data);
  EXPECT_NE(automatic.intensity.data, wrong.intensity.data);
}

TEST(DicomSeries, SeveralSeriesInOneFolderAreAnErrorListingThemUnlessOneIsNamed) {
  const fs::path dir = write_small_series("mixed");
  SliceSpec localizer;
  localizer.series_uid = "1.2.826.0.1.3680043.9.7777.2";
  localizer.description = "localizer";
  write_slice((dir / "scout.dcm").string(), localizer, std::vector<std::int16_t>(6, 5));
  const std::vector<DicomSeries> series = dicom_series_in(dir.string());
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].files.size(), 4u);  // largest first
  EXPECT_EQ(series[1].description, "localizer");
  try {
    read_ct_volume(dir.string());
    FAIL() << "mixed series accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), dir.string());
    const std::string message = e.what();
    EXPECT_NE(message.find("2 DICOM series"), std::string::npos) << message;
    EXPECT_NE(message.find("2: 1 files of series 1.2.826.0.1.3680043.9.7777.2 (localizer)"), std::string::npos)
        << message;
    EXPECT_NE(message.find("--series"), std::string::npos) << message;
  }
  // Named by number or by UID, a series is read alone.
  EXPECT_EQ(read_dicom_series(dir.string(), "1").intensity.geometry.dims, (std::array<int, 3>{3, 2, 4}));
  const DicomVolume scout = read_dicom_series(dir.string(), "1.2.826.0.1.3680043.9.7777.2");
  EXPECT_EQ(scout.intensity.geometry.dims, (std::array<int, 3>{3, 2, 1}));
  EXPECT_EQ(scout.intensity.data, std::vector<float>(6, 5.0f));
  EXPECT_EQ(read_ct_volume(dir.string(), {}, "1").intensity.data,
            read_ct_volume(dir.string(), {}, "1.2.826.0.1.3680043.9.7777.1").intensity.data);
  // A series the folder does not hold, or a series named for a file, is an error listing what there is.
  for (const std::string missing : {"3", "1.2.3"}) {
    try {
      read_dicom_series(dir.string(), missing);
      FAIL() << missing;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("no DICOM series '" + missing + "'"), std::string::npos) << message;
      EXPECT_NE(message.find("1: 4 files of series"), std::string::npos) << message;
    }
  }
  EXPECT_THROW(read_ct_volume(default_ct(), {}, "1"), Error);
}

TEST(DicomSeries, UnevenSpacingDuplicatePositionsAndEmptyFoldersAreErrors) {
  const fs::path uneven = write_small_series("uneven");
  SliceSpec far;
  far.position = Eigen::Vector3d(0, 0, 20);
  write_slice((uneven / "e.dcm").string(), far, std::vector<std::int16_t>(6, 1));
  EXPECT_THROW(read_dicom_series(uneven.string()), Error);

  const fs::path duplicate = write_small_series("duplicate");
  SliceSpec again;
  again.position = Eigen::Vector3d(0, 0, 2.5);
  write_slice((duplicate / "e.dcm").string(), again, std::vector<std::int16_t>(6, 1));
  EXPECT_THROW(read_dicom_series(duplicate.string()), Error);

  const fs::path empty = fresh_dir("empty");
  std::ofstream(empty / "notes.txt") << "nothing here";
  try {
    read_ct_volume(empty.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no DICOM image"), std::string::npos) << e.what();
  }
}

// A series acquired with the gantry tilted: axial slices 2.5 mm apart whose origins move one row (0.7 mm) along the
// columns per slice, towards +y or -y. Slice k's pixel (i, j) shows an upright volume's voxel (i, j + k) (or j - k):
// read back, the volume is that upright one on a grid holding every slice (each voxel a slice's pixel, exactly), the
// volume's lowest value where no slice reaches, and the tilt is atan(0.7 / 2.5).
TEST(DicomSeries, AGantryTiltedSeriesIsResampledOntoAnUprightGrid) {
  constexpr int kSlices = 4, kRows = 3;
  const auto upright = [](int i, int j, int k) { return static_cast<float>(2 * (i + 10 * j + 100 * k) - 1000); };
  for (const int direction : {1, -1}) {
    const fs::path dir = fresh_dir("tilted" + std::to_string(direction + 1));
    for (int k = 0; k < kSlices; ++k) {
      SliceSpec s;
      s.ny = kRows;
      s.slope = 2;
      s.intercept = -1000;
      s.position = Eigen::Vector3d(0, direction * k * 0.7, k * 2.5);
      std::vector<std::int16_t> raw;
      for (int j = 0; j < s.ny; ++j)
        for (int i = 0; i < s.nx; ++i)
          raw.push_back(static_cast<std::int16_t>(i + 10 * (j + direction * k + 10) + 100 * k));
      write_slice((dir / ("s" + std::to_string(k) + ".dcm")).string(), s, raw);
    }
    const DicomVolume v = read_dicom_series(dir.string());
    const GridGeometry& g = v.intensity.geometry;
    EXPECT_NEAR(v.gantry_tilt_degrees, std::atan2(3 * 0.7, 3 * 2.5) * 180 / M_PI, 1e-6) << direction;
    ASSERT_EQ(g.dims, (std::array<int, 3>{3, kRows + kSlices - 1, kSlices})) << direction;
    EXPECT_NEAR(g.origin.y(), direction > 0 ? 0 : -(kSlices - 1) * 0.7, 1e-9) << direction;
    const float lowest = *std::min_element(v.intensity.data.begin(), v.intensity.data.end());
    for (int k = 0; k < kSlices; ++k)
      for (int j = 0; j < g.dims[1]; ++j)
        for (int i = 0; i < 3; ++i) {
          // The grid's row j lies at y = origin + 0.7 j: slice k's row j - (direction k) from its own origin.
          const double y = g.origin.y() + 0.7 * j;
          const int row = static_cast<int>(std::lround((y - direction * k * 0.7) / 0.7));
          const float expected = row >= 0 && row < kRows ? upright(i, std::lround(y / 0.7) + 10, k) : lowest;
          EXPECT_EQ(v.intensity(i, j, k), expected) << direction << ": " << i << " " << j << " " << k;
        }
  }
}

// The bundled CT written as a DICOM series the way scanners store axial slices (LPS: rows towards the patient's left,
// columns towards posterior; the segmentation frame's +x is the patient's right, +y anterior), one file per slice in
// reverse name order, reads back as the same volume in the segmentation frame: the orientation comes from the files,
// not from an option.
TEST(DicomSeries, BundledCtAsADicomSeriesReadsBackAsTheSameVolume) {
  const CtVolume ct = read_ct_volume(default_ct());
  const GridGeometry& g = ct.intensity.geometry;
  const fs::path dir = fresh_dir("bundled");
  write_bundled_series(dir, [](int) { return 0; });
  const CtVolume back = read_ct_volume(dir.string());
  EXPECT_EQ(back.intensity.geometry.dims, g.dims);
  EXPECT_TRUE(back.intensity.geometry.spacing.isApprox(g.spacing, 1e-6));
  EXPECT_EQ(back.intensity.data, ct.intensity.data);
  // Each voxel lies at its slice's patient position: column i at LPS x = i * spacing (the writer's column i holds our
  // x = nx - 1 - i), row j at y = j * spacing; so the patient's left is at -x of the segmentation frame.
  const GridGeometry& b = back.intensity.geometry;
  for (const std::array<int, 3>& v : {std::array<int, 3>{0, 0, 0}, {g.dims[0] - 1, 5, 7}, {3, g.dims[1] - 1, 2}}) {
    const Eigen::Vector3d lps((g.dims[0] - 1 - v[0]) * g.spacing(0), (g.dims[1] - 1 - v[1]) * g.spacing(1),
                              g.origin(2) + v[2] * g.spacing(2));
    EXPECT_TRUE(back.scan_frame.to_scan(b.point(v[0], v[1], v[2])).isApprox(lps, 1e-9))
        << back.scan_frame.to_scan(b.point(v[0], v[1], v[2])).transpose() << " vs " << lps.transpose();
  }
  EXPECT_TRUE(back.scan_frame.left_at_minus_x());
}

// The bundled CT as that LPS series, segmented: the model carries its scan frame through a .vtu file, and its
// landmarks are written where a DICOM viewer shows the series (the segmentation frame's (x, y, z) at LPS (-x, -y, z),
// the series' positions starting at x = y = 0), with the patient's sides: the eye and mouth corners at the model's +x
// lie at the patient's right. Read back onto the model, the files give the model's landmarks.
TEST(DicomSeries, ASegmentedSeriesWritesItsLandmarksInThePatientsFrameAndSides) {
  const fs::path dir = fresh_dir("landmarks");
  write_bundled_series(dir, [](int) { return 0; });
  const PatientTetModel model = load_patient_model(dir.string());
  const std::string vtu = (dir / "model.vtu").string();
  write_volume_mesh(vtu, model.mesh);
  const VolumeMesh read = read_volume_mesh(vtu);
  const ScanFrame frame = scan_frame(read, vtu);
  EXPECT_TRUE(frame.rotation.isApprox(Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix(), 1e-12));
  EXPECT_TRUE(frame.translation.isZero(1e-9)) << frame.translation.transpose();
  const FaceLandmarks found = find_face_landmarks(read.V, side_mask_of(read), landmark_options_for(read, vtu));
  ASSERT_TRUE(found.points.count("exocanthion left") && found.points.count("cheilion left"));
  const std::vector<NamedLandmark> named = named_landmarks(found);
  for (const std::string file : {"l.mrk.json", "l.json"}) {
    const std::string path = (dir / file).string();
    write_landmark_file(path, named, found.scan_frame);
    std::ifstream in(path);
    const nlohmann::json doc = nlohmann::json::parse(in);
    const bool slicer = file == "l.mrk.json";
    std::map<std::string, Eigen::Vector3d> written;
    for (const nlohmann::json& p : slicer ? doc["markups"][0]["controlPoints"] : doc["landmarks"])
      written[p[slicer ? "label" : "name"].get<std::string>()] = Eigen::Vector3d(
          p["position"][0].get<double>(), p["position"][1].get<double>(), p["position"][2].get<double>());
    for (const auto& [name, x] : found.points) {
      const std::string side = name.find(" left") != std::string::npos    ? "left"
                               : name.find(" right") != std::string::npos ? "right"
                                                                          : "";
      std::string patient_name = name;
      if (!side.empty())
        patient_name.replace(name.size() - side.size(), side.size(), side == "left" ? "right" : "left");
      ASSERT_TRUE(written.count(patient_name)) << file << ": " << patient_name;
      const Eigen::Vector3d expected = slicer ? Eigen::Vector3d(-x.x(), -x.y(), x.z()) : x;
      EXPECT_TRUE(written.at(patient_name).isApprox(expected, 1e-6)) << file << ": " << name;
    }
    const std::vector<NamedLandmark> back = read_landmark_file(path, frame);
    ASSERT_EQ(back.size(), named.size());
    for (size_t i = 0; i < back.size(); ++i) {
      EXPECT_EQ(back[i].name, named[i].name);
      EXPECT_TRUE(back[i].position.isApprox(named[i].position, 1e-9)) << back[i].name;
    }
  }
}

// The bundled CT's slices moved forward by a row every fourth slice (a gantry tilt of atan(3.2 / 6)): segmented from
// the folder, its cuts and model are those of the same CT written upright, and the summary says it was resampled.
TEST(DicomSeries, TheBundledCtWithItsSlicesShearedIsSegmentedAsUpright) {
  const auto every_fourth = [](int k) { return k / 4; };
  const fs::path sheared_dir = fresh_dir("sheared"), upright_dir = fresh_dir("upright");
  write_bundled_series(sheared_dir, every_fourth);
  write_bundled_series(upright_dir, [](int) { return 0; });
  const PatientTetModel sheared = load_patient_model(sheared_dir.string());
  const PatientTetModel upright = load_patient_model(upright_dir.string());
  ASSERT_TRUE(sheared.segmentation && upright.segmentation);
  const GridGeometry& g = read_ct_volume(default_ct()).intensity.geometry;
  EXPECT_NEAR(sheared.segmentation->gantry_tilt_degrees,
              std::atan2(every_fourth(g.dims[2] - 1) * g.spacing(1), (g.dims[2] - 1) * g.spacing(2)) * 180 / M_PI,
              1e-6);
  EXPECT_EQ(upright.segmentation->gantry_tilt_degrees, 0);
  EXPECT_NE(segmentation_summary(*sheared.segmentation).find("resampled upright from a gantry tilt"),
            std::string::npos);
  const FaceCuts &a = sheared.segmentation->cuts, &b = upright.segmentation->cuts;
  EXPECT_NEAR(a.top_z, b.top_z, 0.5);
  EXPECT_NEAR(a.bottom_z, b.bottom_z, 0.5);
  EXPECT_NEAR(a.centre_x, b.centre_x, 0.5);
  EXPECT_NEAR(a.posterior_y, b.posterior_y, 0.5);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(sheared.mesh.V.col(axis).minCoeff(), upright.mesh.V.col(axis).minCoeff(), 0.5) << axis;
    EXPECT_NEAR(sheared.mesh.V.col(axis).maxCoeff(), upright.mesh.V.col(axis).maxCoeff(), 0.5) << axis;
  }
}

}  // namespace
}  // namespace facehex
