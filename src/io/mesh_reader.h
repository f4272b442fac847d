#pragma once
/// \file
/// Reading a mesh file into a TriangleSoup: what the file says, nothing repaired.

#include "core/triangle_soup.h"

#include <filesystem>

namespace xparam {

/// Reads OBJ, PLY (ascii, binary little and big endian), OFF and STL (ascii and binary) into a
/// TriangleSoup (core/triangle_soup.h) with the file's own indices; nothing repaired, nothing
/// dropped silently. The format is chosen by the extension (case-insensitive).
///
/// Vertex i of the soup is the file's vertex i and face j is the file's face j; a polygon with
/// n > 3 corners becomes the fan (c0, ck, ck+1), k = 1..n-2, and is counted in
/// `polygons_triangulated`. Coordinates are kept as doubles (float files convert exactly).
/// Extra per-vertex and per-face values (normals, colours, texture coordinates, OBJ groups,
/// lines and points, other PLY elements) are parsed for syntax and not kept.
/// STL stores triangles as corner positions: corners with equal coordinates (bit-identical, with
/// -0 equal to +0) are welded into one vertex, numbered in order of first appearance.
///
/// Throws InputError("<path>: <what is wrong>") for anything it cannot read faithfully: a
/// missing, empty or unknown-extension file, syntax errors and garbage (with the line), a
/// header count the file size cannot hold (refused before anything is allocated for it),
/// truncation, data after the last declared element, NaN or infinite coordinates, faces with
/// fewer than 3 corners, out-of-range, negative or repeated indices, and files with no vertex
/// or no face. Indices in messages are 0-based like the soup's, except where an OBJ index is
/// quoted as written. Non-manifold or otherwise odd topology is not an error here (see
/// core/validation.h). Thread-safe: no OpenMesh reader is involved, no state is shared.
TriangleSoup read_triangle_soup(const std::filesystem::path& path);

}  // namespace xparam
