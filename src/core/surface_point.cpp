#include "core/surface_point.h"

#include "core/errors.h"

namespace xparam {

Eigen::Vector3d position(const Mesh& mesh, const SurfacePoint& point) {
  XP_ASSERT_MSG(point.face >= 0 && point.face < static_cast<int>(mesh.n_faces()), "face " << point.face);
  Eigen::Vector3d result = Eigen::Vector3d::Zero();
  int corner = 0;
  for (VertexHandle v : mesh.fv_range(mesh.face_handle(point.face))) {
    result += point.bary[corner++] * position(mesh, v);
  }
  return result;
}

Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  // Least-squares solve of p - a = s (b - a) + t (c - a): the projection into the plane.
  const Eigen::Vector3d e1 = b - a;
  const Eigen::Vector3d e2 = c - a;
  const Eigen::Vector3d d = p - a;
  const double d11 = e1.dot(e1);
  const double d12 = e1.dot(e2);
  const double d22 = e2.dot(e2);
  const double r1 = d.dot(e1);
  const double r2 = d.dot(e2);
  const double det = d11 * d22 - d12 * d12;
  const double s = (d22 * r1 - d12 * r2) / det;
  const double t = (d11 * r2 - d12 * r1) / det;
  return {1.0 - s - t, s, t};
}

}  // namespace xparam
