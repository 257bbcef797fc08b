#pragma once
// A standard's parameterization domain with its openings closed.
//
// A patient model from a CT is one solid without tunnels (eyes, nostrils and mouth are filled, see docs), while a
// hand-built standard may keep the openings as holes through the shell. Harmonic fields with free (Neumann) walls
// on such holes bend sharply around their rims (the rim of a slit such as the mouth behaves like a crack tip), and
// the parameterization folds there. closed_domain() fills every opening: each opening's wall is capped at its rims
// (least-area triangulation of each rim loop, no new vertex) and the plug it encloses is tetrahedralized by TetGen
// without Steiner points on its surface, so the plug conforms to the auxiliary tets around it. The caps lie on the
// skin or bone side and carry that side; the hex vertices stay the domain's first vertices.
//
// An opening whose cap cannot be built or meshed (e.g. rims that touch each other, or caps that would cut through
// its wall) stays open; the returned description says how many were closed.
#include <vector>

#include "core/fields/tet_domain.h"

namespace facehex {

TetDomain closed_domain(const VolumeMesh& hex);

// The openings of any tet domain closed as closed_domain() closes a standard's: a patient model with open eyes,
// nostrils or mouth (walls on no side) gets the standard's plugs, so that the two domains have the same shape there.
// An opening is a connected set of boundary triangles with no side common to their three vertices that reaches a
// boundary vertex on no side (its wall) and is bounded by two or more rim loops (it goes through the shell, from one
// side to another); where sides meet, the three vertices carry different sides but each has one, and a patch with
// one rim loop is a dent, not an opening. `kind` names the domain in the description ("the model's own tets");
// closed_openings counts the openings closed.
TetDomain close_openings(TetDomain domain, const std::string& kind);

// A domain's boundary triangles with no side common to their three vertices (the walls of its openings, and patches
// where sides meet), in pieces connected through shared edges, each piece's triangles in boundary order.
std::vector<std::vector<Eigen::Vector3i>> sideless_boundary_pieces(const TetDomain& domain);

// Of each piece of sideless_boundary_pieces (same order), the vertices of its triangles on any side of `side_bits`
// (e.g. side_bit(W1): the rim on the skin), sorted, each once.
std::vector<std::vector<int>> opening_rims(const TetDomain& domain,
                                           const std::vector<std::vector<Eigen::Vector3i>>& pieces, int side_bits);

// A domain's boundary as a closed surface on the domain's boundary vertices (renumbered), each triangle labelled
// Side + 1 with the side its three vertices share (0: none, the walls of an opening left open; tetrahedralize.h's
// convention).
SurfaceMesh domain_surface(const TetDomain& domain);

}  // namespace facehex
