#pragma once
/// \file
/// What each mesh vertex of one layout side is: an anchor, a chain's interior vertex, or free.
/// Paths may only pass through free vertices; refinement and tracing read these labels.

#include "layout/layout.h"

#include <vector>

namespace xparam {

/// Per-vertex labels of one side, indexed by vertex id.
struct VertexLabels {
  std::vector<int> anchor;    ///< anchor index at the vertex, or -1
  std::vector<int> edge;      ///< layout edge whose chain has the vertex in its interior, or -1
  std::vector<int> position;  ///< index of the vertex in that chain, or -1

  /// True when no new path may pass through vertex v (an anchor or on a chain).
  bool blocked(VertexHandle v) const { return anchor[v.idx()] >= 0 || edge[v.idx()] >= 0; }

  /// Grow to `n_vertices` entries; new vertices are free.
  void resize(std::size_t n_vertices);
};

/// Labels of every vertex of `layout.sides[side]` from its anchors and chains.
VertexLabels label_vertices(const Layout& layout, int side);

/// Record `chain` (vertices from one anchor to another) as the chain of layout edge `edge`.
void label_chain(VertexLabels& labels, int edge, const std::vector<VertexHandle>& chain);

/// True when the mesh edge (v, w) is an edge of some chain of `side`.
bool is_chain_edge(const LayoutSide& side, const VertexLabels& labels, VertexHandle v, VertexHandle w);

/// The layout halfedge whose chain leaves anchor vertex `anchor` along mesh halfedge `out`,
/// or -1 when `out` starts no chain.
int chain_leaving(const LayoutSide& side, const VertexLabels& labels, HalfedgeHandle out);

}  // namespace xparam
