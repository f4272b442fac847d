#include "core/feature_curves.h"

#include "core/anchors.h"
#include "core/errors.h"

#include <map>

namespace xparam {
namespace {

std::string curve_where(const FeatureCurveSet& set, const FeatureCurveSpec& curve) {
  std::string out = set.source;
  if (curve.line > 0) out.append(":").append(std::to_string(curve.line));
  return out.append(": curve \"").append(curve.name).append("\"");
}

// Two points closer than this (a fraction of the bounding-box diagonal) are one place.
constexpr double kSamePlace = 1e-12;

}  // namespace

std::vector<FeatureCurve> validate_curves(const FeatureCurveSet& set, const Mesh& input) {
  const int n_vertices = static_cast<int>(input.n_vertices());
  const int n_faces = static_cast<int>(input.n_faces());
  const double same_place = kSamePlace * bounding_box_diagonal(input);
  std::map<std::string, const FeatureCurveSpec*> by_name;
  std::vector<FeatureCurve> curves;
  for (const FeatureCurveSpec& spec : set.curves) {
    const std::string where = curve_where(set, spec);
    if (spec.name.empty()) throw InputError(where + ": empty name");
    if (const auto [it, inserted] = by_name.emplace(spec.name, &spec); !inserted) {
      throw InputError(where + ": duplicate name (first at line " + std::to_string(it->second->line) + ")");
    }
    const int needed = spec.closed ? 3 : 2;
    if (static_cast<int>(spec.points.size()) < needed) {
      throw InputError(where + ": " + std::to_string(spec.points.size()) + " points; " +
                       (spec.closed ? "a closed" : "an open") + " curve needs at least " +
                       std::to_string(needed));
    }
    FeatureCurve curve{spec.name, {}, spec.closed};
    std::vector<Eigen::Vector3d> places;
    for (int i = 0; i < static_cast<int>(spec.points.size()); ++i) {
      const std::string at = where + ": point " + std::to_string(i) + ": ";
      SurfacePoint point;
      if (const int* vertex = std::get_if<int>(&spec.points[i])) {
        if (*vertex < 0 || *vertex >= n_vertices) {
          throw InputError(at + "vertex " + std::to_string(*vertex) + " out of range (the mesh has " +
                           std::to_string(n_vertices) + " vertices)");
        }
        point = vertex_surface_point(input, input.vertex_handle(*vertex));
      } else {
        point = std::get<SurfacePoint>(spec.points[i]);
        if (point.face < 0 || point.face >= n_faces) {
          throw InputError(at + "face " + std::to_string(point.face) + " out of range (the mesh has " +
                           std::to_string(n_faces) + " faces)");
        }
        if (const std::string problem = barycentric_problem(point.bary); !problem.empty()) {
          throw InputError(at + problem);
        }
        point.bary = point.bary.cwiseMax(0.0);
        point.bary /= point.bary.sum();
      }
      places.push_back(position(input, point));
      curve.points.push_back(point);
    }
    const int n = static_cast<int>(places.size());
    for (int i = 0; i + 1 < n + (spec.closed ? 1 : 0); ++i) {
      if ((places[i] - places[(i + 1) % n]).norm() <= same_place) {
        throw InputError(where + ": points " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
                         " are at the same place");
      }
    }
    curves.push_back(std::move(curve));
  }
  return curves;
}

}  // namespace xparam
