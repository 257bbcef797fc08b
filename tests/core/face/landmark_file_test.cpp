#include "core/face/landmark_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "core/face/face_landmarks.h"
#include "core/util/error.h"
#include "tests/core/io/io_test_util.h"

namespace facehex {
namespace {
namespace fs = std::filesystem;

std::string scratch(const std::string& name) { return (test::program_scratch_dir() / name).string(); }

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = scratch(name);
  std::ofstream(path) << text;
  return path;
}

const std::vector<NamedLandmark> kSet = {{"pronasale", {1.25, 2.5, -3.75}, LandmarkStatus::estimated},
                                         {"glabella", {0, 100, 200}, LandmarkStatus::found},
                                         {"tragus left", {-70.125, 0.5, 1e-3}, LandmarkStatus::given}};

TEST(LandmarkFile, RoundTripsBothFormats) {
  for (const char* name : {"set.json", "set.mrk.json"}) {
    const std::string path = scratch(name);
    write_landmark_file(path, kSet);
    const std::vector<NamedLandmark> back = read_landmark_file(path);
    ASSERT_EQ(back.size(), kSet.size()) << name;
    for (std::size_t i = 0; i < kSet.size(); ++i) {
      EXPECT_EQ(back[i].name, kSet[i].name) << name;
      EXPECT_EQ(back[i].position, kSet[i].position) << name;  // exact: JSON keeps doubles
      EXPECT_EQ(back[i].status, kSet[i].status) << name;
    }
  }
}

TEST(LandmarkFile, ReadsSlicerRasAsLps) {
  const std::string path = write_text("ras.mrk.json", R"({"markups": [{"type": "Fiducial", "coordinateSystem": "RAS",
    "controlPoints": [{"label": "nasion", "position": [1, -2, 3]}]}]})");
  const std::vector<NamedLandmark> l = read_landmark_file(path);
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].position, Eigen::Vector3d(-1, 2, 3));
  EXPECT_EQ(l[0].status, LandmarkStatus::given);
}

