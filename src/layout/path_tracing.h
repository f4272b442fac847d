#pragma once
/// \file
/// Tracing one layout path: the shortest chain of mesh edges between two anchors that leaves
/// and enters them through given wedges and passes only through free vertices. Because chains
/// bound the layout faces, a path that starts in a corner's wedge stays in that corner's face:
/// "trace inside a region between two corners" is this function with the two corners' wedges.

#include "layout/layout.h"
#include "layout/vertex_labels.h"

#include <functional>
#include <limits>
#include <vector>

namespace xparam {

/// A wedge at an anchor vertex: the outgoing mesh halfedges strictly counter-clockwise after
/// `after` up to (not including) the next halfedge that starts a chain. With `after` invalid,
/// the whole one-ring (an anchor no chain touches yet).
struct MeshWedge {
  VertexHandle anchor;
  HalfedgeHandle after;
};

/// The wedge of the corner named by layout halfedge `h` on `side`: counter-clockwise from the
/// first mesh edge of h's chain. `h` = -1 gives the whole one-ring of `anchor`.
MeshWedge corner_wedge(const Layout& layout, int side, int anchor, int h);

/// Free vertices adjacent to the wedge's anchor inside the wedge, in counter-clockwise order.
std::vector<VertexHandle> wedge_vertices(const LayoutSide& side, const VertexLabels& labels,
                                         const MeshWedge& wedge);

/// The layout halfedge naming the wedge that mesh halfedge `out` (leaving an anchor) lies in:
/// the first chain met turning clockwise from `out`; -1 when no chain leaves the anchor.
int wedge_of(const LayoutSide& side, const VertexLabels& labels, HalfedgeHandle out);

/// A traced path: anchor, free vertices, anchor; empty when none exists.
struct TracedPath {
  std::vector<VertexHandle> vertices;
  double length = std::numeric_limits<double>::infinity();  ///< sum of 3-D edge lengths
  bool found() const { return !vertices.empty(); }
};

/// Reusable shortest-path buffers for one mesh (grown on demand); reuse pays when tracing many paths.
struct TraceScratch {
  std::vector<double> distance;
  std::vector<int> parent;
  std::vector<unsigned> stamp;
  /// The `passable` answer for a vertex, valid where passable_stamp equals this search's stamp:
  /// a vertex is asked once per search instead of once per neighbour settled.
  std::vector<unsigned> passable_stamp;
  std::vector<char> passable_answer;
  unsigned current = 0;
};

/// Which vertices (by id) a path may pass through besides being free; empty: every free vertex.
using PassableVertex = std::function<bool(int)>;

/// Shortest path (Euclidean edge lengths; A*, goal-directed by the straight line to `to`) from
/// anchor vertex `from` to anchor vertex `to` whose second vertex is one of `first` and whose
/// second-to-last is one of `last`, through free vertices only (and only `passable` ones, when
/// given). Deterministic: ties in the queue go to the smaller vertex id.
TracedPath trace_path(const Mesh& mesh, const VertexLabels& labels, VertexHandle from,
                      const std::vector<VertexHandle>& first, VertexHandle to,
                      const std::vector<VertexHandle>& last, TraceScratch& scratch,
                      const PassableVertex& passable = {});

}  // namespace xparam
