#pragma once
/// \file
/// How well the remesh covers the target: the distance from every target vertex to the remesh's
/// chord triangles. A bijective map can still leave part of the target out of the remesh's
/// shape: an unanchored finger whose template finger was squeezed onto the palm lies inside
/// one wide remesh triangle's image, so the remesh has a stub where the target has a finger. Fold
/// counts and stretch measured on the remesh do not see that; this does.

#include "core/mesh.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// A target point is uncovered when it lies farther than this fraction of sqrt(target area)
/// from the remesh (1.4 cm on an adult body; the chord's sagitta on a 7k-vertex body is a
/// millimetre or less).
constexpr double kUncoveredGap = 0.01;

/// What measure_remesh_coverage found.
struct RemeshCoverage {
  /// Per target vertex: its distance to the remesh, target units.
  std::vector<double> gap;
  double max_gap = 0.0;         ///< largest gap divided by sqrt(target area)
  double uncovered_area = 0.0;  ///< share of the target's area (a third of each face per corner) at vertices farther than kUncoveredGap sqrt(area)
  int uncovered_vertices = 0;   ///< target vertices farther than that
};

/// Each vertex's area: a third of the area of each face round it (they sum to the mesh's area).
std::vector<double> vertex_areas(const Mesh& mesh);

/// The distance of every target vertex to the remesh whose vertex i lies at positions[i], faces
/// `faces` (template vertex ids). \pre positions and faces non-empty, indices valid
RemeshCoverage measure_remesh_coverage(const Mesh& target, const std::vector<Eigen::Vector3d>& positions,
                                       const std::vector<std::array<int, 3>>& faces);

}  // namespace xparam
