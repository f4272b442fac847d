#include "core/surface_walk.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <cmath>

namespace xparam {
namespace {

// Barycentrics clamped into [0, 1] and summing to 1 again after rounding.
Eigen::Vector3d clamped(Eigen::Vector3d bary) {
  bary = bary.cwiseMax(0.0);
  return bary / bary.sum();
}

}  // namespace

SurfaceWalker::SurfaceWalker(const Mesh& mesh) : mesh_(&mesh), corners_(triangles_of(mesh)) {
  across_.assign(corners_.size(), {-1, -1, -1});
  normals_.reserve(corners_.size());
  for (FaceHandle face : mesh.faces()) {
    const std::array<int, 3>& t = corners_[face.idx()];
    const Eigen::Vector3d a = position(mesh, VertexHandle(t[0]));
    normals_.push_back(
        (position(mesh, VertexHandle(t[1])) - a).cross(position(mesh, VertexHandle(t[2])) - a).normalized());
    for (HalfedgeHandle side : mesh.fh_range(face)) {
      const FaceHandle other = mesh.opposite_face_handle(side);
      if (!other.is_valid()) continue;
      // The corner opposite the side is the one it does not start or end at.
      const int from = mesh.from_vertex_handle(side).idx();
      const int to = mesh.to_vertex_handle(side).idx();
      for (int k = 0; k < 3; ++k) {
        if (t[k] != from && t[k] != to) across_[face.idx()][k] = other.idx();
      }
    }
  }
}

std::optional<SurfacePoint> SurfaceWalker::walk(const SurfacePoint& start, const Eigen::Vector3d& step,
                                                int max_faces) const {
  XP_ASSERT_MSG(start.face >= 0 && start.face < static_cast<int>(corners_.size()), "face " << start.face);
  int face = start.face;
  std::array<Eigen::Vector3d, 3> points;
  const auto enter = [&](int f) {
    for (int c = 0; c < 3; ++c) points[c] = position(*mesh_, VertexHandle(corners_[f][c]));
  };
  enter(face);
  Eigen::Vector3d bary = start.bary;
  Eigen::Vector3d rest = step - normals_[face] * normals_[face].dot(step);
  for (int crossed = 0; crossed <= max_faces; ++crossed) {
    const Eigen::Vector3d& normal = normals_[face];
    if (!normal.allFinite()) return std::nullopt;
    // The step's change of barycentrics in this face (the coordinates of a vector sum to 0).
    const Eigen::Vector3d delta =
        barycentric(points[0] + rest, points[0], points[1], points[2]) - Eigen::Vector3d(1.0, 0.0, 0.0);
    double fraction = 1.0;  // of `rest` used inside this face
    int exit = -1;          // the corner opposite the edge crossed
    for (int i = 0; i < 3; ++i) {
      if (delta[i] >= 0.0) continue;
      const double reach = bary[i] / -delta[i];
      if (reach < fraction) {
        fraction = reach;
        exit = i;
      }
    }
    if (exit < 0) return SurfacePoint{face, clamped(bary + delta)};
    bary += fraction * delta;
    bary[exit] = 0.0;
    bary = clamped(bary);
    rest *= 1.0 - fraction;

    const int j = (exit + 1) % 3;
    const int k = (exit + 2) % 3;
    const int next = across_[face][exit];
    if (next < 0) return std::nullopt;
    // Unfold about the edge: keep the components along the edge and away from it.
    const Eigen::Vector3d edge = (points[k] - points[j]).normalized();
    const Eigen::Vector3d out_of_face = edge.cross(normal);
    const double along = rest.dot(edge);
    const double away = rest.dot(out_of_face);
    const int vertex_j = corners_[face][j];
    const int vertex_k = corners_[face][k];
    const double on_j = bary[j];
    const double on_k = bary[k];
    face = next;
    enter(face);
    rest = along * edge + away * edge.cross(normals_[face]);
    bary.setZero();
    for (int c = 0; c < 3; ++c) {
      if (corners_[face][c] == vertex_k) bary[c] = on_k;
      if (corners_[face][c] == vertex_j) bary[c] = on_j;
    }
  }
  return std::nullopt;
}

}  // namespace xparam
