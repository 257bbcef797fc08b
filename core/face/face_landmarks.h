#pragma once
// Facial landmarks from the skin surface of a model (standard or patient) and the feature constraints built on them
// (paper 3.4: mid-sagittal line, eyebrow line, below-nose line, middle lip line).
//
// Frame: +x lateral, +y anterior (the face looks to +y), +z superior. The skin is the model's w1 side (side_mask).
//  - mid-sagittal plane x = plane.x_at(y, z): the model's own when it carries one (a segmented CT's, LandmarkOptions,
//    leaning with a head tilted towards a shoulder), else the skin's vertical mirror plane (the median over 2 mm rows
//    of z of the plane that best mirrors the row's front, core/util/mirror_symmetry.h), searched near the most
//    anterior point within 20 mm of the middle of the skin's x range (looked for as the nose tip is, below);
//  - the profile: for 1 mm bins of z, the most anterior skin point within `profile_band` of the plane, moved onto it
//    (a band wider than the philtrum's groove would catch its ridges);
//  - pronasale (nose tip): the most anterior profile point in the middle 80 % of the z range, or above its lowest 30 %
//    when that point lies lower (a chin in front of a nose the field of view clipped, a head pitched chin-up: no
//    face's nose tip lies so low);
//    the lips below it, from the profile's turns within 50 mm below the nose: the points its Douglas-Peucker
//    simplification keeps (at 1.5 mm, else at 1 or 0.5 mm if that shows fewer than the four), each a hollow if it lies
//    behind the chord of its kept neighbours, else a prominence (runs of one kind reduced to the deepest or most
//    anterior). After any prominence on the nose's own underside: the first hollow (the subnasale's), then labrale
//    superius (the next prominence), stomion (the next hollow, lip contact or the middle of an open mouth) and labrale
//    inferius (the next prominence); a hollow and prominence pair less than 10 mm above the next hollow is a ripple
//    under the nose (no upper lip is so short) and the lips are read below it. Turns measured against chords, not
//    windows of fixed height, keep their order on a longer nose or lip and on a pitched head. labrale superius is then
//    the most anterior point between the hollows either side of its turn (the front of a flat lip, not the corner of
//    its rise). subnasale, the point between the upper lip and the nose deepest behind the chord joining them, moved up
//    to the top of the lip's part as deep within 0.75 mm, depths averaged over three bins (where the columella meets
//    the lip); nasion: the least anterior point from 10 mm above the nose tip up to where the
//    profile comes 2 mm forward of it again (the brow; within 70 mm of the tip, else up to 45 mm); glabella (brow
//    ridge): the middle of the points within 0.5 mm of the most anterior one 3-30 mm above the nasion (a flat brow's
//    centre), or, where the skin ends too close above the nasion to show a brow, the profile's front 12 mm above it
//    (estimated); pogonion (soft-tissue chin): the most anterior point up to 30 mm below the labiomental fold (the
//    first local minimum below the labrale inferius); menton (soft tissue): on a model whose CT gave the bony menton
//    (ct_landmarks), the skin within 3 mm of the plane on the vertical under it (within 1.5 mm in y, up to 25 mm
//    below), nearest the bone, as cephalometry defines it; else the lowest skin point within 3 mm of the plane and 20
//    mm behind the pogonion (the underside of the chin); moved onto the plane, unless it lies on the model's bottom
//    edge.
// A field-of-view cut: when the front of the profile is a plateau (within clipped_depth of its most anterior point;
// bins without a vertex, between the vertices of a coarse model, neither end nor extend it) at least clipped_length
// long, the scan cut the face flat there (a nose drops more than that within 25 mm of its
// tip; a plateau below whose flat front, within clipped_flat_depth, the profile recedes and comes forward again by
// more than 1 mm holds the subnasale and the upper lip, and the cut is that flat front). A cut that leans in the head
// frame (a head pitched in the scanner, whose field of view is level with the scanner) is followed along the line
// fitted to its plateau (leaning up to 15 degrees) when that line's plateau is at least 5 mm longer and the profile
// only recedes between the two plateaus' lower ends (a flat nose's comes forward again at the upper lip). The lips
// and subnasale are found below it as above (the cut's lowest point standing for the nose). When the
// cut ends well below the top of the skin (the nose alone was cut), the pronasale is estimated at the cut's middle and
// the nasion and glabella are found above the cut, unless the nasion found there lies further from the subnasale than
// an adult's (70 mm: the cut reached past it); otherwise the pronasale, nasion and glabella are placed by typical
// adult proportions above the subnasale (15, 55 and 67 mm) on the cut. Placed landmarks are listed in `estimated`.
// Objects on the skin (a strap, thick tape: core/segment/skin_objects.h, carried with the CT's landmarks): the profile
// is read under each, on the skin the CT shows there (moved onto the skin read at the ends of its range); the
// landmarks found there are estimated.
// The mouth corners (cheilion right, left): the ends of the mouth line traced out from the plane under the upper lip
// (core/face/mouth_corners.h); absent where the lips show no such line. The tragi and eye corners: the ones the
// segmentation found in the CT, when the model carries them (LandmarkOptions::ct_landmarks), and its stomion, read in
// the lips' slit, in place of the profile's.
// Then the plausibility check (check_plausible). Every landmark is listed with its status: found, or estimated.
// Each feature constraint pins the chosen field on the skin (and on walls of openings, e.g. the standard's mouth
// slit) near the landmark: v on the horizontal plane through it (horizontal in the head frame of a pitched head, whose
// plane says so), u = 0.5 on the mid-sagittal plane (whole volume).
#include <Eigen/Core>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/face/landmark_file.h"
#include "core/fields/constraint_set.h"
#include "core/mesh/ct_landmarks.h"
#include "core/mesh/mesh.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/mesh/scan_frame.h"

