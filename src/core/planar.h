#pragma once
/// \file
/// Planar helpers shared by the stages that flatten surface pieces (funnels, stars, discs, patch
/// polygons, plane sections).

#include <Eigen/Core>

namespace xparam {

/// z of the cross product of two plane vectors: twice the signed area of the triangle (0, a, b),
/// positive when b lies counter-clockwise of a.
inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Twice the signed area of triangle (a, b, c): positive when counter-clockwise.
inline double signed_area2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

}  // namespace xparam
