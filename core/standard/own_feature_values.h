#pragma once
// The feature values of a model's own harmonic fields: what a new standard's constraint set takes, so that its
// feature constraints sit where its side-only fields already put them (`facehex constraints --own-values`).
#include <map>
#include <string>

#include "core/face/face_landmarks.h"
#include "core/mesh/mesh.h"

namespace facehex {

// Each feature's value is the mean of the model's side-only harmonic field (no orthogonality improvement) over the
// vertices the feature selects at the model's landmarks (slabs `band` mm wide); the mid-sagittal line's u is 0.5.
// `model`: a tet model (its own domain) or a hex-dominant standard (its closed domain), with side labels. Throws
// facehex::Error naming `source` when a landmark is not found or a feature selects no vertex.
std::map<std::string, double> own_feature_values(const VolumeMesh& model, double band, const std::string& source);

// The same with the features at landmarks found beforehand (e.g. on a resampled surface of the model).
std::map<std::string, double> own_feature_values(const VolumeMesh& model, const FaceLandmarks& landmarks, double band,
                                                 const std::string& source);

}  // namespace facehex
