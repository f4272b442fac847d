#include "measure/plane_section.h"

#include "core/closest_point.h"
#include "core/planar.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace xparam {
namespace {

// The point where the plane crosses edge (a, b), from the signed distances of its ends.
Eigen::Vector3d crossing(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double da, double db) {
  const double t = da / (da - db);
  return a + t * (b - a);
}

}  // namespace

double SectionLoop::length() const {
  double total = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) total += (points[i] - points[i - 1]).norm();
  if (closed && points.size() > 2) total += (points.front() - points.back()).norm();
  return total;
}

std::vector<SectionLoop> plane_section(const Mesh& mesh, const Eigen::Vector3d& origin, const Eigen::Vector3d& normal) {
  std::vector<double> side(mesh.n_vertices());
  for (const VertexHandle v : mesh.vertices()) side[static_cast<std::size_t>(v.idx())] = normal.dot(position(mesh, v) - origin);
  const auto above = [&](VertexHandle v) { return side[static_cast<std::size_t>(v.idx())] >= 0.0; };
  const auto crossed = [&](EdgeHandle e) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    return above(mesh.from_vertex_handle(h)) != above(mesh.to_vertex_handle(h));
  };
  // Each crossed edge is a section point; a face with a crossed edge has exactly two, joined by
  // a segment. Walking from edge to edge through faces gives the loops.
  std::vector<bool> visited(mesh.n_edges(), false);
  std::vector<SectionLoop> loops;
  const auto point_of = [&](EdgeHandle e) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const VertexHandle a = mesh.from_vertex_handle(h);
    const VertexHandle b = mesh.to_vertex_handle(h);
    return crossing(position(mesh, a), position(mesh, b), side[static_cast<std::size_t>(a.idx())],
                    side[static_cast<std::size_t>(b.idx())]);
  };
  // The other crossed edge of the face on halfedge h's side, entered through h's edge.
  const auto next_edge = [&](HalfedgeHandle h) -> HalfedgeHandle {
    for (HalfedgeHandle g = mesh.next_halfedge_handle(h); g != h; g = mesh.next_halfedge_handle(g))
      if (crossed(mesh.edge_handle(g))) return g;
    return HalfedgeHandle();
  };
  // Follow the section from edge `start` through the face of halfedge `h`, appending points.
  const auto follow = [&](HalfedgeHandle h, std::vector<Eigen::Vector3d>& points) -> bool {
    while (!mesh.is_boundary(h)) {
      const HalfedgeHandle out = next_edge(h);
      if (!out.is_valid()) return false;
      const EdgeHandle e = mesh.edge_handle(out);
      if (visited[static_cast<std::size_t>(e.idx())]) return true;  // back at the start: closed
      visited[static_cast<std::size_t>(e.idx())] = true;
      points.push_back(point_of(e));
      h = mesh.opposite_halfedge_handle(out);
    }
    return false;
  };
  for (const EdgeHandle e : mesh.edges()) {
    if (visited[static_cast<std::size_t>(e.idx())] || !crossed(e)) continue;
    visited[static_cast<std::size_t>(e.idx())] = true;
    SectionLoop loop;
    loop.points.push_back(point_of(e));
    loop.closed = follow(mesh.halfedge_handle(e, 0), loop.points);
    if (!loop.closed) {
      // A boundary ended the walk: walk the other way from the start and join the two halves.
      std::vector<Eigen::Vector3d> back;
      follow(mesh.halfedge_handle(e, 1), back);
      std::reverse(back.begin(), back.end());
      back.insert(back.end(), loop.points.begin(), loop.points.end());
      loop.points = std::move(back);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

double distance_to_loop(const SectionLoop& loop, const Eigen::Vector3d& point) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = loop.points.size();
  if (n == 1) return (loop.points.front() - point).norm();
  const std::size_t segments = loop.closed ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i)
    best = std::min(best, (closest_point_on_segment(point, loop.points[i], loop.points[(i + 1) % n]) - point).norm());
  return best;
}

double convex_hull_perimeter(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& normal) {
  if (points.size() < 2) return 0.0;
  // Coordinates in the plane perpendicular to the normal.
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d w = normal.cross(u);
  std::vector<Eigen::Vector2d> flat;
  flat.reserve(points.size());
  for (const Eigen::Vector3d& p : points) flat.emplace_back(p.dot(u), p.dot(w));
  std::sort(flat.begin(), flat.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  // Andrew's monotone chain: lower hull, then upper hull.
  std::vector<Eigen::Vector2d> hull(2 * flat.size());
  std::size_t k = 0;
  for (const Eigen::Vector2d& p : flat) {
    while (k >= 2 && signed_area2(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = flat.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && signed_area2(hull[k - 2], hull[k - 1], flat[i]) <= 0.0) --k;
    hull[k++] = flat[i];
  }
  // The chain ends where it started; its segments are the hull's sides.
  double perimeter = 0.0;
  for (std::size_t i = 1; i < k; ++i) perimeter += (hull[i] - hull[i - 1]).norm();
  return perimeter;
}

}  // namespace xparam
