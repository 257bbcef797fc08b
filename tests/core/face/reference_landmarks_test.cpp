// The automatic landmarks against the ones placed by hand (tests/data/landmarks/README.md) on the two real CTs: the
// bundled 3.2 mm one (its patient model, resources/patients/headsq) and the 1 mm Visible Human Female (the skin of its
// models at 2 mm and at the default edge length, stored as points, so that the test needs neither ../shared nor a
// minute of segmentation); also the bundled
// CT's model meshed coarsely (4.2 mm edges, stored as points too). Tolerances: 2 mm on the 1 mm CT, 3 mm on the
// 3.2 mm one, 5 mm for a landmark inside a field-of-view cut (which must then be marked estimated). Landmarks the
// finder does not place on the skin are only in the reference: the eye corners, and the tragi, which the
// segmentation finds in the CT (core/segment/tragus.h; tested on the bundled CT in
// SoftTissue.RealCtMakesASixSidedModel).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/face/face_landmarks.h"
#include "core/face/landmark_file.h"
#include "core/fields/constraint_set.h"
#include "core/io/mesh_io.h"
#include "core/mesh/head_turn.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/mesh/sides.h"
#include "core/util/error.h"
#include "core/util/resources.h"

namespace facehex {
namespace {

const std::string kData = std::string(FACEHEX_TEST_DATA_DIR) + "/landmarks/";

// coarsening: mm added to both bounds for a model meshed coarser than the scan, half its edge length (its skin
// vertices, where the landmarks are found, sample the face that much more sparsely). wider: bounds of named landmarks
// that the model's surface, not the finder, keeps from the reference.
void expect_near_reference(const FaceLandmarks& found, const std::string& reference_file, double tolerance,
                           std::size_t at_least, double coarsening = 0,
                           const std::map<std::string, double>& wider = {}) {
  std::size_t compared = 0;
  for (const NamedLandmark& ref : read_landmark_file(reference_file)) {
    const auto p = found.points.find(ref.name);
    if (p == found.points.end()) continue;
    const bool estimated = std::find(found.estimated.begin(), found.estimated.end(), ref.name) != found.estimated.end();
    const bool in_cut = ref.status == LandmarkStatus::estimated;
    EXPECT_EQ(estimated, in_cut) << ref.name;
    const double bound = wider.count(ref.name) ? wider.at(ref.name) : in_cut ? 5.0 : tolerance;
    EXPECT_LE((p->second - ref.position).norm(), bound + coarsening)
        << ref.name << " found at " << p->second.transpose() << ", placed at " << ref.position.transpose();
    ++compared;
  }
  EXPECT_GE(compared, at_least);
}

// The skin (side w1) vertices stored as "x y z" lines (tests/data/landmarks/README.md), all labelled skin, and the
// model's mid-sagittal plane where a comment line "# mid_sagittal_plane X SLOPE Z [TURN Y]" gives it.
struct SkinPoints {
  Eigen::MatrixXd V;
  Eigen::VectorXi side_mask;
  LandmarkOptions options;
};
SkinPoints read_skin_points(const std::string& file) {
  std::ifstream in(file);
  EXPECT_TRUE(in) << file;
  std::vector<Eigen::Vector3d> points;
  SkinPoints skin;
  const std::string plane = std::string("# ") + kMidSagittalPlaneField + " ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(plane, 0) == 0) {
      std::istringstream values(line.substr(plane.size()));
      MidSagittalPlane p;
      values >> p.x >> p.slope >> p.z;
      if (!(values >> p.turn >> p.y)) p.turn = 0, p.y = 0;
      skin.options.mid_sagittal_plane = p;
    }
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    Eigen::Vector3d p;
    s >> p.x() >> p.y() >> p.z();
    points.push_back(p);
  }
  skin.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) skin.V.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  skin.side_mask = Eigen::VectorXi::Constant(skin.V.rows(), side_bit(W1));
  return skin;
}

TEST(ReferenceLandmarks, BundledCtWithinThreeMillimetres) {
  const VolumeMesh model = read_volume_mesh(resource_dir() + "/patients/headsq/patient.vtu");
  const FaceLandmarks found = find_face_landmarks(model.V, side_mask_of(model));
  EXPECT_FALSE(std::isnan(found.clipped_from));  // its nose and brow are cut flat
  // glabella, nasion, pronasale (estimated), subnasale, the lips, stomion, the mouth corners.
  expect_near_reference(found, kData + "headsq.json", 3.0, 9);
}

