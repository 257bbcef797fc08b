#pragma once
// Per-vertex side masks (sides.h) from per-face side labels.
#include <Eigen/Core>

#include "core/mesh/mesh.h"

namespace facehex {

// #V mask: the OR of side_bit(side(f)) over the faces around each vertex. F is #F x 3 (or x 4); side(f) is a Side, or
// -1 for a face on no side.
Eigen::VectorXi side_mask_from_faces(int num_vertices, const Eigen::MatrixXi& F, const Eigen::VectorXi& side);

// Where opposite sides of one field meet (a zero-thickness rim: skin touching bone, or the two lateral ends), a vertex
// cannot take both values; such vertices lose both bits and are left free for that field. Returns how many
// (vertex, field) pairs were cleared.
int clear_opposite_sides(Eigen::VectorXi& side_mask);

// A quad face with three vertices on the same two sides would be pinned flat along the sides' common edge (a
// labelling artefact at the corners of hand-built shells, where one cell face turns the corner). The middle one of
// the three keeps only the sides all four vertices of the face share, so it may move off that edge. Returns how many
// vertices were relaxed.
int relax_corner_quads(const VolumeMesh& mesh, Eigen::VectorXi& side_mask);

// The vertex on the skin (side w1 of side_mask #V) closest to `point`, or -1 when none is. V is #V x 3.
int closest_skin_vertex(const Eigen::MatrixXd& V, const Eigen::VectorXi& side_mask, const Eigen::Vector3d& point);

}  // namespace facehex
