#include "map/remesh_coverage.h"

#include "core/closest_point.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace xparam {

RemeshCoverage measure_remesh_coverage(const Mesh& target, const std::vector<Eigen::Vector3d>& positions,
                                       const std::vector<std::array<int, 3>>& faces) {
  const ClosestPointIndex remesh(positions, faces);
  const int n_vertices = static_cast<int>(target.n_vertices());
  RemeshCoverage coverage;
  coverage.gap.resize(n_vertices);
  tbb::parallel_for(0, n_vertices, [&](int v) {
    coverage.gap[v] = remesh.closest(position(target, target.vertex_handle(v))).distance;
  });
  std::vector<double> vertex_area(n_vertices, 0.0);
  double area = 0.0;
  for (FaceHandle f : target.faces()) {
    const double face_area = target.calc_face_area(f);
    area += face_area;
    for (VertexHandle v : target.fv_range(f)) vertex_area[v.idx()] += face_area / 3.0;
  }
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
