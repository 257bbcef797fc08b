#pragma once
// The CT in the head frame of a turned or pitched head (core/mesh/head_turn.h), where the face looks to +y, upright,
// and the cuts are placed.
#include "core/mesh/head_turn.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// The field in the head frame, resampled as resample(field, spacing) is (voxel_grid.h): on an isotropic grid of that
// spacing holding the whole turned box, from the field's first voxel centre up, the field's sample at
// turn.to_model(p), or `outside` beyond the field's box (resample_mapped). With a region (an x-y box of the model's
// frame, mm, over the field's whole height), only the part of that grid holding the turned region, at the same voxel
// centres: the air around a body costs a resample for nothing.
Field turned_to_head_frame(const Field& field, const HeadTurn& turn, double spacing, float outside);
Field turned_to_head_frame(const Field& field, const HeadTurn& turn, double spacing, float outside,
                           const Eigen::Vector2d& region_lo, const Eigen::Vector2d& region_hi);

}  // namespace facehex
