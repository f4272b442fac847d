#include "core/surface_walk.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace xparam {
namespace {

struct FaceFrame {
  std::array<VertexHandle, 3> corners;
  std::array<Eigen::Vector3d, 3> points;
  Eigen::Vector3d normal;  // unit; not finite for a degenerate face
};

FaceFrame frame_of(const Mesh& mesh, FaceHandle face) {
  FaceFrame frame;
  int k = 0;
  for (VertexHandle v : mesh.fv_range(face)) {
    frame.corners[k] = v;
    frame.points[k++] = position(mesh, v);
  }
  frame.normal = (frame.points[1] - frame.points[0]).cross(frame.points[2] - frame.points[0]).normalized();
  return frame;
}

// Barycentrics clamped into [0, 1] and summing to 1 again after rounding.
Eigen::Vector3d clamped(Eigen::Vector3d bary) {
  bary = bary.cwiseMax(0.0);
  return bary / bary.sum();
}

}  // namespace

std::optional<SurfacePoint> walk_on_surface(const Mesh& mesh, const SurfacePoint& start,
                                            const Eigen::Vector3d& step, int max_faces) {
  XP_ASSERT_MSG(start.face >= 0 && start.face < static_cast<int>(mesh.n_faces()), "face " << start.face);
  FaceHandle face = mesh.face_handle(start.face);
  FaceFrame frame = frame_of(mesh, face);
  Eigen::Vector3d bary = start.bary;
  Eigen::Vector3d rest = step - frame.normal * frame.normal.dot(step);
  for (int crossed = 0; crossed <= max_faces; ++crossed) {
    if (!frame.normal.allFinite()) return std::nullopt;
    // The step's change of barycentrics in this face (the coordinates of a vector sum to 0).
    const Eigen::Vector3d delta =
        barycentric(frame.points[0] + rest, frame.points[0], frame.points[1], frame.points[2]) -
        Eigen::Vector3d(1.0, 0.0, 0.0);
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
    if (exit < 0) return SurfacePoint{face.idx(), clamped(bary + delta)};
    bary += fraction * delta;
    bary[exit] = 0.0;
    bary = clamped(bary);
    rest *= 1.0 - fraction;

    const int j = (exit + 1) % 3;
    const int k = (exit + 2) % 3;
    const HalfedgeHandle across = mesh.opposite_halfedge_handle(mesh.find_halfedge(frame.corners[j], frame.corners[k]));
    const FaceHandle next = mesh.face_handle(across);
    if (!next.is_valid()) return std::nullopt;
    // Unfold about the edge: keep the components along the edge and away from it.
    const Eigen::Vector3d edge = (frame.points[k] - frame.points[j]).normalized();
    const Eigen::Vector3d out_of_face = edge.cross(frame.normal);
    const double along = rest.dot(edge);
    const double away = rest.dot(out_of_face);
    const double on_j = bary[j];
    const double on_k = bary[k];
    face = next;
    frame = frame_of(mesh, face);
    rest = along * edge + away * edge.cross(frame.normal);
    bary.setZero();
    for (int c = 0; c < 3; ++c) {
      if (frame.corners[c] == mesh.from_vertex_handle(across)) bary[c] = on_k;
      if (frame.corners[c] == mesh.to_vertex_handle(across)) bary[c] = on_j;
    }
  }
  return std::nullopt;
}

}  // namespace xparam
