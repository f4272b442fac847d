#pragma once
// Closed prisms built by hand for the tests: a polygon in the xy-plane extruded
// along z through several rings, capped by fans from the polygon's centre.
#include "core/mesh.h"
#include "core/mesh_builder.h"
#include "core/triangle_soup.h"

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace xparam::test {

// The prism of `polygon` (counter-clockwise, star-shaped about the origin) with one ring of
// vertices at each of `heights` (increasing); ring r holds vertices r * n .. r * n + n - 1, the
// two cap centres come last. Every point shifted by `offset`.
inline Mesh prism(const std::vector<Eigen::Vector2d>& polygon, const std::vector<double>& heights,
                  const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  TriangleSoup soup;
  soup.source = "prism.obj";
  const int n = static_cast<int>(polygon.size());
  const int rings = static_cast<int>(heights.size());
  for (const double z : heights)
    for (const Eigen::Vector2d& p : polygon) soup.vertices.push_back(Eigen::Vector3d(p.x(), p.y(), z) + offset);
  const int bottom = n * rings;
  soup.vertices.push_back(Eigen::Vector3d(0, 0, heights.front()) + offset);
  soup.vertices.push_back(Eigen::Vector3d(0, 0, heights.back()) + offset);
  for (int r = 0; r + 1 < rings; ++r) {
    for (int i = 0; i < n; ++i) {
      const int a = r * n + i, b = r * n + (i + 1) % n, c = a + n, d = b + n;
      soup.triangles.push_back({a, b, d});
      soup.triangles.push_back({a, d, c});
    }
  }
  for (int i = 0; i < n; ++i) {
    soup.triangles.push_back({bottom, (i + 1) % n, i});
    const int top = (rings - 1) * n;
    soup.triangles.push_back({bottom + 1, top + i, top + (i + 1) % n});
  }
  return build_mesh(soup);
}

// A regular n-gon of circumradius r (the cylinder's cross-section).
inline std::vector<Eigen::Vector2d> regular_polygon(int n, double r) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * M_PI * i / n;
    points.emplace_back(r * std::cos(angle), r * std::sin(angle));
  }
  return points;
}

// The mesh's vertex positions as rows (vertex i = row i), the "map" of a surface onto itself.
inline Eigen::MatrixX3d vertex_rows(const Mesh& mesh) {
  Eigen::MatrixX3d rows(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (const VertexHandle v : mesh.vertices()) rows.row(v.idx()) = position(mesh, v).transpose();
  return rows;
}

}  // namespace xparam::test
