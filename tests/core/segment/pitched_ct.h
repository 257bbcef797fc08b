#pragma once
// The bundled CT pitched about the lateral axis on its own grid, as a head pitched in the scanner: what turns out of
// the field of view is lost, and the scan's first and last slices lean in the head by the pitch.
#include <algorithm>

#include "core/mesh/head_turn.h"
#include "core/segment/ct_volume.h"
#include "core/segment/voxel_grid.h"

namespace facehex::testing {

// The pitch about the bundled CT's middle: scan.to_model maps a point of the pitched CT to where it lies in the upright
// one and scan.to_head back, so that a positive pitch lowers the chin of the pitched CT.
inline HeadTurn bundled_ct_pitch(double pitch) {
  HeadTurn scan;
  scan.pitch = pitch;
  scan.axis = Eigen::Vector2d(100.8, 100.8);
  scan.axis_z = 69;
  return scan;
}

// `upright` resampled on its own grid so that its content is moved by `scan`; outside its box, its lowest value.
inline CtVolume pitched_on_its_grid(const CtVolume& upright, const HeadTurn& scan) {
  CtVolume ct = upright;
  ct.intensity = resample_mapped(
      upright.intensity, upright.intensity.geometry, [&](const Eigen::Vector3d& p) { return scan.to_model(p); },
      *std::min_element(upright.intensity.data.begin(), upright.intensity.data.end()));
  return ct;
}

}  // namespace facehex::testing
