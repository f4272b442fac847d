#pragma once
/// \file
/// Refinement that gives new paths room: split the mesh edges that would let two blocked
/// vertices (anchors, chain vertices) touch without a chain between them.
///
/// After `make_room` around every chain and anchor, every mesh edge with two blocked ends is a
/// chain edge. Then (1) every wedge of an anchor between two consecutive chains holds a free
/// neighbour, (2) every mesh face has a free corner (three blocked corners would need three
/// chain edges closing a triangle, which disjoint chains of two or more edges never do), and
/// (3) the free vertices of one layout face are connected through mesh edges, so a path between
/// any two corners of a layout face always exists. This is the pre-split of LAYOUT.md; face
/// splits are never needed once the edges are split.

#include "layout/layout.h"
#include "layout/vertex_labels.h"

#include <vector>

namespace xparam {

/// Split at its midpoint every mesh edge incident to a vertex of `around` whose two ends are
/// blocked and that no chain runs along. New vertices are free, lie on the edge's input faces
/// (provenance kept, see core/provenance.h) and are labelled in `labels`.
/// Returns the number of vertices created.
int make_room(LayoutSide& side, VertexLabels& labels, const std::vector<VertexHandle>& around);

}  // namespace xparam
