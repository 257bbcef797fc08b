#pragma once
// Checks of surface files that VTK's readers lack, run before handing a file to them (internal to core/io).
// VTK reads a truncated binary STL or OBJ without complaint (losing triangles) and crashes on a truncated binary
// PLY; these checks turn such files into a facehex::Error naming the file.
#include <string>

namespace facehex::io {

// Binary STL: the file must hold the 84 + 50 n bytes its header announces. ASCII STL is left to VTK.
void check_stl_file(const std::string& path);
// PLY: a well-formed header, and a body (ASCII or binary) that holds every element the header announces, with face
// vertex indices in range.
void check_ply_file(const std::string& path);
// OBJ: every vertex line has 3 coordinates, every face line at least 3 vertex indices within the vertex list. OBJ
// has no counts, so a file cut exactly at a line break cannot be told from a smaller surface.
void check_obj_file(const std::string& path);

}  // namespace facehex::io
