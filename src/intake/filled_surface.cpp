#include "intake/filled_surface.h"

#include "core/closest_point.h"
#include "core/errors.h"

#include <algorithm>
#include <optional>

namespace xparam {

FilledSurfaceImages filled_surface_images(const LoadedMesh& target, const std::vector<SurfacePoint>& images,
                                          const Eigen::MatrixX3d& positions, int n) {
  XP_ASSERT(n >= 0 && static_cast<std::size_t>(n) <= images.size() && n <= positions.rows());
  FilledSurfaceImages out;
  out.on_filled.assign(static_cast<std::size_t>(n), 0);
  out.distance_to_scan.assign(static_cast<std::size_t>(n), 0.0);
  const FileOrder& order = target.file_order;
  for (int v = 0; v < n; ++v) out.on_filled[v] = order.is_filled(images[v].face) ? 1 : 0;
  out.count = static_cast<int>(std::count(out.on_filled.begin(), out.on_filled.end(), 1));
  if (out.count == 0) return out;

  // The scan's own surface: every mesh face the file had.
  std::vector<Eigen::Vector3d> points;
  points.reserve(target.mesh.n_vertices());
  for (VertexHandle v : target.mesh.vertices()) points.push_back(position(target.mesh, v));
  std::vector<std::array<int, 3>> faces;
  for (FaceHandle f : target.mesh.faces()) {
    if (order.is_filled(f.idx())) continue;
    std::array<int, 3> corners{};
    int k = 0;
    for (VertexHandle v : target.mesh.fv_range(f)) corners[k++] = v.idx();
    faces.push_back(corners);
  }
  const ClosestPointIndex scan(points, faces);
  for (int v = 0; v < n; ++v) {
    if (out.on_filled[v] == 0) continue;
    out.distance_to_scan[v] = scan.closest(positions.row(v).transpose()).distance;
    out.max_distance = std::max(out.max_distance, out.distance_to_scan[v]);
  }
  return out;
}

}  // namespace xparam
