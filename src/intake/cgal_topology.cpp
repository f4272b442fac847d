// The second and last translation unit of xparam that includes CGAL (see cgal_topology.h).
#include "intake/cgal_topology.h"

#include "core/errors.h"

#include <CGAL/Curves_on_surface_topology.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Path_on_surface.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>

namespace xparam::intake {
namespace {

using SurfaceMesh = CGAL::Surface_mesh<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
namespace SMT = CGAL::Surface_mesh_topology;

// Rounds of the descent and base points tried per round (see short_non_contractible_cycle).
constexpr int kMaxRounds = 12;
constexpr int kBasePointsPerRound = 8;

// A closed walk's vertices with its back-and-forth steps removed: a shortest-path loop through a
// base point off the handle is a lasso, whose stem is walked there and back; what is left is
// freely homotopic to the walk, so it stays non-contractible.
std::vector<int> without_spurs(std::vector<int> walk) {
  for (bool removed = true; removed && walk.size() > 2;) {
    removed = false;
    const std::size_t n = walk.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (walk[(i + n - 1) % n] != walk[(i + 1) % n]) continue;
      // Drop walk[i] and the repeated walk[i + 1] (indices taken before erasing).
      const std::size_t next = (i + 1) % n;
      walk.erase(walk.begin() + static_cast<std::ptrdiff_t>(std::max(i, next)));
      walk.erase(walk.begin() + static_cast<std::ptrdiff_t>(std::min(i, next)));
      removed = true;
      break;
    }
  }
  return walk;
}

double loop_length(const std::vector<Point>& points, const std::vector<int>& loop) {
  double length = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Point& a = points[loop[i]];
    const Point& b = points[loop[(i + 1) % loop.size()]];
    length += std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  }
  return length;
}

}  // namespace

EdgeCycle short_non_contractible_cycle(const std::vector<Point>& points,
                                      const std::vector<Triangle>& triangles) {
  SurfaceMesh mesh;
  for (const Point& p : points) mesh.add_vertex({p[0], p[1], p[2]});
  for (const Triangle& t : triangles) {
    const auto f = mesh.add_face(VertexIndex(t[0]), VertexIndex(t[1]), VertexIndex(t[2]));
    XP_ASSERT_MSG(f != SurfaceMesh::null_face(), "triangle (" << t[0] << ", " << t[1] << ", " << t[2]
                                                              << ") is not manifold before the handle cut");
  }
  const SMT::Curves_on_surface_topology<SurfaceMesh> topology(mesh);
  const SMT::Euclidean_length_weight_functor<SurfaceMesh> weight(mesh);

  // The shortest non-contractible loop through one vertex, spurs removed.
  const auto loop_through = [&](int vertex) -> EdgeCycle {
    const SMT::Path_on_surface<SurfaceMesh> path =
        topology.compute_shortest_non_contractible_cycle_with_base_point(mesh.halfedge(VertexIndex(vertex)), weight);
    // Each vertex of the walk is the one two consecutive edges share (the path's own halfedge
    // directions are the wrapper's business, not ours).
    std::vector<int> walk;
    const std::size_t n = path.length();
    for (std::size_t i = 0; i < n; ++i) {
      const auto a = path[i];
      const auto b = path[(i + 1) % n];
      const VertexIndex a0 = mesh.source(a), a1 = mesh.target(a);
      walk.push_back(static_cast<int>(((a1 == mesh.source(b) || a1 == mesh.target(b)) ? a1 : a0).idx()));
    }
    std::vector<int> loop = without_spurs(std::move(walk));
    const double length = loop_length(points, loop);
    return {std::move(loop), length};
  };

  EdgeCycle best = loop_through(0);
  if (best.vertices.empty()) return best;
  for (int round = 0; round < kMaxRounds; ++round) {
    // Base points spread evenly along the best loop so far; the first round's loop is a lasso
    // from vertex 0 whose noose, around the handle, is among them.
    const std::vector<int> base = best.vertices;
    bool improved = false;
    const std::size_t step = std::max<std::size_t>(1, base.size() / kBasePointsPerRound);
    for (std::size_t i = 0; i < base.size(); i += step) {
      EdgeCycle loop = loop_through(base[i]);
      if (loop.length < best.length * (1.0 - 1e-12)) {
        best = std::move(loop);
        improved = true;
      }
    }
    if (!improved) break;
  }
  return best;
}

}  // namespace xparam::intake
