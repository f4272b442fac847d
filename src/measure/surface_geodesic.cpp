#include "measure/surface_geodesic.h"

#include "core/closest_point.h"
#include "core/errors.h"
#include "geodesic/locally_shortest.h"
#include "geodesic/straighten_path.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <queue>
#include <utility>

namespace xparam {
namespace {

// The length of a path that cannot be traced as a shortest one.
constexpr double kNoLength = std::numeric_limits<double>::quiet_NaN();

// Makes surface points vertices of `mesh`, which starts as a copy of the measured surface. A
// split keeps the split face's handle for one piece and appends the others, so a point of input
// face f lies in f or in an appended face: those are the only candidates to look at.
class PointInserter {
 public:
  PointInserter(Mesh& mesh, double snap)
      : mesh_(mesh), index_(mesh), input_faces_(static_cast<int>(mesh.n_faces())), snap_(snap) {}

  // The vertex at the surface point nearest to `p`; `distance` receives how far p lies from it.
  VertexHandle insert(const Eigen::Vector3d& p, double& distance) {
    const ClosestPoint hit = index_.closest(p);
    distance = hit.distance;
    const Eigen::Vector3d q = hit.point;
    FaceHandle face(hit.location.face);
    double nearest = distance_to_face(face, q);
    for (int f = input_faces_; f < static_cast<int>(mesh_.n_faces()); ++f) {
      const double d = distance_to_face(FaceHandle(f), q);
      if (d < nearest) {
        nearest = d;
        face = FaceHandle(f);
      }
    }
    if (const VertexHandle corner = corner_near(face, q); corner.is_valid()) return corner;
    // On an edge (within the snap): split the edge there, so no sliver face is cut beside it.
    HalfedgeHandle closest_edge;
    Eigen::Vector3d on_edge = q;
    double edge_distance = snap_;
    for (const HalfedgeHandle h : mesh_.fh_range(face)) {
      const Eigen::Vector3d e = closest_point_on_segment(q, position(mesh_, mesh_.from_vertex_handle(h)),
                                                   position(mesh_, mesh_.to_vertex_handle(h)));
      if ((e - q).norm() <= edge_distance) {
        edge_distance = (e - q).norm();
        closest_edge = h;
        on_edge = e;
      }
    }
    if (closest_edge.is_valid()) {
      if (const VertexHandle corner = corner_near(face, on_edge); corner.is_valid()) return corner;
      const VertexHandle v = mesh_.add_vertex(to_point(on_edge));
      mesh_.split(mesh_.edge_handle(closest_edge), v);
      return v;
    }
    return mesh_.split(face, to_point(q));
  }

 private:
  double distance_to_face(FaceHandle f, const Eigen::Vector3d& q) const {
    std::array<Eigen::Vector3d, 3> corner;
    int k = 0;
    for (const VertexHandle v : mesh_.fv_range(f)) corner[static_cast<std::size_t>(k++)] = position(mesh_, v);
    return (closest_point_on_triangle(q, corner[0], corner[1], corner[2]).point - q).norm();
  }

  // The corner of `f` within the snap of q (the nearest one); invalid when none is.
  VertexHandle corner_near(FaceHandle f, const Eigen::Vector3d& q) const {
    VertexHandle corner;
    double nearest = snap_;
    for (const VertexHandle v : mesh_.fv_range(f)) {
      const double d = (position(mesh_, v) - q).norm();
      if (d <= nearest) {
        nearest = d;
        corner = v;
      }
    }
    return corner;
  }

  Mesh& mesh_;
  ClosestPointIndex index_;  // over the faces before any split
  int input_faces_;
  double snap_;
};

// The shortest chain of mesh edges from `from` to `to` (Dijkstra, edge lengths), passing through
// no boundary vertex (straighten_curve keeps a chain's interior inside the region); empty when
// `to` is not reached. Ties go to the vertex settled first, in (distance, index) order.
std::vector<VertexHandle> edge_path(const Mesh& mesh, VertexHandle from, VertexHandle to) {
  const std::size_t n = mesh.n_vertices();
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  std::vector<int> parent(n, -1);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  distance[static_cast<std::size_t>(from.idx())] = 0.0;
  queue.emplace(0.0, from.idx());
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[static_cast<std::size_t>(v)]) continue;
    if (v == to.idx()) break;
    const VertexHandle vh(v);
    if (vh != from && mesh.is_boundary(vh)) continue;
    const Eigen::Vector3d p = position(mesh, vh);
    for (const VertexHandle w : mesh.vv_range(vh)) {
      const double through = d + (position(mesh, w) - p).norm();
      if (through < distance[static_cast<std::size_t>(w.idx())]) {
        distance[static_cast<std::size_t>(w.idx())] = through;
        parent[static_cast<std::size_t>(w.idx())] = v;
        queue.emplace(through, w.idx());
      }
    }
  }
  if (parent[static_cast<std::size_t>(to.idx())] < 0) return {};
  std::vector<VertexHandle> path{to};
  while (path.back() != from) path.emplace_back(parent[static_cast<std::size_t>(path.back().idx())]);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace

SurfaceGeodesic surface_geodesic(const Mesh& surface, const std::vector<Eigen::Vector3d>& points, bool closed,
                                 const SurfaceGeodesicSettings& settings) {
  XP_ASSERT(points.size() >= 2);
  SurfaceGeodesic result;
  result.settings = settings;
  Mesh mesh = surface;
  PointInserter inserter(mesh, settings.snap_tolerance * bounding_box_diagonal(surface));
  std::vector<VertexHandle> at;
  for (const Eigen::Vector3d& p : points) {
    XP_ASSERT(p.allFinite());
    double distance = 0.0;
    at.push_back(inserter.insert(p, distance));
    result.max_point_distance = std::max(result.max_point_distance, distance);
  }
  const std::vector<bool> whole_surface(mesh.n_faces(), true);
  // Measuring, not inserting: no crossing is moved onto a vertex (only those within rounding).
  StraightenSettings straighten;
  straighten.snap_tolerance = 0.0;
  result.length = 0.0;
  result.edge_path_length = 0.0;
  const std::size_t segments = closed ? at.size() : at.size() - 1;
  for (std::size_t k = 0; k < segments; ++k) {
    const VertexHandle from = at[k];
    const VertexHandle to = at[(k + 1) % at.size()];
    double length = 0.0;
    if (from != to) {
      const std::vector<VertexHandle> path = edge_path(mesh, from, to);
      if (path.empty()) {
        length = kNoLength;
        result.edge_path_length = kNoLength;
      } else {
        result.edge_path_length += chain_length(mesh, path);
        try {
          const StraightenedCurve curve = straighten_curve(mesh, whole_surface, path, straighten);
          length = curve.length;
          result.converged = result.converged && curve.converged;
        } catch (const LayoutError&) {
          length = kNoLength;  // the straightened path would cross a face twice: not a shortest path
        }
      }
    }
    result.segment_lengths.push_back(length);
    result.length += length;
  }
  return result;
}

}  // namespace xparam
