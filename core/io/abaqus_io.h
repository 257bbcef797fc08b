#pragma once
// Abaqus / CalculiX input decks (.inp) <-> VolumeMesh. Internal to core/io: use mesh_io.h.
//
// The writer produces the MODEL part of a deck, ready to *INCLUDE in a job that adds the step (docs/export.md):
//   *NODE, NSET=NALL                     node i+1 = row i of V (mm)
//   *ELEMENT, TYPE=C3D8 / C3D6 / C3D4    ELSET HEX / WEDGE / TET, element c+1 = cell c; wedges reordered (fe_sets.h)
//   *ELSET ALL, *NSET and *SURFACE, TYPE=ELEMENT per side (fe_sets.h), faces as S1..S6 (abaqus_face below)
//   *DISTRIBUTION FRAMES + *ORIENTATION FRAME when the mesh has material frames: one line per element, point a = e1
//                                        and point b = e2 of its frame, so the local axes 1, 2, 3 are e1, e2, e3
//   *MATERIAL SOFT_TISSUE (placeholder: isotropic linear elastic E = 0.015 MPa, nu = 0.45) and
//   *SOLID SECTION, ELSET=ALL, MATERIAL=SOFT_TISSUE[, ORIENTATION=FRAME]
// Units: mm, N, MPa. The *DISTRIBUTION is written as CalculiX 2.20 reads it (no TABLE parameter); Abaqus/Standard
// also wants a *DISTRIBUTION TABLE (COORD3D, COORD3D) named by TABLE= on the *DISTRIBUTION line (docs/export.md).
// CalculiX reads 132 characters per line and 20 per field: coordinates are the shortest text that reads back exactly
// when that fits (else rounded to 13+ significant digits), frame vectors have 9 digits.
//
// The reader takes *NODE, *ELEMENT (C3D8*, C3D6*, C3D4*: linear bricks, wedges, tets with any R/H/I suffix),
// *NSET (ids, set names, GENERATE) and one *DISTRIBUTION, and skips every other keyword with its data lines. Node and
// element ids may have gaps; cells are ordered by element id. Node sets named after the sides become point data
// "side_mask", the distribution becomes cell data "frame_e1".."frame_e3" (fe_sets.h). *INCLUDE is an error. A deck
// with the writer's heading ("FaceHex VERSION mesh: N nodes, M C3D8, ...") must hold those sizes and reach its
// *SOLID SECTION, else it is refused as cut short; other decks have no counts to check against.
#include <string>

#include "core/mesh/mesh.h"

namespace facehex::io {

VolumeMesh read_abaqus(const std::string& path);
void write_abaqus(const std::string& file, const VolumeMesh& mesh);

// The Abaqus face number (1 = S1, ...) of face `vtk_face` of cell_faces(type), from the face node lists of the Abaqus
// manual (C3D8: S1 1-2-3-4, S2 5-8-7-6, S3 1-5-6-2, S4 2-6-7-3, S5 3-7-8-4, S6 4-8-5-1; C3D6: S1 1-2-3, S2 4-6-5,
// S3 1-4-5-2, S4 2-5-6-3, S5 3-6-4-1; C3D4: S1 1-2-3, S2 1-4-2, S3 2-4-3, S4 3-4-1).
int abaqus_face(CellType type, int vtk_face);

}  // namespace facehex::io
