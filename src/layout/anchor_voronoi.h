#pragma once
/// \file
/// Geodesic Voronoi cells of the anchors (one multi-source Dijkstra along mesh edges) and the
/// anchor pairs whose cells touch: the intrinsic Delaunay neighbours, the candidate layout
/// edges that are tried first (LAYOUT.md, "Candidates").

#include "core/mesh.h"

#include <vector>

namespace xparam {

/// Two anchors whose Voronoi cells share a mesh edge, with the length of the shortest edge path
/// between them that crosses the shared border once: d(u) + |uv| + d(v) minimised over border
/// edges (u, v).
struct AnchorNeighbours {
  int a = -1;           ///< smaller anchor index
  int b = -1;           ///< larger anchor index
  double length = 0.0;  ///< 3-D units
  /// Separate stretches of border the cells share: 1 for an intrinsic Delaunay edge; 2 or more
  /// where the cells meet on two sides of something (a limb or a neck with an anchor at its
  /// front and one at its back), so an edge between them may pass either way.
  int borders = 1;
};

/// The Voronoi partition of one mesh by its anchors.
struct AnchorVoronoi {
  std::vector<int> cell;                     ///< #vertices: index of the nearest anchor (edge-path metric)
  std::vector<double> distance;              ///< #vertices: edge-path distance to that anchor
  std::vector<AnchorNeighbours> neighbours;  ///< touching cells, sorted by (a, b)
};

/// Cells of `anchors` (distinct vertices of a connected mesh) by multi-source Dijkstra.
/// Deterministic: ties go to the smaller vertex id, then the smaller anchor.
AnchorVoronoi anchor_voronoi(const Mesh& mesh, const std::vector<VertexHandle>& anchors);

/// The same cells and distances without the neighbours (left empty), for callers that need only
/// those (the neighbours take a pass over every edge and face, and maps of the border).
AnchorVoronoi anchor_cells(const Mesh& mesh, const std::vector<VertexHandle>& anchors);

/// All-pairs anchor distances along the Delaunay graph of `voronoi` (#anchors x #anchors, row
/// major; infinity between anchors of different components). Equals the neighbour length for
/// touching cells whose direct estimate is shortest; an upper bound of the geodesic otherwise.
std::vector<double> delaunay_graph_distances(const AnchorVoronoi& voronoi, int n_anchors);

}  // namespace xparam
