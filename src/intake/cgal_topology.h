#pragma once
/// \file
/// The intake's one job for CGAL's Surface_mesh_topology (GPL-3.0-or-later): a short
/// non-contractible cycle of a closed mesh. Like cgal_repair.h, plain arrays in and out; CGAL is
/// included by cgal_topology.cpp alone, so its compile cost stays in one translation unit.

#include "intake/cgal_repair.h"

#include <vector>

namespace xparam::intake {

/// A closed walk along a mesh's edges and its length.
struct EdgeCycle {
  /// Vertices in order, consecutive ones (and the last with the first) joined by an edge; no step
  /// goes back along the edge it came, but a vertex may come twice (a figure eight).
  std::vector<int> vertices;
  double length = 0.0;  ///< Euclidean, mesh units
};

/// A short non-contractible cycle of a closed, oriented mesh of genus > 0 under Euclidean edge
/// lengths. Empty when every cycle is contractible (genus 0). Deterministic.
///
/// CGAL's global search (compute_shortest_non_contractible_cycle) runs a shortest-path search from
/// every vertex: quadratic, over 10 minutes on a 15k-vertex scan. This is a descent instead: the
/// shortest loop through vertex 0 (a lasso whose noose goes around a handle), then, while one is
/// shorter, the shortest loops through a few vertices spread along the best loop so far
/// (compute_shortest_non_contractible_cycle_with_base_point: one shortest-path search each). It
/// finds a handle's short loop around it, not always the globally shortest one.
/// \pre a valid, closed, oriented polygon mesh of one component
EdgeCycle short_non_contractible_cycle(const std::vector<Point>& points,
                                      const std::vector<Triangle>& triangles);

}  // namespace xparam::intake
