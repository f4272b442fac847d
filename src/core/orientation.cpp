#include "core/orientation.h"

#include <Eigen/Geometry>

namespace xparam {

double signed_volume(const Mesh& mesh) {
  if (mesh.n_vertices() == 0) return 0.0;
  Eigen::Vector3d lo = position(mesh, *mesh.vertices().begin());
  Eigen::Vector3d hi = lo;
  for (VertexHandle v : mesh.vertices()) {
    lo = lo.cwiseMin(position(mesh, v));
    hi = hi.cwiseMax(position(mesh, v));
  }
  const Eigen::Vector3d center = 0.5 * (lo + hi);
  double six_volume = 0.0;
  for (FaceHandle f : mesh.faces()) {
    auto corner = mesh.fv_range(f).begin();
    const Eigen::Vector3d a = position(mesh, *corner++) - center;
    const Eigen::Vector3d b = position(mesh, *corner++) - center;
    const Eigen::Vector3d c = position(mesh, *corner) - center;
    six_volume += a.dot(b.cross(c));
  }
  return six_volume / 6.0;
}

Eigen::Vector3d to_file_order(const Eigen::Vector3d& bary, bool orientation_flipped) {
  if (!orientation_flipped) return bary;
  return {bary[0], bary[2], bary[1]};
}

}  // namespace xparam
