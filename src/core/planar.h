#pragma once
/// \file
/// Planar helpers shared by the stages that flatten surface pieces (funnels, stars, discs).

#include <Eigen/Core>

namespace xparam {

/// z of the cross product of two plane vectors: twice the signed area of the triangle (0, a, b),
/// positive when b lies counter-clockwise of a.
inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace xparam
