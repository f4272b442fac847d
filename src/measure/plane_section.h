#pragma once
/// \file
/// The section of a surface by a plane: the polylines where the plane cuts the mesh's faces,
/// chained into loops, as a tape measure laid in that plane would follow them.

#include "core/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// One connected piece of a plane section.
struct SectionLoop {
  std::vector<Eigen::Vector3d> points;  ///< in order along the section (each on a mesh edge)
  bool closed = true;                   ///< false only where the mesh has a boundary
  /// The length of the polyline (with the closing segment when closed), mesh units.
  double length() const;
};

/// The plane {x : normal . (x - origin) = 0} cutting `mesh`: one loop per connected piece.
/// A vertex exactly on the plane counts as above it, so every loop is a clean polygon through
/// edge points. Deterministic: loops start at their lowest-numbered crossed edge, in that order.
/// \pre normal has unit length
std::vector<SectionLoop> plane_section(const Mesh& mesh, const Eigen::Vector3d& origin, const Eigen::Vector3d& normal);

/// The distance from `point` to the nearest segment of `loop`.
double distance_to_loop(const SectionLoop& loop, const Eigen::Vector3d& point);

/// The perimeter of the convex hull of `points` seen along `normal` (projected into the plane
/// perpendicular to it): the length of a tape stretched round them. 0 for fewer than 2 points.
/// \pre normal has unit length
double convex_hull_perimeter(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal);

}  // namespace xparam
