#pragma once
/// \file
/// Body measurements defined on the template (docs/measurements.md, schemas/measurements.schema.json):
/// plane girths, straight and geodesic distances and heights, each through template vertices, and
/// the lengths of the template's feature curves, so that the same definition is evaluated on the
/// template and, through the map, on every target (measure/body_measurements.h).

#include <Eigen/Core>

#include <string>
#include <vector>

namespace xparam {

/// What a measurement measures.
enum class MeasurementKind {
  /// The length of a plane's section of the surface (a tape measure laid in a plane): the loop
  /// nearest a reference point, or the convex hull of that loop (the tape bridges hollows).
  PlaneGirth,
  /// The length of the straight polyline through the points, in order (two points: their distance).
  Straight,
  /// The length of the shortest path on the surface through the points, in order (two points:
  /// their geodesic distance): a tape laid on the skin from landmark to landmark.
  Geodesic,
  /// How far a point lies above the lowest point of the surface along an "up" direction (the
  /// height above the floor the body stands on).
  Height,
  /// The length of one of the template's feature curves (core/feature_curves.h) as it lies on the
  /// surface: on the template traced on its own faces, on a target its image traced on the
  /// target's (map/curve_tracing.h); open or closed as the curve file says.
  CurveLength,
};

/// How a girth's plane is chosen. Points are template vertex indices (file numbering).
struct PlaneRule {
  /// One point with a normal rule below, or three points the plane passes through.
  std::vector<int> through;
  /// With one `through` point: the normal runs from `normal_from` to `normal_to` (two template
  /// vertices, so the plane follows the body's pose, e.g. a limb's axis); -1 when the normal is
  /// the fixed `normal` instead.
  int normal_from = -1;
  int normal_to = -1;  ///< see normal_from
  /// With one `through` point and no normal_from/normal_to: a fixed normal in the template's
  /// coordinates (e.g. its up axis), turned onto a target by the set's frame. Unit length.
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

/// One measurement, its points resolved to template vertices.
struct MeasurementDefinition {
  std::string name;  ///< unique within its set
  MeasurementKind kind = MeasurementKind::Straight;
  PlaneRule plane;        ///< PlaneGirth: the plane
  bool convex_hull = false;  ///< PlaneGirth: measure the section loop's convex hull (the tape measure)
  int near = -1;          ///< PlaneGirth: the section loop nearest this template vertex is measured
  std::vector<int> points;  ///< Straight, Geodesic: the path's vertices (>= 2); Height: the one point
  bool closed = false;      ///< Straight, Geodesic: the last point joins the first
  /// Height: the up direction in the template's coordinates (turned like a fixed normal), unit length
  Eigen::Vector3d up = Eigen::Vector3d::Zero();
  int curve = -1;  ///< CurveLength: the template's feature curve, its index in the curve file
};

/// The points that carry the set's fixed directions (a plane's `normal`, a height's `up`, given in
/// the template's coordinates) onto a surface: on a target, the rotation that best fits the images
/// of these points to their template positions turns every fixed direction
/// (measure/measurement_frame.h), so a body turned or moved in space measures as the template's
/// frame would measure it upright.
struct MeasurementFrame {
  std::vector<int> vertices;         ///< template vertices (file numbering); empty: directions taken as given
  Eigen::MatrixX3d template_points;  ///< #vertices x 3: where they lie on the template
};

/// A measurement file as read and resolved against a template.
struct MeasurementSet {
  std::string source;  ///< the file, named in messages
  /// The length unit of the template's coordinates (e.g. "m"); every value is in it.
  std::string unit;
  std::vector<MeasurementDefinition> measurements;  ///< in file order
  MeasurementFrame frame;  ///< how fixed directions follow a target's pose; empty: not at all
};

}  // namespace xparam
