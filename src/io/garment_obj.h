#pragma once
/// \file
/// A garment as an OBJ file with texture coordinates: read, and written back with new vertex
/// positions but the file's vertex order, triangles and UVs unchanged, so the warped garment
/// drops into the pipeline its rest shape came from (same UV layout, same texture).

#include "core/triangle_soup.h"

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <vector>

namespace xparam {

/// A garment mesh: positions and triangles as in the file, and its texture coordinates.
struct GarmentObj {
  TriangleSoup mesh;                               ///< `v` in file order, `f` in file order (0-based)
  std::vector<Eigen::Vector2d> uvs;                ///< `vt` u v in file order (a third value is dropped)
  std::vector<std::array<int, 3>> triangle_uvs;    ///< per triangle, the `vt` of each corner (0-based);
                                                   ///< empty when the file's faces give none
};

/// Read `path`: `v`, `vt` and triangular `f` (corners `v`, `v/vt`, `v//vn` or `v/vt/vn`);
/// normals, groups and materials are ignored (a warped garment's normals are recomputed by the
/// viewer). \throw InputError "FILE: line L: what; fix" for a polygon with more than three
/// corners, faces that give UVs for some corners only, a `vt` index out of range, or what
/// read_triangle_soup refuses (bad numbers, vertex indices out of range).
GarmentObj read_garment_obj(const std::filesystem::path& path);

/// Write `garment` with `vertices` (#V, the file's order) in place of its positions: `v`, then
/// `vt`, then `f v/vt` (or `f v` without UVs). Doubles are written exactly (shortest
/// round-trip). Written to `<path>.tmp` and renamed. \pre vertices.size() == garment's #V
/// \throw InputError naming the path when it cannot be written
void write_garment_obj(const std::filesystem::path& path, const GarmentObj& garment,
                       const std::vector<Eigen::Vector3d>& vertices);

}  // namespace xparam
