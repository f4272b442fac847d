#pragma once
/// \file
/// A mesh file's content before any topology is built: what the file said, nothing repaired.

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace xparam {

/// Vertices and triangles exactly as read from a file, with the file's own 0-based indices,
/// so that validation can name them (`edge (12, 40) has 3 faces`). Polygons with more than
/// three corners are fan-triangulated by the reader and counted in `polygons_triangulated`.
struct TriangleSoup {
  std::string source;                           ///< file name used in every message about it
  std::vector<Eigen::Vector3d> vertices;        ///< #V positions, in file order
  std::vector<std::array<int, 3>> triangles;    ///< #F vertex indices, in file order
  int polygons_triangulated = 0;                ///< faces with more than 3 corners that were fanned
};

}  // namespace xparam
