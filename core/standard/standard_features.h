#pragma once
// The standard's facial features as its own vertices, so that where a transfer puts them can be measured: the rims
// of its openings, named by where they lie against its landmarks, and its landmarks' vertices.
//
// Rims: the walls on no side (eyes, nostrils, mouth left open in a hex standard; closed_domain.h
// sideless_boundary_pieces) are grouped by name, from where each piece's centroid lies: "eye at -x" and "eye at +x"
// above the pronasale (5 mm and more), "nostril at -x" and "nostril at +x" down to 4 mm below the subnasale, "mouth"
// within 12 mm of the stomion's height, "opening N" otherwise; a rim's vertices are its walls' vertices on the skin
// or bone side. Landmarks: find_face_landmarks on the standard's skin with its openings' skin rims
// (LandmarkOptions::opening_rims), so that the corners of its open eyes and mouth are its rims' ends (the right eye's
// exocanthion and endocanthion, the left eye's endocanthion and exocanthion, the mouth's right and left cheilion).
// Landmark vertices: the skin vertex nearest each landmark (a rim's end is its own vertex).
#include <map>
#include <string>
#include <vector>

#include "core/face/face_landmarks.h"
#include "core/mesh/mesh.h"

namespace facehex {

struct StandardFeatures {
  FaceLandmarks landmarks;                       // found on the standard's skin and at its rims' ends
  std::map<std::string, std::vector<int>> rims;  // by name ("eye at -x", ...), sorted vertex ids
  std::map<std::string, int> landmark_vertices;  // by landmark name (core/face/landmark_file.h)
};

// standard: hex-dominant, point data "side_mask". Throws facehex::Error("landmarks", ...) when its landmarks cannot be
// found.
StandardFeatures standard_features(const VolumeMesh& standard);

}  // namespace facehex
