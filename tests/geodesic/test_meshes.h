#pragma once
/// \file
/// Meshes and edge paths for the geodesic tests and benchmarks (header only, no GoogleTest).

#include "core/mesh.h"
#include "core/provenance.h"

#include <OpenMesh/Core/IO/MeshIO.hh>

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace xparam::test {

/// A mesh file read into xparam::Mesh, with provenance started.
inline Mesh load_mesh_with_provenance(const std::string& path) {
  Mesh mesh;
  if (!OpenMesh::IO::read_mesh(mesh, path)) throw std::runtime_error("cannot read " + path);
  init_provenance(mesh);
  return mesh;
}

/// A flat (z = 0) grid of nx by ny unit squares, each cut by its (i, j)-(i+1, j+1) diagonal;
/// vertex (i, j) has index j * (nx + 1) + i. Interior vertices move in the plane by up to
/// `jitter` (deterministic). Provenance started.
inline Mesh flat_grid(int nx, int ny, double jitter = 0.0, std::uint32_t seed = 7) {
  Mesh mesh;
  std::mt19937 random(seed);
  // mt19937's raw output is the same on every platform (its distributions are not).
  const auto offset = [&] { return jitter * (2.0 * static_cast<double>(random()) / 4294967295.0 - 1.0); };
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const bool interior = i > 0 && j > 0 && i < nx && j < ny;
      const double dx = interior ? offset() : 0.0;
      const double dy = interior ? offset() : 0.0;
      mesh.add_vertex({i + dx, j + dy, 0.0});
    }
  }
  const auto v = [&](int i, int j) { return mesh.vertex_handle(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      mesh.add_face(v(i, j), v(i + 1, j), v(i + 1, j + 1));
      mesh.add_face(v(i, j), v(i + 1, j + 1), v(i, j + 1));
    }
  }
  init_provenance(mesh);
  return mesh;
}

/// Vertex (i, j) of flat_grid(nx, ...).
inline VertexHandle grid_vertex(int nx, int i, int j) { return VertexHandle(j * (nx + 1) + i); }

/// The grid vertices through `corners` (grid coordinates), walking straight along grid lines
/// between consecutive corners (each pair must share a row or a column).
inline std::vector<VertexHandle> grid_walk(int nx, const std::vector<std::array<int, 2>>& corners) {
  std::vector<VertexHandle> path{grid_vertex(nx, corners[0][0], corners[0][1])};
  for (std::size_t k = 1; k < corners.size(); ++k) {
    int i = corners[k - 1][0];
    int j = corners[k - 1][1];
    while (i != corners[k][0] || j != corners[k][1]) {
      i += (corners[k][0] > i) - (corners[k][0] < i);
      j += (corners[k][1] > j) - (corners[k][1] < j);
      path.push_back(grid_vertex(nx, i, j));
    }
  }
  return path;
}

/// The surface of the unit cube [0, 1]^3, every side an n by n grid of squares cut in two,
/// outward oriented. Vertices are found by cube_vertex. Provenance started.
inline Mesh subdivided_cube(int n, std::map<std::array<int, 3>, VertexHandle>* index = nullptr) {
  Mesh mesh;
  std::map<std::array<int, 3>, VertexHandle> vertices;
  const auto vertex = [&](const std::array<int, 3>& key) {
    auto it = vertices.find(key);
    if (it == vertices.end()) {
      it =
          vertices.emplace(key, mesh.add_vertex({key[0] / double(n), key[1] / double(n), key[2] / double(n)}))
              .first;
    }
    return it->second;
  };
  // Per side: origin and axes (grid units) with u x v pointing out of the cube.
  const std::array<std::array<std::array<int, 3>, 3>, 6> sides = {{
      {{{0, 0, n}, {1, 0, 0}, {0, 1, 0}}},
      {{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}}},
      {{{n, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
      {{{0, 0, 0}, {0, 0, 1}, {0, 1, 0}}},
      {{{0, n, 0}, {0, 0, 1}, {1, 0, 0}}},
      {{{0, 0, 0}, {1, 0, 0}, {0, 0, 1}}},
  }};
  for (const auto& side : sides) {
    const auto at = [&](int i, int j) {
      std::array<int, 3> key;
      for (int c = 0; c < 3; ++c) key[c] = side[0][c] + i * side[1][c] + j * side[2][c];
      return vertex(key);
    };
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        mesh.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1));
        mesh.add_face(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
    }
  }
  if (index) *index = vertices;
  init_provenance(mesh);
  return mesh;
}

/// The cube vertices through `corners` (grid coordinates of subdivided_cube), walking one
/// grid step at a time along the one coordinate in which consecutive corners differ.
inline std::vector<VertexHandle> cube_walk(const std::map<std::array<int, 3>, VertexHandle>& index,
                                           const std::vector<std::array<int, 3>>& corners) {
  std::array<int, 3> at = corners[0];
  std::vector<VertexHandle> path{index.at(at)};
  for (std::size_t k = 1; k < corners.size(); ++k) {
    while (at != corners[k]) {
      for (int c = 0; c < 3; ++c) at[c] += (corners[k][c] > at[c]) - (corners[k][c] < at[c]);
      path.push_back(index.at(at));
    }
  }
  return path;
}

/// True when every face around v is in the region and v is not on the mesh boundary.
inline bool inside_region(const Mesh& mesh, const std::vector<bool>& region, VertexHandle v) {
  if (mesh.is_boundary(v)) return false;
  for (FaceHandle f : mesh.vf_range(v)) {
    if (!region[f.idx()]) return false;
  }
  return true;
}

/// Shortest path along mesh edges from a to b (Dijkstra on edge lengths) whose interior
/// vertices lie inside the region. Empty when there is none.
inline std::vector<VertexHandle> shortest_edge_path(const Mesh& mesh, const std::vector<bool>& region,
                                                    VertexHandle a, VertexHandle b) {
  std::vector<double> distance(mesh.n_vertices(), std::numeric_limits<double>::infinity());
  std::vector<int> parent(mesh.n_vertices(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  distance[a.idx()] = 0.0;
  queue.push({0.0, a.idx()});
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > distance[i]) continue;
    const VertexHandle v(i);
    if (v == b) break;
    if (v != a && !inside_region(mesh, region, v)) continue;
    for (VertexHandle w : mesh.vv_range(v)) {
      const double next = d + (mesh.point(v) - mesh.point(w)).norm();
      if (next < distance[w.idx()]) {
        distance[w.idx()] = next;
        parent[w.idx()] = i;
        queue.push({next, w.idx()});
      }
    }
  }
  if (parent[b.idx()] < 0) return {};
  std::vector<VertexHandle> path{b};
  while (path.back() != a) path.push_back(VertexHandle(parent[path.back().idx()]));
  return {path.rbegin(), path.rend()};
}

}  // namespace xparam::test
