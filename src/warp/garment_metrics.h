#pragma once
/// \file
/// How a warped garment sits on a body and how much it changed against its rest shape:
/// penetration (TailorNet/SNUG count vertices inside the body), edge-length ratios and
/// per-triangle stretch (the larger singular value of the rest-to-warped triangle map).

#include "core/triangle_soup.h"
#include "warp/body_distance.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// Mean, 95th percentile (nearest rank), largest and smallest of a set of values; NaN when empty.
struct ValueSummary {
  double mean = 0.0;  ///< arithmetic mean
  double p95 = 0.0;   ///< the value at rank ceil(0.95 n) of the sorted values
  double max = 0.0;   ///< largest value
  double min = 0.0;   ///< smallest value
};

/// Summarize `values` (sorted here; the order given does not matter). NaNs when empty.
ValueSummary summarize(std::vector<double> values);

/// Garment vertices inside a body.
struct Penetration {
  int count = 0;           ///< vertices with a negative signed distance
  double max_depth = 0.0;  ///< deepest of them, body units (0 when none)
};

/// The penetration of `vertices` into `body`.
Penetration penetration(const std::vector<Eigen::Vector3d>& vertices, const BodyDistance& body);

/// A warped garment against its rest shape.
struct ShapeChange {
  ValueSummary edge_ratio;  ///< over the garment's edges: warped length / rest length
  ValueSummary stretch;     ///< over its triangles: largest singular value of rest -> warped (1: not stretched)
};

/// Check that a rest garment can be measured against: at least one triangle, every vertex
/// finite, every triangle of nonzero area. \throw InputError "G.obj: face F ...; fix"
void check_rest_garment(const TriangleSoup& garment);

/// Edge ratios and triangle stretch of `warped` against `rest` (same vertex order, `triangles`).
/// \pre rest triangles not degenerate (their edges have length > 0)
ShapeChange shape_change(const std::vector<Eigen::Vector3d>& rest, const std::vector<Eigen::Vector3d>& warped,
                         const std::vector<std::array<int, 3>>& triangles);

}  // namespace xparam
