#pragma once
/// \file
/// Cutting a closed mesh open along a cycle of its edges: the step of the handle cut that needs
/// no CGAL (the cycle comes from cgal_topology.h, the caps from cgal_repair.h's fill_holes).

#include "intake/cgal_repair.h"

#include <vector>

namespace xparam::intake {

/// Cut the mesh open along `cycle` (its vertices in order, the last joined to the first): every
/// cycle vertex is copied, and the faces on the left of the cycle (those holding the edge
/// cycle[i] -> cycle[i + 1] in their corner order, and the faces turning around cycle[i] from
/// there to the edge cycle[i - 1] -> cycle[i]) take the copy instead. A non-separating cycle
/// leaves two boundary loops along it. The copies are appended to `points`, in the cycle's order;
/// returned: the point each copy copies (cycle order). Faces keep their numbers and corner order.
/// \pre a closed, oriented, manifold mesh; `cycle` a simple cycle of its edges, at least 3 vertices
std::vector<int> cut_along_cycle(std::vector<Point>& points, std::vector<Triangle>& triangles,
                                 const std::vector<int>& cycle);

}  // namespace xparam::intake
