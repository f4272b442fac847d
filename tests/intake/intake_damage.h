#pragma once
/// \file
/// Synthetic damage with known truth for the intake tests: a clean bundled mesh, and copies with
/// faces punched out, a floater added, a face duplicated; each knows which file elements are which.

#include "core/triangle_soup.h"
#include "io/mesh_reader.h"
#include "support/test_data.h"

#include <Eigen/Core>

#include <array>
#include <utility>
#include <vector>

namespace xparam::test {

/// spot_low_resolution.obj (829 vertices, 1654 faces, genus 0) read as a soup.
inline TriangleSoup clean_spot() { return read_triangle_soup(data_path("spot_low_resolution.obj")); }

/// `soup` without the faces whose centroid lies within `radius` of vertex `center`: one hole.
/// The removed faces are listed in `removed` (file indices of `soup`), the rest keep their order.
inline TriangleSoup punch_hole(const TriangleSoup& soup, int center, double radius, std::vector<int>& removed) {
  TriangleSoup out = soup;
  out.triangles.clear();
  removed.clear();
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const auto& t = soup.triangles[f];
    const Eigen::Vector3d centroid = (soup.vertices[t[0]] + soup.vertices[t[1]] + soup.vertices[t[2]]) / 3.0;
    if ((centroid - soup.vertices[center]).norm() < radius)
      removed.push_back(static_cast<int>(f));
    else
      out.triangles.push_back(t);
  }
  return out;
}

/// `soup` with a closed tetrahedron of edge `size` added at `at` (4 vertices and 4 faces after
/// the soup's own).
inline TriangleSoup add_floater(const TriangleSoup& soup, const Eigen::Vector3d& at, double size) {
  TriangleSoup out = soup;
  const int first = static_cast<int>(out.vertices.size());
  for (const Eigen::Vector3d& corner : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                        Eigen::Vector3d(0, 0, 1)})
    out.vertices.push_back(at + size * corner);
  for (const std::array<int, 3>& t : {std::array<int, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}})
    out.triangles.push_back({first + t[0], first + t[1], first + t[2]});
  return out;
}

/// `soup` with face `face` repeated at the end (reversed when `reversed`).
inline TriangleSoup duplicate_face(const TriangleSoup& soup, int face, bool reversed) {
  TriangleSoup out = soup;
  std::array<int, 3> t = soup.triangles[face];
  if (reversed) std::swap(t[1], t[2]);
  out.triangles.push_back(t);
  return out;
}

}  // namespace xparam::test
