#include "map/curve_tracing.h"

#include "core/surface_path.h"

#include <optional>

namespace xparam {
namespace {

// `points` with every segment (the closing one too, when closed) replaced by its surface path
// on `mesh`; a segment whose path cannot be followed stays a chord and is counted.
std::vector<SurfacePoint> along_surface(const Mesh& mesh, const std::vector<SurfacePoint>& points, bool closed,
                                        int& chords) {
  std::vector<SurfacePoint> dense;
  const std::size_t n = points.size();
  const std::size_t segments = closed ? n : n - 1;
  dense.push_back(points.front());
  for (std::size_t i = 0; i < segments; ++i) {
    const SurfacePoint& next = points[(i + 1) % n];
    const std::optional<std::vector<SurfacePoint>> crossings = surface_path_crossings(mesh, points[i], next);
    if (crossings)
      dense.insert(dense.end(), crossings->begin(), crossings->end());
    else
      ++chords;
    if (i + 1 < n) dense.push_back(next);
  }
  return dense;
}

}  // namespace

MappedCurve trace_curve(const FeatureCurve& curve, const Mesh& source, const Mesh& target, const CurvePointMap& map) {
  MappedCurve mapped;
  mapped.name = curve.name;
  mapped.closed = curve.closed;
  if (curve.points.empty()) return mapped;
  // On the template: the curve's segments as paths across its faces.
  const std::vector<SurfacePoint> on_template = along_surface(source, curve.points, curve.closed, mapped.chord_segments);
  // Through the map, then joined across the target's faces.
  std::vector<SurfacePoint> images;
  images.reserve(on_template.size());
  for (const SurfacePoint& point : on_template) images.push_back(map(point));
  mapped.points = along_surface(target, images, curve.closed, mapped.chord_segments);
  for (const SurfacePoint& point : mapped.points) mapped.positions.push_back(position(target, point));
  return mapped;
}

double polyline_length(const std::vector<Eigen::Vector3d>& positions, bool closed) {
  double length = 0.0;
  for (std::size_t i = 1; i < positions.size(); ++i) length += (positions[i] - positions[i - 1]).norm();
  if (closed && positions.size() > 2) length += (positions.front() - positions.back()).norm();
  return length;
}

}  // namespace xparam
