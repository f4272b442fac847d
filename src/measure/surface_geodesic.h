#pragma once
/// \file
/// The length of the shortest path on a surface through points on it, in order: a tape laid on
/// the skin from landmark to landmark (docs/measurements.md, `geodesic`). The surface is not
/// touched: the points become vertices of a copy (an existing vertex, an edge split or a face
/// split), Dijkstra along the copy's edges gives a first path between consecutive points, and the
/// funnel with re-routing around vertices (geodesic/straighten_path.h, the whole surface as the
/// region) shortens it into a locally shortest geodesic: straight in the unfolding of the faces it
/// crosses, and at least pi on both sides of every vertex it passes through. Between points whose
/// edge path runs the short way (every body measurement) that is the shortest path; a locally
/// shortest path of another kind (round the far side of a limb) is found only when Dijkstra's path
/// already runs there.

#include "core/mesh.h"

#include <Eigen/Core>

#include <limits>
#include <vector>

namespace xparam {

/// Options of surface_geodesic.
struct SurfaceGeodesicSettings {
  /// A point closer than this to a vertex (an edge) of the face it lies in is that vertex (is put
  /// on that edge), so no sliver triangle is cut where only rounding moved a point off a vertex.
  /// Fraction of the surface's bounding-box diagonal; every point moves by at most this much, so a
  /// segment's length changes by at most twice it.
  double snap_tolerance = 1e-7;
};

/// What surface_geodesic measured.
struct SurfaceGeodesic {
  /// The geodesic polyline's length (mesh units); NaN when two consecutive points lie on parts
  /// of the surface that no path joins, or a segment could not be straightened.
  double length = std::numeric_limits<double>::quiet_NaN();
  /// Per segment (point k to k + 1, then the closing one): its geodesic length.
  std::vector<double> segment_lengths;
  /// The Dijkstra paths' total length along mesh edges: an upper bound of `length`.
  double edge_path_length = std::numeric_limits<double>::quiet_NaN();
  /// How far the farthest point lay from the surface (mesh units): the points are measured at
  /// their nearest surface points.
  double max_point_distance = 0.0;
  bool converged = true;  ///< false when a segment's funnel stopped at its round limit
  SurfaceGeodesicSettings settings;
};

/// The shortest path on `surface` through `points` in order (`closed`: back to the first),
/// each point taken at its nearest surface point. Deterministic; `surface` is left unchanged.
/// \pre points.size() >= 2, every point finite; `surface` a triangle mesh with >= 1 face
SurfaceGeodesic surface_geodesic(const Mesh& surface, const std::vector<Eigen::Vector3d>& points, bool closed,
                                 const SurfaceGeodesicSettings& settings = {});

}  // namespace xparam
