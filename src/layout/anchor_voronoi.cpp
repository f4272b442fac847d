#include "layout/anchor_voronoi.h"

#include "core/disjoint_sets.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <tuple>
#include <utility>

namespace xparam {
namespace {

// The cells of edge e's two ends.
std::pair<int, int> cells_of(const Mesh& mesh, const AnchorVoronoi& voronoi, EdgeHandle e) {
  const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
  return {voronoi.cell[mesh.from_vertex_handle(h).idx()], voronoi.cell[mesh.to_vertex_handle(h).idx()]};
}

}  // namespace

AnchorVoronoi anchor_cells(const Mesh& mesh, const std::vector<VertexHandle>& anchors) {
  const std::size_t n = mesh.n_vertices();
  AnchorVoronoi voronoi;
  voronoi.cell.assign(n, -1);
  voronoi.distance.assign(n, std::numeric_limits<double>::infinity());
  using Entry = std::tuple<double, int, int>;  // (distance, anchor, vertex)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (int a = 0; a < static_cast<int>(anchors.size()); ++a) queue.emplace(0.0, a, anchors[a].idx());
  std::vector<char> settled(n, 0);
  while (!queue.empty()) {
    const auto [d, a, v] = queue.top();
    queue.pop();
    if (settled[v]) continue;
    settled[v] = 1;
    voronoi.cell[v] = a;
    voronoi.distance[v] = d;
    const Eigen::Vector3d p = position(mesh, VertexHandle(v));
    for (const VertexHandle w : mesh.vv_range(VertexHandle(v))) {
      if (settled[w.idx()]) continue;
      const double dw = d + (position(mesh, w) - p).norm();
      if (dw < voronoi.distance[w.idx()]) {
        voronoi.distance[w.idx()] = dw;
        queue.emplace(dw, a, w.idx());
      }
    }
  }
  return voronoi;
}

AnchorVoronoi anchor_voronoi(const Mesh& mesh, const std::vector<VertexHandle>& anchors) {
  AnchorVoronoi voronoi = anchor_cells(mesh, anchors);
  // Per touching pair: the length estimate, and its border edges, joined into stretches where
  // two of them bound one face (a face whose corners lie in three cells ends a stretch).
  std::map<std::pair<int, int>, double> border;
  DisjointSets stretches(static_cast<int>(mesh.n_edges()));
  std::vector<char> on_border(mesh.n_edges(), 0);
  for (const EdgeHandle e : mesh.edges()) {
    const auto [cu, cv] = cells_of(mesh, voronoi, e);
    if (cu == cv || cu < 0 || cv < 0) continue;
    on_border[e.idx()] = 1;
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const double length = voronoi.distance[mesh.from_vertex_handle(h).idx()] + mesh.calc_edge_length(e) +
                          voronoi.distance[mesh.to_vertex_handle(h).idx()];
    const auto [it, inserted] = border.emplace(std::minmax(cu, cv), length);
    if (!inserted) it->second = std::min(it->second, length);
  }
  for (const FaceHandle f : mesh.faces()) {
    std::vector<int> border_edges;
    for (const EdgeHandle e : mesh.fe_range(f)) {
      if (on_border[e.idx()]) border_edges.push_back(e.idx());
    }
    if (border_edges.size() == 2) stretches.unite(border_edges[0], border_edges[1]);
  }
  std::map<std::pair<int, int>, std::set<int>> stretch_roots;
  for (const EdgeHandle e : mesh.edges()) {
    if (!on_border[e.idx()]) continue;
    const auto [cu, cv] = cells_of(mesh, voronoi, e);
    stretch_roots[std::minmax(cu, cv)].insert(stretches.find(e.idx()));
  }
  for (const auto& [pair, length] : border) {
    voronoi.neighbours.push_back(
        {pair.first, pair.second, length, static_cast<int>(stretch_roots[pair].size())});
  }
  return voronoi;
}

std::vector<double> delaunay_graph_distances(const AnchorVoronoi& voronoi, int n_anchors) {
  const double inf = std::numeric_limits<double>::infinity();
  const auto n = static_cast<std::size_t>(n_anchors);
  std::vector<double> d(n * n, inf);
  for (std::size_t i = 0; i < n; ++i) d[i * n + i] = 0.0;
  for (const AnchorNeighbours& pair : voronoi.neighbours) {
    const auto a = static_cast<std::size_t>(pair.a);
    const auto b = static_cast<std::size_t>(pair.b);
    d[a * n + b] = d[b * n + a] = std::min(d[a * n + b], pair.length);
  }
  // Floyd-Warshall: anchors number in the tens to hundreds.
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t i = 0; i < n; ++i) {
      if (d[i * n + k] == inf) continue;
      for (std::size_t j = 0; j < n; ++j) d[i * n + j] = std::min(d[i * n + j], d[i * n + k] + d[k * n + j]);
    }
  }
  return d;
}

}  // namespace xparam
