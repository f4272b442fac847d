#pragma once
/// \file
/// One parser per mesh format behind read_triangle_soup (io/mesh_reader.h). Each takes the
/// whole file's bytes and the name to use in messages, and returns the soup or throws
/// InputError. Internal to src/io.

#include "core/triangle_soup.h"

#include <string>
#include <string_view>

namespace xparam::detail {

/// Wavefront OBJ: `v` and `f` statements (1-based or negative relative indices); texture
/// coordinates, normals, groups, materials, lines and points are skipped; free-form geometry
/// and unknown statements are refused.
TriangleSoup read_obj(const std::string& source, std::string_view content);

/// OFF with optional ST/C/N/4 prefixes ignored per vertex (extra values on a line are skipped);
/// binary OFF and 4-D or n-D OFF are refused.
TriangleSoup read_off(const std::string& source, std::string_view content);

/// STL, ascii or binary (told apart by the size a binary file must have); corners welded.
TriangleSoup read_stl(const std::string& source, std::string_view content);

/// PLY 1.0, ascii or binary little/big endian; `vertex` x, y, z and the `face` index list.
TriangleSoup read_ply(const std::string& source, std::string_view content);

}  // namespace xparam::detail