TEST(ReferenceLandmarks, BundledCtMeshedCoarselyKeepsItsCut) {
  // The model `facehex bench --edge-length 4.2` makes: 4 mm between the profile's vertices, so several empty 1 mm
  // bins in a row on the field-of-view cut, which must still be found as one (else the nose tip is taken high on the
  // cut and every lip landmark one turn too high).
  const SkinPoints skin = read_skin_points(kData + "headsq-edge4.2-skin.xyz");
  const FaceLandmarks found = find_face_landmarks(skin.V, skin.side_mask);
  EXPECT_FALSE(std::isnan(found.clipped_from));
  EXPECT_NO_THROW(check_plausible(found, "test"));
  expect_near_reference(found, kData + "headsq.json", 3.0, 9, 4.2 / 2);
}

TEST(ReferenceLandmarks, VisibleHumanFemaleWithinTwoMillimetres) {
  const SkinPoints skin = read_skin_points(kData + "vhfemale-head-skin.xyz");
  const FaceLandmarks found = find_face_landmarks(skin.V, skin.side_mask);
  EXPECT_NO_THROW(check_plausible(found, "test"));
  // glabella, nasion, pronasale (estimated: the nose tip is cut), subnasale, the lips, stomion, pogonion, menton, the
  // mouth corners.
  expect_near_reference(found, kData + "vhfemale-head.json", 2.0, 11);
}

TEST(ReferenceLandmarks, VisibleHumanFemaleDefaultModelWithItsPlane) {
  // A model `facehex segment` made of the 1 mm CT by default (2.5 mm edges, the cuts of 85af599: the data's README)
  // with the CT's mid-sagittal plane, as `facehex run CT` finds its landmarks. This head is turned by a few degrees in
  // the scanner (its left eye and mouth corners and tragus lie 4-9 mm in front of the right ones), the plane with it;
  // the reference's profile landmarks lie on one sagittal slice, which crosses the turned plane near the chin. Wider
  // bounds where the model's surface differs from the CT's skin: it bridges the closed lips' groove (the stomion lies
  // in front of the CT's by about 2 mm at the same height), and the mouth line traced on it ends further out and lower
  // than the left corner placed on the CT.
  const SkinPoints skin = read_skin_points(kData + "vhfemale-head-default-skin.xyz");
  ASSERT_TRUE(skin.options.mid_sagittal_plane);
  EXPECT_LT(skin.options.mid_sagittal_plane->turn, std::tan(-2 * M_PI / 180));
  const FaceLandmarks found = find_face_landmarks(skin.V, skin.side_mask, skin.options);
  EXPECT_EQ(found.plane.x, skin.options.mid_sagittal_plane->x);
  EXPECT_NO_THROW(check_plausible(found, "test"));
  expect_near_reference(found, kData + "vhfemale-head.json", 2.0, 11, 0, {{"stomion", 2.5}, {"cheilion left", 3.0}});
}

TEST(ReferenceLandmarks, VisibleHumanFemaleOnTheCtsSkinPoints) {
  // What `facehex run CT` reads the face from: the skin points the segmentation stores with its model
  // (core/mesh/skin_points.h), the skin side of its surface at the 1 mm working spacing before the remeshing, here
  // within 60 mm of the plane and 50 mm of the front. The same landmarks at every edge length, and the remeshed
  // skin's mouth line no longer ends 4.7 mm from the right corner. Wider bounds as above: the working spacing's
  // surface too bridges the closed lips' groove in front of the CT's skin at the stomion, and the mouth line traced
  // on it ends lower than the left corner placed on the CT.
  const SkinPoints points = read_skin_points(kData + "vhfemale-head-ct-skin.xyz");
  LandmarkOptions options = points.options;
  options.skin_points = points.V;
  // The model's own skin vertices are not read when it carries the skin points.
  const SkinPoints remeshed = read_skin_points(kData + "vhfemale-head-default-skin.xyz");
  const FaceLandmarks found = find_face_landmarks(remeshed.V, remeshed.side_mask, options);
  const FaceLandmarks on_points = find_face_landmarks(points.V, points.side_mask, points.options);
  for (const auto& [name, p] : on_points.points) EXPECT_EQ(found.points.at(name), p) << name;
  EXPECT_NO_THROW(check_plausible(found, "test"));
  expect_near_reference(found, kData + "vhfemale-head.json", 2.0, 11, 0, {{"stomion", 2.5}, {"cheilion left", 2.5}});
}

