#pragma once
/// \file
/// Small predicates on planar polygons used by the parameterization and the domain maps.

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// Twice the signed area of triangle (a, b, c): positive when counter-clockwise.
inline double signed_area2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// True when `polygon` (#k >= 3 corners) is simple, strictly convex (every corner turns left,
/// no two consecutive sides collinear) and counter-clockwise (winds once).
bool is_strictly_convex(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace xparam
