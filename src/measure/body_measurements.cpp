#include "measure/body_measurements.h"

#include "core/errors.h"
#include "measure/measurement_frame.h"
#include "measure/plane_section.h"
#include "measure/surface_geodesic.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace xparam {
namespace {

// What a measurement that cannot be taken (no plane, no section) reads.
constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

Eigen::Vector3d point_of(const Eigen::MatrixX3d& vertex_points, int vertex) {
  XP_ASSERT(vertex >= 0 && vertex < vertex_points.rows());
  return vertex_points.row(vertex).transpose();
}

// The plane's origin and unit normal; nothing when its points do not define one.
std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> plane_of(const PlaneRule& rule,
                                                                    const Eigen::MatrixX3d& vertex_points,
                                                                    const Eigen::Matrix3d& frame) {
  const Eigen::Vector3d origin = point_of(vertex_points, rule.through.front());
  Eigen::Vector3d normal = frame * rule.normal;
  if (rule.through.size() == 3) {
    normal = (point_of(vertex_points, rule.through[1]) - origin).cross(point_of(vertex_points, rule.through[2]) - origin);
  } else if (rule.normal_from >= 0) {
    normal = point_of(vertex_points, rule.normal_to) - point_of(vertex_points, rule.normal_from);
  }
  if (!(normal.norm() > 0.0) || !normal.allFinite()) return std::nullopt;
  return std::make_pair(origin, normal.normalized());
}

double plane_girth(const MeasurementDefinition& m, const Mesh& surface, const Eigen::MatrixX3d& vertex_points,
                   const Eigen::Matrix3d& frame) {
  const auto plane = plane_of(m.plane, vertex_points, frame);
  if (!plane) return kNotMeasured;
  const std::vector<SectionLoop> loops = plane_section(surface, plane->first, plane->second);
  if (loops.empty()) return kNotMeasured;
  // The loop the tape goes round: nearest the reference point (first such loop on a tie).
  const Eigen::Vector3d near = point_of(vertex_points, m.near);
  const auto nearest = std::min_element(loops.begin(), loops.end(), [&](const SectionLoop& a, const SectionLoop& b) {
    return distance_to_loop(a, near) < distance_to_loop(b, near);
  });
  return m.convex_hull ? convex_hull_perimeter(nearest->points, plane->second) : nearest->length();
}

double straight(const MeasurementDefinition& m, const Eigen::MatrixX3d& vertex_points) {
  double total = 0.0;
  for (std::size_t i = 1; i < m.points.size(); ++i)
    total += (point_of(vertex_points, m.points[i]) - point_of(vertex_points, m.points[i - 1])).norm();
  if (m.closed) total += (point_of(vertex_points, m.points.front()) - point_of(vertex_points, m.points.back())).norm();
  return total;
}

// A tape on the skin: the shortest path on the surface through the points' images.
double geodesic(const MeasurementDefinition& m, const Mesh& surface, const Eigen::MatrixX3d& vertex_points) {
  std::vector<Eigen::Vector3d> points;
  for (const int vertex : m.points) points.push_back(point_of(vertex_points, vertex));
  return surface_geodesic(surface, points, m.closed).length;
}

// Above the floor: the lowest surface vertex along `up`.
double height(const MeasurementDefinition& m, const Mesh& surface, const Eigen::MatrixX3d& vertex_points,
              const Eigen::Matrix3d& frame) {
  const Eigen::Vector3d up = frame * m.up;
  double floor = std::numeric_limits<double>::infinity();
  for (const VertexHandle v : surface.vertices()) floor = std::min(floor, up.dot(position(surface, v)));
  return up.dot(point_of(vertex_points, m.points.front())) - floor;
}

}  // namespace

double measure_one(const MeasurementDefinition& measurement, const Mesh& surface,
                   const Eigen::MatrixX3d& vertex_points, const std::vector<double>& curve_lengths,
                   const Eigen::Matrix3d& frame) {
  switch (measurement.kind) {
    case MeasurementKind::PlaneGirth:
      return plane_girth(measurement, surface, vertex_points, frame);
    case MeasurementKind::Straight:
      return straight(measurement, vertex_points);
    case MeasurementKind::Geodesic:
      return geodesic(measurement, surface, vertex_points);
    case MeasurementKind::Height:
      return height(measurement, surface, vertex_points, frame);
    case MeasurementKind::CurveLength:
      XP_ASSERT(measurement.curve >= 0 && static_cast<std::size_t>(measurement.curve) < curve_lengths.size());
      return curve_lengths[static_cast<std::size_t>(measurement.curve)];
  }
  XP_ASSERT_MSG(false, "unknown measurement kind");
  return kNotMeasured;
}

std::vector<double> measure_surface(const MeasurementSet& set, const Mesh& surface,
                                    const Eigen::MatrixX3d& vertex_points,
                                    const std::vector<double>& curve_lengths) {
  const Eigen::Matrix3d frame = frame_rotation(set.frame, vertex_points);
  std::vector<double> values;
  values.reserve(set.measurements.size());
  for (const MeasurementDefinition& m : set.measurements)
    values.push_back(measure_one(m, surface, vertex_points, curve_lengths, frame));
  return values;
}

}  // namespace xparam
