#include "core/surface_path.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <array>
#include <limits>

namespace xparam {
namespace {

Eigen::Vector3d face_normal(const Mesh& mesh, FaceHandle face) {
  std::array<Eigen::Vector3d, 3> p;
  int k = 0;
  for (const VertexHandle v : mesh.fv_range(face)) p[k++] = position(mesh, v);
  return (p[1] - p[0]).cross(p[2] - p[0]).normalized();
}

// The crossing of the plane with the edge of halfedge h, as a point of h's face (the face the
// path leaves): barycentric 0 at the corner opposite the edge.
SurfacePoint crossing_point(const Mesh& mesh, HalfedgeHandle h, double side_from, double side_to) {
  const VertexHandle a = mesh.from_vertex_handle(h);
  const VertexHandle b = mesh.to_vertex_handle(h);
  const double t = side_from / (side_from - side_to);
  SurfacePoint point{mesh.face_handle(h).idx(), Eigen::Vector3d::Zero()};
  int k = 0;
  for (const VertexHandle v : mesh.fv_range(mesh.face_handle(h))) {
    if (v == a) point.bary[k] = 1.0 - t;
    if (v == b) point.bary[k] = t;
    ++k;
  }
  return point;
}

}  // namespace

std::optional<std::vector<SurfacePoint>> surface_path_crossings(const Mesh& mesh, const SurfacePoint& from,
                                                                const SurfacePoint& to, int max_faces) {
  XP_ASSERT(from.face >= 0 && from.face < static_cast<int>(mesh.n_faces()));
  XP_ASSERT(to.face >= 0 && to.face < static_cast<int>(mesh.n_faces()));
  std::vector<SurfacePoint> crossings;
  if (from.face == to.face) return crossings;
  const Eigen::Vector3d start = position(mesh, from);
  const Eigen::Vector3d end = position(mesh, to);
  const Eigen::Vector3d chord = end - start;
  if (chord.squaredNorm() == 0.0) return crossings;  // one point given in two faces (a corner)
  const Eigen::Vector3d plane = chord.cross(face_normal(mesh, mesh.face_handle(from.face)) +
                                            face_normal(mesh, mesh.face_handle(to.face)));
  if (!(plane.norm() > 1e-12 * chord.norm()) || !plane.allFinite()) return std::nullopt;
  const Eigen::Vector3d normal = plane.normalized();
  const auto side = [&](VertexHandle v) { return normal.dot(position(mesh, v) - start); };
  // A vertex on the plane counts as above it, so a face the plane cuts has two crossed edges.
  const auto crossed = [&](HalfedgeHandle h) {
    return (side(mesh.from_vertex_handle(h)) >= 0.0) != (side(mesh.to_vertex_handle(h)) >= 0.0);
  };
  // Leave the first face through the crossed edge towards `end`. A start at a corner may leave
  // through any face around that vertex, across the edge opposite it.
  HalfedgeHandle exit;
  double best = -std::numeric_limits<double>::infinity();
  const auto consider = [&](HalfedgeHandle h) {
    if (!crossed(h)) return;
    const SurfacePoint c = crossing_point(mesh, h, side(mesh.from_vertex_handle(h)), side(mesh.to_vertex_handle(h)));
    const double ahead = (position(mesh, c) - start).dot(chord);
    if (ahead > best) {
      best = ahead;
      exit = h;
    }
  };
  Eigen::Index corner = 0;
  if (from.bary.maxCoeff(&corner) > 1.0 - 1e-12) {
    VertexHandle vertex;
    Eigen::Index k = 0;
    for (const VertexHandle v : mesh.fv_range(mesh.face_handle(from.face)))
      if (k++ == corner) vertex = v;
    for (const FaceHandle f : mesh.vf_range(vertex))
      for (const HalfedgeHandle h : mesh.fh_range(f))
        if (mesh.from_vertex_handle(h) != vertex && mesh.to_vertex_handle(h) != vertex) consider(h);
  } else {
    for (const HalfedgeHandle h : mesh.fh_range(mesh.face_handle(from.face))) consider(h);
  }
  if (!exit.is_valid()) return std::nullopt;
  for (int faces = 0; faces < max_faces; ++faces) {
    const SurfacePoint c =
        crossing_point(mesh, exit, side(mesh.from_vertex_handle(exit)), side(mesh.to_vertex_handle(exit)));
    // At or past the end: `to` lies on the border of this face (an edge or a corner of `to.face`).
    if ((position(mesh, c) - start).dot(chord) >= (1.0 - 1e-12) * chord.squaredNorm()) return crossings;
    crossings.push_back(c);
    const HalfedgeHandle entry = mesh.opposite_halfedge_handle(exit);
    if (mesh.is_boundary(entry)) return std::nullopt;
    if (mesh.face_handle(entry).idx() == to.face) return crossings;
    // The face's other crossed edge.
    exit = HalfedgeHandle();
    for (HalfedgeHandle h = mesh.next_halfedge_handle(entry); h != entry; h = mesh.next_halfedge_handle(h))
      if (crossed(h)) exit = h;
    if (!exit.is_valid()) return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace xparam
