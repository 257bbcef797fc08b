#pragma once
// Objects lying on the face's front, a head strap or thick tape, read from the CT's own grey values. At a soft
// tissue's density such an object is segmented with the skin, and the profile's landmarks would take its front for
// the skin's (a strap over the brow for the glabella); its edges are steps that no forehead or nose shows.
//
// In the head frame of the face's mid-sagittal plane (core/mesh/head_turn.h), the face's front (face_front.h) in the
// columns within kProfileHalfWidth of the plane, averaged into one profile y(z) every kStep mm from kAbovePronasale
// above the nose tip up to kReach above it, where the scan holds the face. With w the CT's voxel spacing along z (at
// least kMinEdgeSpan: a voxel-sharp edge spreads over one slice in the interpolated grey values), the step at z is
// y(z + w) - y(z - w) less w times the slopes over kSlopeSpan either side (each the median of its samples' slopes, so
// that a step or a voxel stair nearby does not count), so that a bend of the profile (the nasion, the brow, the end of
// a field-of-view cut) makes none:
//  1. an object's lower edge is a largest step within w either side of at least kMinStep (the front comes forward going
//     up), its upper edge the nearest such step of at most -kMinStep above it (the front goes back), within kMaxHeight
//     and with no other lower edge between them; each edge lies where the profile changes fastest within w of it;
//  2. the object's thickness at each edge is the profile's change across it less what the skin outside it, continued
//     with its own slope, accounts for; the two agree within a factor kMaxStepRatio (one object's, not two bends);
//  3. the skin under it, every kSkinStep mm from kSkinMargin below its lower edge to kSkinMargin above its upper one:
//     the profile less the thickness (linear in z between the edges) and, across each edge's span (w either side,
//     where the grey values blend its edge), the line between the profile outside and the skin inside.
// Above the nose tip the nasal dorsum, the nasion, the brow and the forehead change smoothly, by about a millimetre per
// millimetre of height at most. Not told apart: objects thinner than kMinStep (tape), one whose upper edge lies beyond
// the scan or kReach, objects on the lips and the chin, whose own profile steps (the lower lip, the chin's underside).
#include <Eigen/Core>
#include <vector>

#include "core/mesh/ct_landmarks.h"
#include "core/mesh/mid_sagittal_plane.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// `ct` the CT's intensities in the model's frame, `skin_threshold` in its units; the plane and the pronasale as found
// on the model's skin (core/face/face_landmarks.h), in the model's frame. The objects in the head frame of `plane`,
// bottom up.
std::vector<SkinObject> find_skin_objects(const Field& ct, double skin_threshold, const MidSagittalPlane& plane,
                                          const Eigen::Vector3d& pronasale);

}  // namespace facehex
