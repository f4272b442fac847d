#pragma once
/// \file
/// Disk patches for the parameterization tests: generated grids, a hemisphere, regions of
/// real meshes, and the counter-clockwise boundary loop of any oriented disk.

#include "param/patch_parameterization.h"

#include <OpenMesh/Core/IO/MeshIO.hh>

#include "core/mesh.h"

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

namespace xparam::test {

/// The boundary loop of an oriented disk, following the triangles' own boundary edges (so it
/// is counter-clockwise with respect to their orientation), starting at `start` when given.
inline std::vector<int> boundary_loop(const std::vector<std::array<int, 3>>& triangles, int start = -1) {
  std::set<std::pair<int, int>> directed;
  for (const auto& t : triangles) {
    for (int c = 0; c < 3; ++c) directed.insert({t[c], t[(c + 1) % 3]});
  }
  std::map<int, int> next;
  for (const auto& [a, b] : directed) {
    if (!directed.count({b, a})) next[a] = b;
  }
  if (next.empty()) throw std::runtime_error("boundary_loop: closed surface");
  if (start < 0) start = next.begin()->first;
  std::vector<int> loop{start};
  while (next.at(loop.back()) != start) loop.push_back(next.at(loop.back()));
  if (loop.size() != next.size()) throw std::runtime_error("boundary_loop: more than one loop");
  return loop;
}

/// Corners of a regular k-gon of circumradius 1, counter-clockwise.
inline std::vector<Eigen::Vector2d> regular_polygon(int k) {
  std::vector<Eigen::Vector2d> corners;
  for (int j = 0; j < k; ++j) {
    const double a = 2.0 * std::numbers::pi * j / k;
    corners.emplace_back(std::cos(a), std::sin(a));
  }
  return corners;
}

/// `k` corner positions spread evenly along a loop of `m` vertices.
inline std::vector<int> even_corner_positions(int m, int k) {
  std::vector<int> positions;
  for (int j = 0; j < k; ++j) positions.push_back(j * m / k);
  return positions;
}

/// A planar (z = 0) jittered grid over the unit square, diagonals chosen at random, mapped by
/// the 2x2 `shape` (so the domain is the parallelogram with corners shape*(0,0), (1,0), (1,1),
/// (0,1)). Boundary vertices stay on the sides (unevenly spaced); corners are loop positions
/// of those four points. Returns the patch with `polygon` = the parallelogram.
inline DiskPatch planar_grid_patch(int n, const Eigen::Matrix2d& shape, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  DiskPatch patch;
  std::vector<Eigen::Vector2d> plane;
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      double x = i, y = j;
      const bool side_x = i == 0 || i == n;
      const bool side_y = j == 0 || j == n;
      if (!side_x) x += jitter(rng);  // slide along a horizontal side or move freely inside
      if (!side_y) y += jitter(rng);
      plane.emplace_back(x / n, y / n);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (rng() % 2) {
        patch.triangles.push_back({a, b, c});
        patch.triangles.push_back({a, c, d});
      } else {
        patch.triangles.push_back({a, b, d});
        patch.triangles.push_back({b, c, d});
      }
    }
  }
  for (const auto& p : plane) {
    const Eigen::Vector2d q = shape * p;
    patch.positions.emplace_back(q.x(), q.y(), 0.0);
  }
  patch.boundary_loop = boundary_loop(patch.triangles, id(0, 0));
  const int corner_ids[4] = {id(0, 0), id(n, 0), id(n, n), id(0, n)};
  for (int corner : corner_ids) {
    for (int p = 0; p < static_cast<int>(patch.boundary_loop.size()); ++p) {
      if (patch.boundary_loop[p] == corner) patch.corner_positions.push_back(p);
    }
    const Eigen::Vector3d& x = patch.positions[corner];
    patch.polygon.emplace_back(x.x(), x.y());
  }
  return patch;
}

/// A unit hemisphere (z >= 0) as a pole fan plus `rings` latitude rings of `segments`
/// vertices, outward oriented; the boundary is the equator.
inline DiskPatch hemisphere_patch(int rings, int segments) {
  DiskPatch patch;
  patch.positions.emplace_back(0.0, 0.0, 1.0);
  for (int r = 1; r <= rings; ++r) {
    const double polar = 0.5 * std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * std::numbers::pi * (s + 0.5 * (r % 2)) / segments;
      patch.positions.emplace_back(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
                                   std::cos(polar));
    }
  }
  auto ring = [segments](int r, int s) {
    return 1 + (r - 1) * segments + (s % segments + segments) % segments;
  };
  for (int s = 0; s < segments; ++s) patch.triangles.push_back({0, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      patch.triangles.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      patch.triangles.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
  }
  patch.boundary_loop = boundary_loop(patch.triangles);
  return patch;
}

/// Read a mesh file (any format OpenMesh reads) into positions and triangles.
inline void read_triangles(const std::string& path, std::vector<Eigen::Vector3d>& positions,
                           std::vector<std::array<int, 3>>& triangles) {
  Mesh mesh;
  if (!OpenMesh::IO::read_mesh(mesh, path)) throw std::runtime_error("cannot read " + path);
  for (VertexHandle v : mesh.vertices()) positions.push_back(position(mesh, v));
  for (FaceHandle f : mesh.faces()) {
    std::array<int, 3> t{};
    int c = 0;
    for (VertexHandle v : mesh.fv_range(f)) t[c++] = v.idx();
    triangles.push_back(t);
  }
}

/// The faces within `rings` face rings of vertex `seed` of a mesh, reindexed locally; the
/// result is a patch only when it is a disk (callers check with the Euler characteristic).
inline DiskPatch region_patch(const std::vector<Eigen::Vector3d>& positions,
                              const std::vector<std::array<int, 3>>& triangles, int seed, int rings) {
  std::set<int> vertices{seed};
  std::set<int> faces;
  for (int r = 0; r < rings; ++r) {
    std::set<int> grown = vertices;
    for (int f = 0; f < static_cast<int>(triangles.size()); ++f) {
      const auto& t = triangles[f];
      if (vertices.count(t[0]) || vertices.count(t[1]) || vertices.count(t[2])) {
        faces.insert(f);
        grown.insert(t.begin(), t.end());
      }
    }
    vertices = grown;
  }
  DiskPatch patch;
  std::map<int, int> local;
  for (int f : faces) {
    std::array<int, 3> t{};
    for (int c = 0; c < 3; ++c) {
      auto [it, inserted] = local.try_emplace(triangles[f][c], static_cast<int>(local.size()));
      if (inserted) patch.positions.push_back(positions[triangles[f][c]]);
      t[c] = it->second;
    }
    patch.triangles.push_back(t);
  }
  patch.boundary_loop = boundary_loop(patch.triangles);
  return patch;
}

/// Twice the signed area of every uv triangle.
inline std::vector<double> uv_signed_areas(const DiskPatch& patch, const std::vector<Eigen::Vector2d>& uv) {
  std::vector<double> areas;
  for (const auto& t : patch.triangles) {
    const Eigen::Vector2d e1 = uv[t[1]] - uv[t[0]];
    const Eigen::Vector2d e2 = uv[t[2]] - uv[t[0]];
    areas.push_back(e1.x() * e2.y() - e1.y() * e2.x());
  }
  return areas;
}

}  // namespace xparam::test
