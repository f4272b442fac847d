#include "core/orientation.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <utility>

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

FileOrder FileOrder::identity(int faces, int vertices) {
  FileOrder order;
  order.reversed.assign(static_cast<size_t>(faces), false);
  order.file_vertices = vertices;
  order.file_faces = faces;
  return order;
}

bool FileOrder::is_reversed(int face) const {
  return face >= 0 && static_cast<size_t>(face) < reversed.size() && reversed[face];
}

int FileOrder::reversed_count() const { return static_cast<int>(std::count(reversed.begin(), reversed.end(), true)); }

int FileOrder::file_face(int face) const {
  if (face_source.empty()) return face;
  XP_ASSERT_MSG(face >= 0 && face < static_cast<int>(face_source.size()), "face " << face);
  return face_source[face];
}

int FileOrder::mesh_face(int face) const {
  if (mesh_face_of_file.empty()) return face;
  return face >= 0 && face < static_cast<int>(mesh_face_of_file.size()) ? mesh_face_of_file[face] : -1;
}

int FileOrder::mesh_vertex(int vertex) const {
  if (mesh_vertex_of_file.empty()) return vertex;
  return vertex >= 0 && vertex < static_cast<int>(mesh_vertex_of_file.size()) ? mesh_vertex_of_file[vertex] : -1;
}

int FileOrder::file_vertex(int vertex) const {
  if (!vertex_source.empty()) {
    XP_ASSERT_MSG(vertex >= 0 && vertex < static_cast<int>(vertex_source.size()), "vertex " << vertex);
    return vertex_source[vertex];
  }
  XP_ASSERT_MSG(vertex >= 0 && vertex < file_vertices + static_cast<int>(copy_of.size()),
                "vertex " << vertex << " of " << file_vertices << " + " << copy_of.size() << " copies");
  return vertex < file_vertices ? vertex : copy_of[vertex - file_vertices];
}

Eigen::Vector3d to_file_order(const FileOrder& order, int face, const Eigen::Vector3d& bary) {
  if (!order.is_reversed(face)) return bary;
  return {bary[0], bary[2], bary[1]};
}

SurfacePoint to_file_point(const FileOrder& order, const SurfacePoint& point) {
  return {order.file_face(point.face), to_file_order(order, point.face, point.bary)};
}

std::array<int, 3> file_triangle(const Mesh& mesh, const FileOrder& order, FaceHandle f) {
  std::array<int, 3> corners{};
  int k = 0;
  for (VertexHandle v : mesh.fv_range(f)) corners[k++] = order.file_vertex(v.idx());
  XP_ASSERT_EQ(k, 3);
  if (order.is_reversed(f.idx())) std::swap(corners[1], corners[2]);
  return corners;
}

}  // namespace xparam
