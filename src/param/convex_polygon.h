#pragma once
/// \file
/// Small predicates on planar polygons used by the parameterization and the domain maps.

#include "core/planar.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// True when `polygon` (#k >= 3 corners) is simple, strictly convex (every corner turns left,
/// no two consecutive sides collinear) and counter-clockwise (winds once).
bool is_strictly_convex(const std::vector<Eigen::Vector2d>& polygon);

}  // namespace xparam
