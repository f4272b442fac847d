#pragma once
/// \file
/// A plain OBJ reader for tests that check written files independently of xparam's own loader.

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <vector>

namespace xparam::test {

/// The vertices and triangles of an OBJ file, in file order, faces 0-based.
struct PlainObj {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;
};

/// Read the "v x y z" and "f a b c" lines of `path` ("f a/t/n ..." corners too); other lines
/// are skipped.
PlainObj read_plain_obj(const std::filesystem::path& path);

}  // namespace xparam::test
