#pragma once
// A synthetic "head" CT for the segmentation tests: an ellipsoid of soft tissue (1000) around a 6 mm bone shell (2000)
// around more soft tissue (the "brain"), in air (0), with a deterministic pseudo-random noise of +-noise. The
// soft-tissue layer over the bone is `thickness` mm thick.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>

#include "core/mesh/head_turn.h"
#include "core/segment/ct_volume.h"
#include "core/segment/soft_tissue.h"

namespace facehex::testing {

inline CtVolume ellipsoid_phantom(double spacing = 2.0, double thickness = 10.0, double noise = 40.0) {
  CtVolume ct;
  ct.source = "phantom";
  GridGeometry& g = ct.intensity.geometry;
  g.dims = {80, 90, 80};
  g.spacing = Eigen::Vector3d::Constant(spacing);
  g.origin = Eigen::Vector3d::Zero();
  ct.intensity.data.resize(g.size());
  const Eigen::Vector3d centre =
      g.origin + 0.5 * Eigen::Vector3d(g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1) * spacing;
  const Eigen::Vector3d head(60, 75, 70), bone = head.array() - thickness, brain = bone.array() - 6.0;
  std::uint32_t state = 12345;
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d p = g.point(i, j, k) - centre;
        const double in_head = p.cwiseQuotient(head).squaredNorm(), in_bone = p.cwiseQuotient(bone).squaredNorm(),
                     in_brain = p.cwiseQuotient(brain).squaredNorm();
        state = state * 1664525u + 1013904223u;
        const double jitter = noise * (2.0 * (state >> 8) / double(1u << 24) - 1.0);
        ct.intensity(i, j, k) = static_cast<float>((in_brain <= 1  ? 1000
                                                    : in_bone <= 1 ? 2000
                                                    : in_head <= 1 ? 1000
                                                                   : 0) +
                                                   jitter);
      }
  return ct;
}

inline Eigen::Vector3d phantom_centre(const CtVolume& ct) {
  const GridGeometry& g = ct.intensity.geometry;
  return g.origin + 0.5 * Eigen::Vector3d(g.dims[0] - 1, g.dims[1] - 1, g.dims[2] - 1).cwiseProduct(g.spacing);
}

// Options that segment the phantom quickly, with its cuts given (it has no face for the automatic ones).
inline SegmentOptions phantom_options(const CtVolume& ct) {
  const Eigen::Vector3d c = phantom_centre(ct);
  SegmentOptions o;
  o.working_spacing = 1.5;
  o.tets.target_edge_length = 3.0;
  o.cuts.top_z = c.z() + 35;
  o.cuts.bottom_z = c.z() - 35;
  o.cuts.posterior_y = c.y();
  o.cuts.centre_x = c.x();
  return o;
}

// A face's front for the landmarks read in the CT (core/segment/face_front.h): tissue (1000) behind y = front(x, z)
// of the head frame `frame` and in front of y = -50, air (-1000) elsewhere, on 0.5 mm voxels over x within
// half_width of 0, y from -60 to 60 and z from -50 to 30 (the model's frame). Across the front the value ramps from
// air half a voxel in front of it to tissue half a voxel behind it, as a CT's partial volume does, so that the front
// read at 0 lies where front(x, z) puts it rather than on the voxels' grid.
inline Field face_front_phantom(const std::function<double(double, double)>& front, const HeadTurn& frame,
                                double half_width = 70) {
  GridGeometry g;
  g.spacing = Eigen::Vector3d::Constant(0.5);
  g.origin = Eigen::Vector3d(-half_width, -60, -50);
  g.dims = {static_cast<int>(2 * half_width / 0.5) + 1, 241, 161};
  Field f(g, -1000);
  for (int k = 0; k < g.dims[2]; ++k)
    for (int j = 0; j < g.dims[1]; ++j)
      for (int i = 0; i < g.dims[0]; ++i) {
        const Eigen::Vector3d q = frame.to_head(g.point(i, j, k));
        if (q.y() > -50) f(i, j, k) = std::clamp(1000 * (front(q.x(), q.z()) - q.y()) / 0.25, -1000.0, 1000.0);
      }
  return f;
}

// The mid-sagittal plane the segmentation finds on the Visible Human Female's CT (../shared, optional; the plane of
// tests/data/landmarks/vhfemale-head-ct-skin.xyz), for reading its landmarks in the CT by the hand-placed ones.
inline MidSagittalPlane visible_human_plane() {
  MidSagittalPlane plane;
  plane.x = 263.08327529903028;
  plane.turn = -0.054158064087028765;
  plane.y = 269.35853203535248;
  return plane;
}

}  // namespace facehex::testing
