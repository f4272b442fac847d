#include "geodesic/face_strip.h"

#include "core/errors.h"

#include <Eigen/Geometry>

namespace xparam {
namespace {

// Corner c of a counter-clockwise triangle (p, q, c), placed left of the plane image
// p2 -> q2 of edge p -> q. Its coordinates along and across the edge come straight from the
// 3-D vectors (dot and cross products), which stays accurate for needle triangles where
// solving from the three edge lengths would cancel.
Eigen::Vector2d third_corner(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& c,
                             const Eigen::Vector2d& p2, const Eigen::Vector2d& q2) {
  const Eigen::Vector3d edge = q - p;
  const double length = edge.norm();
  XP_ASSERT_MSG(length > 0.0, "zero-length edge in face strip");
  const Eigen::Vector2d along = (q2 - p2).normalized();
  const Eigen::Vector2d across(-along.y(), along.x());
  return p2 + (edge.dot(c - p) / length) * along + (edge.cross(c - p).norm() / length) * across;
}

}  // namespace

Eigen::Vector2d UnfoldedStrip::point(int k, VertexHandle v) const {
  for (int c = 0; c < 3; ++c) {
    if (corners[k][c] == v) return points[k][c];
  }
  XP_ASSERT_MSG(false, "vertex " << v.idx() << " is not a corner of strip face " << k);
  return {};
}

UnfoldedStrip unfold_strip(const Mesh& mesh, const std::vector<FaceHandle>& faces) {
  XP_ASSERT(!faces.empty());
  UnfoldedStrip strip;
  const auto lay_out = [&](HalfedgeHandle h, const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
    const VertexHandle a = mesh.from_vertex_handle(h);
    const VertexHandle b = mesh.to_vertex_handle(h);
    const VertexHandle c = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
    strip.corners.push_back({a, b, c});
    strip.points.push_back(
        {from, to, third_corner(position(mesh, a), position(mesh, b), position(mesh, c), from, to)});
  };
  const HalfedgeHandle first = mesh.halfedge_handle(faces.front());
  const double first_length =
      (position(mesh, mesh.to_vertex_handle(first)) - position(mesh, mesh.from_vertex_handle(first))).norm();
  lay_out(first, Eigen::Vector2d::Zero(), Eigen::Vector2d(first_length, 0.0));
  for (std::size_t k = 0; k + 1 < faces.size(); ++k) {
    HalfedgeHandle shared;
    for (HalfedgeHandle h : mesh.fh_range(faces[k])) {
      if (mesh.opposite_face_handle(h) == faces[k + 1]) shared = h;
    }
    XP_ASSERT_MSG(shared.is_valid(),
                  "strip faces " << faces[k].idx() << " and " << faces[k + 1].idx() << " share no edge");
    const int kk = static_cast<int>(k);
    // Walking out of face k across `shared`, its end is on the traveller's left.
    Portal portal;
    portal.left = mesh.to_vertex_handle(shared);
    portal.right = mesh.from_vertex_handle(shared);
    portal.left_point = strip.point(kk, portal.left);
    portal.right_point = strip.point(kk, portal.right);
    strip.portals.push_back(portal);
    strip.edges.push_back(mesh.edge_handle(shared));
    lay_out(mesh.opposite_halfedge_handle(shared), portal.left_point, portal.right_point);
  }
  return strip;
}

}  // namespace xparam
