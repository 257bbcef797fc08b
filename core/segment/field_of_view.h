#pragma once
// Where the scan's field of view cuts the head: the body voxels whose neighbour across the side or the back of the
// head lies outside the CT.
//
// A scan cropped to the face (a cone-beam CT, a volume exported around the face) can end in front of the ears, where
// the posterior cut belongs, or across the cheeks. There the head is cut by the scan's box rather than by air: the
// auricles the posterior cut is placed by are not in the scan, and what the ear rules find instead (a cheek's bulge,
// the rows where the head meets the box) lies anywhere. The contacts say where the scan ends across the head, in the
// head frame, so that the posterior cut stays in front of them (face_cuts.h). A contact across the front of the head
// (a nose the field of view clips) is not one: the face's front is read by its own rules (face_anatomy.h).
//
// A CT's slices are reconstructed in a disc: a scanner fills what lies outside it with one value (its lowest), the
// same in every slice. Where the disc is narrower than the head, the scan ends across it on the disc's edge, inside
// the volume's box.
#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

#include "core/mesh/head_turn.h"
#include "core/segment/voxel_grid.h"

namespace facehex {

// The disc a CT's slices were reconstructed in (x and y, mm, the segmentation frame): the voxel centres within
// `radius` of `centre` hold the scan, those beyond it the scanner's fill.
struct ReconstructionDisc {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0;
};

// The reconstruction disc of a CT whose columns (along z) beyond a circle hold its lowest value in every slice, or
// none. The circle is fitted to the columns that border the filled ones (a least-squares circle, refitted to the
// columns within two voxels of it), and taken when at least nine in ten lie that close and they span a quarter turn
// or more: a fill that follows the body (air set to one value around it) or the box is no disc.
std::optional<ReconstructionDisc> find_reconstruction_disc(const Field& intensity);

// The CT's extent across the head: the box of its voxel centres in x and y (mm, the segmentation frame: the CT's own,
// axes swapped so that the face looks to +y), its reconstruction disc if it has one, and the head frame the grids are
// sampled in (HeadTurn::to_model maps a head-frame point back). A point beyond the box or the disc lies outside the
// scan: the working grid, sampled at the CT's centres and within them, has its next voxel there where it ends with
// the CT.
struct ScanSides {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero();
  std::optional<ReconstructionDisc> disc;
  HeadTurn turn;
  bool outside(const Eigen::Vector3d& head_point) const;
  // Outside the disc but within the box.
  bool outside_disc_only(const Eigen::Vector3d& head_point) const;
  // The disc's outward normal at a head-frame point, in the head frame (z = 0 in the model's frame); with a disc only.
  Eigen::Vector3d disc_normal(const Eigen::Vector3d& head_point) const;
};

// The directions a contact faces, in the head frame.
enum class ScanEdge { MinusX, PlusX, MinusY };

struct FieldOfViewContact {
  Eigen::Vector3d point;  // mm, head frame: the body voxel's centre
  ScanEdge edge;          // its neighbour outside the scan lies this way
  bool on_disc = false;   // that neighbour lies outside the reconstruction disc only, within the box
};

// The contacts of `body` (a mask on a head-frame grid) between heights z_lo and z_hi: body voxels whose neighbour one
// voxel to -x, +x or -y lies outside the scan. The neighbours are looked at beyond the grid's faces too: a grid that
// ends where the CT does has its contacts on its faces. On the disc's edge, only where it faces more than 60 degrees
// away from the front (the disc cuts the side or the back of the head, not a nose or a cheek's front).
std::vector<FieldOfViewContact> field_of_view_contacts(const Mask& body, const ScanSides& scan, double z_lo,
                                                       double z_hi);

// The grid faces (-x, +x, -y, +y, -z, +z) that some contact lies on and faces: where the grid ends with the scan and
// the head is cut there, not surrounded by air.
std::array<bool, 6> cut_grid_faces(const Mask& body, const std::vector<FieldOfViewContact>& contacts);

}  // namespace facehex
