#include "geodesic/vertex_fan.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <cmath>

namespace xparam {
namespace {

// The halfedge of face f that leaves v.
HalfedgeHandle outgoing_in_face(const Mesh& mesh, FaceHandle f, VertexHandle v) {
  for (HalfedgeHandle h : mesh.fh_range(f)) {
    if (mesh.from_vertex_handle(h) == v) return h;
  }
  XP_ASSERT_MSG(false, "vertex " << v.idx() << " is not a corner of face " << f.idx());
  return HalfedgeHandle();
}

}  // namespace

double corner_angle(const Mesh& mesh, FaceHandle f, VertexHandle v) {
  const HalfedgeHandle out = outgoing_in_face(mesh, f, v);
  const Eigen::Vector3d p = position(mesh, v);
  const Eigen::Vector3d e1 = position(mesh, mesh.to_vertex_handle(out)) - p;
  const Eigen::Vector3d e2 = position(mesh, mesh.from_vertex_handle(mesh.prev_halfedge_handle(out))) - p;
  return std::atan2(e1.cross(e2).norm(), e1.dot(e2));
}

std::optional<std::vector<FaceHandle>> fan_between(const Mesh& mesh, VertexHandle v, FaceHandle first,
                                                   FaceHandle last, FanStep step) {
  const int max_steps = static_cast<int>(mesh.valence(v));
  std::vector<FaceHandle> faces;
  faces.reserve(max_steps + 1);  // one allocation, not one per doubling
  faces.push_back(first);
  FaceHandle f = first;
  for (int steps = 0; f != last; ++steps) {
    if (steps >= max_steps) return std::nullopt;
    const HalfedgeHandle out = outgoing_in_face(mesh, f, v);
    const HalfedgeHandle spoke = step == FanStep::AcrossOutgoing ? out : mesh.prev_halfedge_handle(out);
    const HalfedgeHandle across = mesh.opposite_halfedge_handle(spoke);
    if (mesh.is_boundary(across)) return std::nullopt;
    f = mesh.face_handle(across);
    faces.push_back(f);
  }
  return faces;
}

CurveSides curve_sides(const Mesh& mesh, VertexHandle prev, VertexHandle v, VertexHandle next) {
  const HalfedgeHandle in = mesh.find_halfedge(prev, v);
  const HalfedgeHandle out = mesh.find_halfedge(v, next);
  XP_ASSERT_MSG(in.is_valid() && out.is_valid(),
                "no edge path " << prev.idx() << " -> " << v.idx() << " -> " << next.idx());
  CurveSides sides;
  // A face lies to the left of each of its (counter-clockwise) halfedges.
  const HalfedgeHandle in_back = mesh.opposite_halfedge_handle(in);
  const HalfedgeHandle out_back = mesh.opposite_halfedge_handle(out);
  if (!mesh.is_boundary(in) && !mesh.is_boundary(out)) {
    sides.left = fan_between(mesh, v, mesh.face_handle(in), mesh.face_handle(out), FanStep::AcrossOutgoing);
  }
  if (!mesh.is_boundary(in_back) && !mesh.is_boundary(out_back)) {
    sides.right =
        fan_between(mesh, v, mesh.face_handle(in_back), mesh.face_handle(out_back), FanStep::AcrossIncoming);
  }
  return sides;
}

double fan_angle(const Mesh& mesh, const std::vector<FaceHandle>& faces, VertexHandle v) {
  double angle = 0.0;
  for (FaceHandle f : faces) angle += corner_angle(mesh, f, v);
  return angle;
}

bool face_has_vertex(const Mesh& mesh, FaceHandle f, VertexHandle v) {
  for (VertexHandle w : mesh.fv_range(f)) {
    if (w == v) return true;
  }
  return false;
}

}  // namespace xparam
