#include "warp/surface_frame.h"

#include <Eigen/Geometry>

#include <cmath>

namespace xparam {

VertexFrames vertex_frames(const TriangleSoup& mesh) {
  const std::size_t n = mesh.vertices.size();
  VertexFrames frames{std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Zero()), std::vector<double>(n, 0.0)};
  // In face order, so the sums (and every frame) are the same bits on every run.
  for (const std::array<int, 3>& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const Eigen::Vector3d twice_area_normal = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
    const double area = 0.5 * twice_area_normal.norm();
    for (const int v : t) {
      frames.normals[v] += twice_area_normal;
      frames.scales[v] += area;
    }
  }
  for (std::size_t v = 0; v < n; ++v) {
    const double length = frames.normals[v].norm();
    if (length > 0.0) frames.normals[v] /= length;
    frames.scales[v] = std::sqrt(frames.scales[v]);
  }
  return frames;
}

Eigen::Vector3d surface_position(const TriangleSoup& mesh, int face, const Eigen::Vector3d& bary) {
  const std::array<int, 3>& t = mesh.triangles[face];
  return bary[0] * mesh.vertices[t[0]] + bary[1] * mesh.vertices[t[1]] + bary[2] * mesh.vertices[t[2]];
}

Eigen::Matrix3d surface_frame(const TriangleSoup& mesh, const VertexFrames& frames, int face,
                              const Eigen::Vector3d& bary, OffsetFrame kind) {
  const std::array<int, 3>& t = mesh.triangles[face];
  const Eigen::Vector3d e1 = mesh.vertices[t[1]] - mesh.vertices[t[0]];
  const Eigen::Vector3d e2 = mesh.vertices[t[2]] - mesh.vertices[t[0]];
  Eigen::Vector3d normal = bary[0] * frames.normals[t[0]] + bary[1] * frames.normals[t[1]] +
                           bary[2] * frames.normals[t[2]];
  if (normal.norm() < 1e-12) normal = e1.cross(e2);
  if (normal.norm() > 0.0) normal.normalize();
  Eigen::Matrix3d frame;
  if (kind == OffsetFrame::gradient) {
    const double scale =
        bary[0] * frames.scales[t[0]] + bary[1] * frames.scales[t[1]] + bary[2] * frames.scales[t[2]];
    frame << e1, e2, scale * normal;
    return frame;
  }
  // The tangent from the face's first edge; its second edge where the first is along the normal.
  Eigen::Vector3d tangent = e1 - e1.dot(normal) * normal;
  if (tangent.norm() < 1e-9 * e1.norm()) tangent = e2 - e2.dot(normal) * normal;
  if (tangent.norm() > 0.0) tangent.normalize();
  frame << tangent, normal.cross(tangent), normal;
  return frame;
}

}  // namespace xparam
