#include "warp/garment_metrics.h"

#include "core/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

namespace xparam {
namespace {

// Singular values of the map taking triangle (a, b, c) to (p, q, r), each in its own plane.
Eigen::Vector2d triangle_singular_values(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                         const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
  // Rest triangle in an orthonormal basis of its plane; the map's 3x2 Jacobian J = W R^-1.
  const Eigen::Vector3d u = (b - a).normalized();
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  const Eigen::Vector3d v = normal.cross(u).normalized();
  Eigen::Matrix2d rest;
  rest << (b - a).dot(u), (c - a).dot(u), (b - a).dot(v), (c - a).dot(v);
  Eigen::Matrix<double, 3, 2> warped;
  warped << q - p, r - p;
  const Eigen::Matrix<double, 3, 2> jacobian = warped * rest.inverse();
  return Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>>(jacobian).singularValues();
}

}  // namespace

ValueSummary summarize(std::vector<double> values) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (values.empty()) return {kNaN, kNaN, kNaN, kNaN};
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(values.size())));
  const double sum = std::accumulate(values.begin(), values.end(), 0.0);  // sorted: the same sum every run
  return {sum / static_cast<double>(values.size()), values[std::max<std::size_t>(rank, 1) - 1], values.back(),
          values.front()};
}

void check_rest_garment(const TriangleSoup& garment) {
  if (garment.triangles.empty())
    throw InputError(garment.source + ": the garment has no faces; give a triangle mesh with its UVs");
  for (std::size_t v = 0; v < garment.vertices.size(); ++v) {
    if (!garment.vertices[v].allFinite())
      throw InputError(garment.source + ": vertex " + std::to_string(v + 1) + " (OBJ numbering) is not finite");
  }
  for (std::size_t f = 0; f < garment.triangles.size(); ++f) {
    const auto& [a, b, c] = garment.triangles[f];
    const Eigen::Vector3d& p = garment.vertices[a];
    if ((garment.vertices[b] - p).cross(garment.vertices[c] - p).norm() == 0.0)
      throw InputError(garment.source + ": face " + std::to_string(f + 1) +
                       " (OBJ numbering) has zero area, so its stretch is undefined; remove it or move its corners apart");
  }
}

Penetration penetration(const std::vector<Eigen::Vector3d>& vertices, const BodyDistance& body) {
  Penetration result;
  for (const Eigen::Vector3d& p : vertices) {
    const double d = body.sample(p).signed_distance;
    if (d < 0.0) {
      ++result.count;
      result.max_depth = std::max(result.max_depth, -d);
    }
  }
  return result;
}

ShapeChange shape_change(const std::vector<Eigen::Vector3d>& rest, const std::vector<Eigen::Vector3d>& warped,
                         const std::vector<std::array<int, 3>>& triangles) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * triangles.size());
  std::vector<double> stretch;
  stretch.reserve(triangles.size());
  for (const std::array<int, 3>& t : triangles) {
    for (int k = 0; k < 3; ++k) edges.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
    stretch.push_back(triangle_singular_values(rest[t[0]], rest[t[1]], rest[t[2]], warped[t[0]], warped[t[1]],
                                               warped[t[2]])[0]);
  }
  // Each edge once, however many triangles share it.
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> ratio;
  ratio.reserve(edges.size());
  for (const auto& [i, j] : edges) ratio.push_back((warped[j] - warped[i]).norm() / (rest[j] - rest[i]).norm());
  return {summarize(std::move(ratio)), summarize(std::move(stretch))};
}

}  // namespace xparam
