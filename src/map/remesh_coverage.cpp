#include "map/remesh_coverage.h"

#include "core/closest_point.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace xparam {

std::vector<double> vertex_areas(const Mesh& mesh) {
  std::vector<double> areas(mesh.n_vertices(), 0.0);
  for (FaceHandle f : mesh.faces()) {
    const double third = mesh.calc_face_area(f) / 3.0;
    for (VertexHandle v : mesh.fv_range(f)) areas[v.idx()] += third;
  }
  return areas;
}

RemeshCoverage measure_remesh_coverage(const Mesh& target, const std::vector<Eigen::Vector3d>& positions,
                                       const std::vector<std::array<int, 3>>& faces) {
  const ClosestPointIndex remesh(positions, faces);
  const int n_vertices = static_cast<int>(target.n_vertices());
  RemeshCoverage coverage;
  coverage.gap.resize(n_vertices);
  tbb::parallel_for(0, n_vertices, [&](int v) {
    coverage.gap[v] = remesh.closest(position(target, target.vertex_handle(v))).distance;
  });
  const std::vector<double> vertex_area = vertex_areas(target);
  const double area = surface_area(target);
  const double scale = std::sqrt(area);
  double uncovered = 0.0;
  for (int v = 0; v < n_vertices; ++v) {
    coverage.max_gap = std::max(coverage.max_gap, coverage.gap[v] / scale);
    if (coverage.gap[v] > kUncoveredGap * scale) {
      uncovered += vertex_area[v];
      ++coverage.uncovered_vertices;
    }
  }
  coverage.uncovered_area = area > 0.0 ? uncovered / area : 0.0;
  return coverage;
}

}  // namespace xparam