TEST(ReferenceLandmarks, VisibleHumanFemalePitchedIsReadInTheFrameItsPlaneCarries) {
  // The same skin points with the head pitched (its chin raised 15 degrees, lowered 15) about its own lateral axis
  // (this head is turned by a few degrees, so that its pitch mixes with the turn) through its plane's point, and the
  // plane pitched with them: against the hand-placed landmarks pitched with the head, the bounds of the upright head.
  // Read without the pitch, some landmark falls outside them.
  const SkinPoints points = read_skin_points(kData + "vhfemale-head-ct-skin.xyz");
  const MidSagittalPlane& plane = *points.options.mid_sagittal_plane;
  const std::map<std::string, double> wider = {{"stomion", 2.5}, {"cheilion left", 2.5}};
  for (const double pitch : {15.0, -15.0}) {
    const HeadTurn upright = head_turn_of(plane);
    HeadTurn pitched = upright;
    pitched.pitch = pitch;
    const auto moved = [&](const Eigen::Vector3d& p) { return pitched.to_model(upright.to_head(p)); };
    Eigen::MatrixXd V(points.V.rows(), 3);
    for (Eigen::Index v = 0; v < V.rows(); ++v) V.row(v) = moved(points.V.row(v).transpose()).transpose();
    LandmarkOptions options;
    options.mid_sagittal_plane = pitched.to_model(upright.to_head(plane));
    EXPECT_EQ(options.mid_sagittal_plane->pitch, pitch);
    const auto worst_excess = [&](const FaceLandmarks& found) {
      double worst = -std::numeric_limits<double>::infinity();
      std::size_t compared = 0;
      for (const NamedLandmark& ref : read_landmark_file(kData + "vhfemale-head.json")) {
        const auto p = found.points.find(ref.name);
        if (p == found.points.end()) continue;
        const double bound = ref.status == LandmarkStatus::estimated ? 5.0
                             : wider.count(ref.name)                 ? wider.at(ref.name)
                                                                     : 2.0;
        worst = std::max(worst, (p->second - moved(ref.position)).norm() - bound);
        ++compared;
      }
      EXPECT_GE(compared, 11u) << pitch;
      return worst;
    };
    const FaceLandmarks found = find_face_landmarks(V, points.side_mask, options);
    EXPECT_NO_THROW(check_plausible(found, "test")) << pitch;
    EXPECT_LE(worst_excess(found), 0.0) << pitch;
    LandmarkOptions unpitched = options;
    unpitched.mid_sagittal_plane->pitch = 0;
    try {
      EXPECT_GT(worst_excess(find_face_landmarks(V, points.side_mask, unpitched)), 0.0) << pitch;
    } catch (const Error&) {
      // not found at all: as wrong
    }
  }
}

TEST(ReferenceLandmarks, PointsOnWholeMillimetresFallInOneBinHoweverTheyAreRounded) {
  // A third of the skin points lie on whole millimetres of the working grid (iso-surface vertices on its edges). Moved
  // by a nanometre either way, as a change of frame rounds them, they must find the same landmarks: the 1 mm bins take
  // a point on their edge to the bin above (core/face/millimetre_bins.h), where it would otherwise flip a whole plane
  // of points into the bin below and move a landmark by most of a millimetre.
  const SkinPoints points = read_skin_points(kData + "vhfemale-head-ct-skin.xyz");
  Eigen::MatrixXd rounded = points.V;
  int on_whole_millimetres = 0;
  for (Eigen::Index i = 0; i < rounded.size(); ++i) {
    const double x = rounded.data()[i];
    if (x != std::round(x)) continue;
    ++on_whole_millimetres;
    rounded.data()[i] = x + (i % 2 ? 1e-9 : -1e-9);
  }
  EXPECT_GT(on_whole_millimetres, points.V.rows() / 4);
  const FaceLandmarks found = find_face_landmarks(points.V, points.side_mask, points.options);
  const FaceLandmarks again = find_face_landmarks(rounded, points.side_mask, points.options);
  ASSERT_EQ(again.points.size(), found.points.size());
  for (const auto& [name, p] : found.points) EXPECT_LT((again.points.at(name) - p).norm(), 1e-6) << name;
}

}  // namespace
}  // namespace facehex
