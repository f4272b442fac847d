#pragma once
/// \file
/// Feature curves carried onto the target as curves on its surface (ARCHITECTURE.md step 9):
/// every template segment between consecutive curve points is followed across the template's
/// faces (core/surface_path.h), each edge crossing is carried through the map, and consecutive
/// images are joined by a path across the target's faces, so the transferred polyline has a
/// point wherever it crosses a target edge and each of its pieces lies inside one target face.

#include "core/feature_curves.h"
#include "core/mesh.h"
#include "core/surface_point.h"

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace xparam {

/// One template curve carried onto the target.
struct MappedCurve {
  std::string name;
  std::vector<SurfacePoint> points;        ///< on the target input mesh (face + barycentrics, fv order)
  std::vector<Eigen::Vector3d> positions;  ///< the same points in 3-D
  bool closed = false;
  /// Segments (on the template, then on the target) whose surface path could not be followed
  /// and that are a straight chord instead (surface_path_crossings refused: a section that
  /// does not run from one point to the other); 0 when the curve lies on the surface throughout.
  int chord_segments = 0;
};

/// The map applied to one point of the template's input mesh: its image, a point of the
/// target's input mesh.
using CurvePointMap = std::function<SurfacePoint(const SurfacePoint&)>;

/// Carry `curve` (on `source`, the template's input mesh) onto `target` through `map`.
/// The result starts at the image of the curve's first point, passes through the image of
/// every curve point, and (closed curves) does not repeat the first point at the end.
MappedCurve trace_curve(const FeatureCurve& curve, const Mesh& source, const Mesh& target, const CurvePointMap& map);

/// The length of a polyline through `positions` (with the closing segment when `closed`).
double polyline_length(const std::vector<Eigen::Vector3d>& positions, bool closed);

}  // namespace xparam