TEST(LandmarkFile, EveryMalformedFileNamesTheFileAndTheProblem) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{ not json", "not valid JSON"},
      {"[1, 2]", "one JSON object"},
      {R"({"landmarks": []})", "facehex-landmarks"},
      {R"({"format": "facehex-landmarks", "landmarks": {}})", "must be a list"},
      {R"({"format": "facehex-landmarks", "landmarks": []})", "holds no landmark"},
      {R"({"format": "facehex-landmarks", "units": "cm", "landmarks": []})", "units"},
      {R"({"format": "facehex-landmarks", "landmarks": [{"position": [0, 0, 0]}]})", "needs a \"name\""},
      {R"({"format": "facehex-landmarks", "landmarks": [{"name": "nose", "position": [0, 0, 0]}]})",
       "unknown landmark 'nose'"},
      {R"({"format": "facehex-landmarks", "landmarks": [{"name": "nasion"}]})", "has no \"position\""},
      {R"({"format": "facehex-landmarks", "landmarks": [{"name": "nasion", "position": [0, 0]}]})", "three numbers"},
      {R"({"format": "facehex-landmarks", "landmarks": [{"name": "nasion", "position": [0, "a", 0]}]})",
       "three numbers"},
      {R"({"format": "facehex-landmarks", "landmarks": [{"name": "nasion", "position": [0, 0, 0], "status": "maybe"}]})",
       "unknown status 'maybe'"},
      {R"({"format": "facehex-landmarks", "landmarks": [{"name": "nasion", "position": [0, 0, 0]},
          {"name": "nasion", "position": [1, 1, 1]}]})",
       "given twice"}};
  int n = 0;
  for (const auto& [text, words] : cases) {
    const std::string path = write_text("bad" + std::to_string(n++) + ".json", text);
    try {
      read_landmark_file(path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.subject(), path);
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
  const std::vector<std::pair<std::string, std::string>> slicer = {
      {R"({"markups": []})", "no \"markups\" list"},
      {R"({"markups": [{"type": "Line", "controlPoints": []}]})", "only Fiducial"},
      {R"({"markups": [{"type": "Fiducial", "coordinateSystem": "IJK", "controlPoints": []}]})", "LPS or RAS"},
      {R"({"markups": [{"type": "Fiducial", "coordinateUnits": "um", "controlPoints": []}]})", "coordinateUnits"},
      {R"({"markups": [{"type": "Fiducial"}]})", "no \"controlPoints\""},
      {R"({"markups": [{"type": "Fiducial", "controlPoints": [{"position": [0, 0, 0]}]}]})", "\"label\""}};
  for (const auto& [text, words] : slicer) {
    const std::string path = write_text("bad" + std::to_string(n++) + ".mrk.json", text);
    try {
      read_landmark_file(path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_EQ(e.subject(), path);
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(read_landmark_file(scratch("absent.json")), Error);
}

// A plausible adult profile (mm, z up), then each fact of check_plausible broken once.
FaceLandmarks adult() {
  FaceLandmarks l;
  l.points = {
      {"glabella", {0, 95, 140}},         {"nasion", {0, 92, 128}},           {"pronasale", {0, 115, 98}},
      {"subnasale", {0, 100, 78}},        {"labrale superius", {0, 103, 65}}, {"stomion", {0, 99, 59}},
      {"labrale inferius", {0, 101, 53}}, {"pogonion", {0, 100, 30}},         {"menton", {0, 85, 12}},
      {"cheilion left", {25, 95, 58}},    {"cheilion right", {-25, 95, 58}},  {"endocanthion left", {15, 85, 122}}};
  return l;
}

void expect_implausible(FaceLandmarks l, const std::string& landmark) {
  try {
    check_plausible(l, "give them with --landmarks FILE");
    ADD_FAILURE() << "accepted an implausible " << landmark;
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), "landmarks");
    EXPECT_NE(std::string(e.what()).find("implausible " + landmark), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--landmarks FILE"), std::string::npos) << e.what();
  }
}

TEST(LandmarkPlausibility, AnAdultFacePassesAndEachBrokenFactNamesItsLandmark) {
  EXPECT_NO_THROW(check_plausible(adult(), ""));
  FaceLandmarks l = adult();
  l.points["stomion"].z() = 70;  // above the upper lip
  expect_implausible(l, "stomion");
  l = adult();
  l.points["subnasale"].z() = 118;  // 10 mm below the nasion: out of order with the pronasale too
  expect_implausible(l, "subnasale");
  l = adult();
  l.points.erase("pronasale");
  l.points["subnasale"].z() = 120;  // in order, but a nose 8 mm tall
  l.points["labrale superius"].z() = 110;
  expect_implausible(l, "subnasale");
  l = adult();
  // The profile read 15-20 mm too high below the nose (a field-of-view cut of the nose not recognised on a warped CT):
  // each landmark in order, the chin's and the mouth corners not found, but a nose 37 mm tall.
  for (const char* name : {"pogonion", "menton", "cheilion left", "cheilion right"}) l.points.erase(name);
  l.points["subnasale"].z() = 92;
  l.points["labrale superius"].z() = 84;
  l.points["stomion"].z() = 78;
  l.points["labrale inferius"].z() = 65;
  expect_implausible(l, "subnasale");
  l = adult();
  l.points["menton"].z() = -30;  // lower face 108 mm
  expect_implausible(l, "menton");
  l = adult();
  l.points["cheilion left"].x() = 80;  // mouth 105 mm wide
  expect_implausible(l, "cheilion");
  l = adult();
  l.points["endocanthion left"].z() = 50;  // below the mouth corners
  expect_implausible(l, "endocanthion left");
  l = adult();
  l.points["cheilion left"].y() = std::numeric_limits<double>::quiet_NaN();  // no distance compares false with it
  expect_implausible(l, "cheilion left");
}

TEST(LandmarkPlausibility, NamedLandmarksKeepTheirStatus) {
  FaceLandmarks l = adult();
  l.estimated = {"pronasale"};
  const std::vector<NamedLandmark> named = named_landmarks(l);
  ASSERT_EQ(named.size(), l.points.size());
  EXPECT_EQ(named.front().name, "glabella");  // landmark_names() order
  for (const NamedLandmark& n : named)
    EXPECT_EQ(n.status, n.name == "pronasale" ? LandmarkStatus::estimated : LandmarkStatus::found) << n.name;
  const FaceLandmarks given = landmarks_from(named, "file.json");
  EXPECT_TRUE(given.given);
  EXPECT_EQ(given.plane.x, 0);
  for (const NamedLandmark& n : named_landmarks(given)) EXPECT_EQ(n.status, LandmarkStatus::given);
  std::vector<NamedLandmark> missing = named;
  missing.erase(
      std::remove_if(missing.begin(), missing.end(), [](const NamedLandmark& n) { return n.name == "stomion"; }),
      missing.end());
  try {
    landmarks_from(missing, "file.json");
    ADD_FAILURE() << "accepted a set without the stomion";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), "file.json");
    EXPECT_NE(std::string(e.what()).find("'stomion'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace facehex