namespace facehex {

struct FaceLandmarks {
  MidSagittalPlane plane;  // the profile's plane, x = plane.x_at(y, z)
  // Where the plane came from: "model" (the model's own, LandmarkOptions), "skin" (the skin's mirror plane) or
  // "given" (through the given pronasale).
  std::string plane_source;
  std::map<std::string, Eigen::Vector3d> points;  // "pronasale", "subnasale", "nasion", "glabella", "stomion", ...
  // Where the profile is clipped flat by the scan's field of view (z range, mm; NaN if it is not), and the landmarks
  // that lie inside the cut and were placed by typical proportions instead of found.
  double clipped_from = std::numeric_limits<double>::quiet_NaN(), clipped_to = clipped_from;
  std::vector<std::string> estimated;
  // Objects lying on the skin's front that the segmentation found in the CT (LandmarkOptions::ct_landmarks): the
  // profile is read under them, and the landmarks there are estimated.
  std::vector<SkinObject> skin_objects;
  bool given = false;  // read from the user's file (landmarks_from), not found
  // The model's scan frame (LandmarkOptions::scan_frame): the points are named by the model's sides (its +x one left),
  // and what the user reads of them (landmarks_text, check_plausible's errors, landmark files) by the patient's.
  ScanFrame scan_frame;
};

struct LandmarkOptions {
  double profile_band = 1.5;     // mm
  double clipped_depth = 3.5;    // mm: profile points this close to the most anterior one are on a front plateau
  double clipped_length = 25.0;  // mm: a front plateau this long is a field-of-view cut, not anatomy
  // mm: a field-of-view cut's flat front, where its plateau holds the lips (a nose clipped back to their level)
  double clipped_flat_depth = 1.5;
  // The mid-sagittal plane when it is known (the CT's, core/segment/face_anatomy.h: the whole head's symmetry reads it
  // better than the skin of the face alone, and its lean too); else the skin's vertical mirror plane.
  std::optional<MidSagittalPlane> mid_sagittal_plane;
  // The skin to read the face from instead of the model's skin vertices, #P x 3 in the model's frame: a segmented
  // CT's, at the segmentation's working spacing (core/mesh/skin_points.h).
  std::optional<Eigen::MatrixXd> skin_points;
  // The tragi, eye corners, stomion and mouth corners the segmentation found in the CT (core/mesh/ct_landmarks.h), in
  // the model's frame: they lie behind a model's posterior cut and in the closed eyes' and lips' slits, where the skin
  // read does not show them.
  std::optional<CtLandmarks> ct_landmarks;
  // Where the model lies in its scan (core/mesh/scan_frame.h), passed on to FaceLandmarks::scan_frame.
  ScanFrame scan_frame;
  // The skin vertices on the rim of each opening of the model (walls on no side: open eyes, nostrils or a mouth, as a
  // hex standard or a face model has them), #R x 3 each, in the model's frame. The mouth's and the eyes' corners are
  // then the ends of the largest such opening of that name (opening_name), as the standard's are
  // (core/standard/standard_features.h), rather than read on the skin beside it, where an open or a plugged mouth
  // misleads the mouth line; the CT's eye corners still win.
  std::vector<Eigen::MatrixXd> opening_rims;
};

// The name of an opening whose rim's centroid is `centroid`, from where it lies against the landmarks: "eye at -x"
// and "eye at +x" 5 mm and more above the pronasale, "nostril at -x" and "nostril at +x" down to 4 mm below the
// subnasale, "mouth" within 12 mm of the stomion's height, "opening N" (index + 1) otherwise.
std::string opening_name(const Eigen::Vector3d& centroid, const FaceLandmarks& landmarks, int index);

// The options for `model`: its own mid-sagittal plane, the CT's skin points and the CT's landmarks when it carries them
// (core/mesh/mid_sagittal_plane.h, core/mesh/skin_points.h, core/mesh/ct_landmarks.h). Throws facehex::Error(source,
// ...) when they are malformed.
LandmarkOptions landmark_options_for(const VolumeMesh& model, const std::string& source);

// V #V x 3, side_mask #V; with options.skin_points the face is read from those points instead (V and side_mask are
// then not used). Throws facehex::Error("landmarks", ...) naming the landmark that cannot be found.
FaceLandmarks find_face_landmarks(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask,
                                  const LandmarkOptions& options = {});

// Adult ranges, each a fact an implausible set breaks: the profile landmarks in order from the top (glabella, nasion,
// pronasale, subnasale, labrale superius, stomion, labrale inferius, pogonion, menton); nasion-subnasale (nose
// height) 38-70 mm; subnasale-menton (lower face height) 45-95 mm and 0.45-0.70 of nasion-menton; glabella 3-35 mm
// above the nasion; mouth width (cheilion to cheilion) 35-85 mm; eye corners above the mouth corners and below the
// glabella, biocular width (exocanthia) 70-120 mm, intercanthal width 20-50 mm, each eye 20-45 mm wide; bitragion
// breadth 110-175 mm, nasion-tragus 80-150 mm, the tragi between the menton and the glabella in height; each paired
// landmark on its side of the mid-sagittal plane (`landmarks.plane`: the model's left ones at +x of it), which a file
// with left and right swapped breaks. Landmarks absent from the set are not checked. Throws facehex::Error("landmarks", ...) naming the landmark and `remedy` (e.g.
// "give them with --landmarks FILE").
void check_plausible(const FaceLandmarks& landmarks, const std::string& remedy);

// The landmarks as named points with their status (found or estimated), in landmark_names() order.
std::vector<NamedLandmark> named_landmarks(const FaceLandmarks& landmarks);
// Landmarks given by the user: the mid-sagittal plane through the given pronasale. Throws facehex::Error(source, ...)
// when a landmark the feature constraints need is missing.
FaceLandmarks landmarks_from(const std::vector<NamedLandmark>& given, const std::string& source);

// One line per landmark, "name at (x, y, z) mm", marked "(estimated)" where placed by proportions or read under an
// object on the skin, after a line per such object (skin_object_text) and one naming the field-of-view cut if there is
// one; each line starts with `indent`.
std::string landmarks_text(const FaceLandmarks& landmarks, const std::string& indent);

// "an object lies on the skin's front from z = 150.0 to 170.0 mm, 4.0 mm thick (a strap or tape): ...".
std::string skin_object_text(const SkinObject& object);

// The names, fields and selection radii of the feature constraints.
struct FeatureSpec {
  std::string name, landmark;
  int field;
  double radius;  // mm around the landmark (0: the whole plane)
};
const std::vector<FeatureSpec>& feature_specs();

// Feature constraints at the landmarks with the given values per feature name (missing names: u = 0.5 for the
// mid-sagittal line; others are required). band: slab width in mm.
ConstraintSet feature_constraints(const FaceLandmarks& landmarks, const std::map<std::string, double>& values,
                                  double band);

}  // namespace facehex
