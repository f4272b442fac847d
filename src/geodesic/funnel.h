#pragma once
/// \file
/// The funnel algorithm (Lee & Preparata 1984): the shortest path through a sequence of
/// portals of a triangle strip unfolded into the plane.

#include "core/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// One edge a strip crosses, seen by a traveller walking the strip: `left` is on the
/// traveller's left. Endpoints carry the mesh vertex they were unfolded from.
struct Portal {
  VertexHandle left;
  VertexHandle right;
  Eigen::Vector2d left_point = Eigen::Vector2d::Zero();
  Eigen::Vector2d right_point = Eigen::Vector2d::Zero();

  bool has(VertexHandle v) const { return left == v || right == v; }
};

/// A corner of a funnel path: a portal endpoint the path bends at, or the path's start or end.
struct FunnelApex {
  int portal = -1;  ///< portal index whose endpoint this is; -1 for the start, portals.size() for the end
  VertexHandle vertex;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
};

/// Shortest path from `start` to `end` that crosses every portal in order, as its corners:
/// start, the portal endpoints it bends at (in order), end. A portal that has the current
/// corner's vertex as an endpoint (the strip turning around that vertex) is crossed at it.
/// Collinear contacts count as corners (the path passes through that vertex straight).
/// O(n^2) worst case, O(n) typical, for n portals.
/// \pre start.portal == -1, end.portal == portals.size(); the portals come from one
/// consistently oriented unfolding (every left endpoint left of the walk)
std::vector<FunnelApex> funnel_path(const std::vector<Portal>& portals, const FunnelApex& start,
                                    const FunnelApex& end);

}  // namespace xparam
