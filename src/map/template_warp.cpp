#include "map/template_warp.h"

#include "core/planar.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace xparam {
namespace {

// Barycentrics of p in triangle (a, b, c) of the plane (not clamped).
Eigen::Vector3d barycentric2(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                             const Eigen::Vector2d& c) {
  const double area = cross2(b - a, c - a);
  const double l1 = cross2(p - a, c - a) / area;
  const double l2 = cross2(b - a, p - a) / area;
  return {1.0 - l1 - l2, l1, l2};
}

// The fan triangle around `centre` that holds p (the one whose smallest barycentric is largest,
// so a point on a spoke gets a definite answer), with p's clamped barycentrics there.
std::pair<int, Eigen::Vector3d> locate_in_fan(const StarMove& move, const Eigen::Vector2d& centre,
                                              const Eigen::Vector2d& p) {
  const int k = static_cast<int>(move.ring.size());
  int best = -1;
  Eigen::Vector3d best_bary = Eigen::Vector3d::Zero();
  double best_min = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < k; ++j) {
    const Eigen::Vector3d bary = barycentric2(p, centre, move.ring[j], move.ring[(j + 1) % k]);
    if (bary.minCoeff() > best_min) {
      best_min = bary.minCoeff();
      best = j;
      best_bary = bary;
    }
  }
  best_bary = best_bary.cwiseMax(0.0);
  return {best, best_bary / best_bary.sum()};
}

// The triangle of a flat triangulation that holds p (largest smallest barycentric, as in
// locate_in_fan), with p's clamped barycentrics in the triangle's corner order.
std::pair<int, Eigen::Vector3d> locate_in_disc(const RingMove& move,
                                               const std::vector<Eigen::Vector2d>& places,
                                               const Eigen::Vector2d& p) {
  int best = -1;
  Eigen::Vector3d best_bary = Eigen::Vector3d::Zero();
  double best_min = -std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < move.corners.size(); ++j) {
    const std::array<int, 3>& c = move.corners[j];
    const Eigen::Vector3d bary = barycentric2(p, places[c[0]], places[c[1]], places[c[2]]);
    if (bary.minCoeff() > best_min) {
      best_min = bary.minCoeff();
      best = static_cast<int>(j);
      best_bary = bary;
    }
  }
  best_bary = best_bary.cwiseMax(0.0);
  return {best, best_bary / best_bary.sum()};
}

// The disc face and local corner of a template point, or face -1 when the point is outside the
// disc. Moved: whether the point lies where the move acts (positive weight on a vertex whose
// place changes); points elsewhere, the centre and the disc's boundary among them, stay exactly.
struct DiscHit {
  int face = -1;
  bool moved = false;
};

DiscHit find_in_disc(const RingMove& move, const SurfacePoint& point) {
  DiscHit hit;
  const auto it = std::find(move.faces.begin(), move.faces.end(), point.face);
  if (it == move.faces.end()) return hit;
  hit.face = static_cast<int>(it - move.faces.begin());
  for (int c = 0; c < 3; ++c) {
    const int u = move.corners[hit.face][c];
    if (point.bary[c] > 0.0 && move.from[u] != move.to[u]) hit.moved = true;
  }
  return hit;
}

SurfacePoint apply_move(const std::variant<StarMove, RingMove>& move, const SurfacePoint& point) {
  if (const StarMove* star = std::get_if<StarMove>(&move)) return apply_star(*star, point);
  return apply_ring(std::get<RingMove>(move), point);
}

// The mean-value weight of edge (i, j) seen from i (Floater 2003): (tan(alpha/2) + tan(beta/2))
// / |x_j - x_i|, alpha and beta the angles at i of the two faces beside the edge.
double mean_value_weight(const Mesh& mesh, HalfedgeHandle h) {
  const Eigen::Vector3d xi = position(mesh, mesh.from_vertex_handle(h));
  const Eigen::Vector3d e = position(mesh, mesh.to_vertex_handle(h)) - xi;
  auto half_tan = [&](const Eigen::Vector3d& other) {
    const double angle = std::atan2(e.cross(other).norm(), e.dot(other));
    return std::tan(0.5 * angle);
  };
  const Eigen::Vector3d next = position(mesh, mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - xi;
  const HalfedgeHandle back = mesh.opposite_halfedge_handle(h);
  const Eigen::Vector3d prev = position(mesh, mesh.to_vertex_handle(mesh.next_halfedge_handle(back))) - xi;
  return (half_tan(next) + half_tan(prev)) / e.norm();
}

}  // namespace

// Twice the signed area of fan triangle j of `move` around centre x.
double fan_area2(const StarMove& move, int j, const Eigen::Vector2d& x) {
  const int k = static_cast<int>(move.ring.size());
  return cross2(move.ring[j] - x, move.ring[(j + 1) % k] - x);
}

// One applied star move: p in the star's open interior is re-fanned, anything else stays.
SurfacePoint apply_star(const StarMove& move, const SurfacePoint& point) {
  return apply_star(move, move.to, point);
}

SurfacePoint apply_star(const StarMove& move, const Eigen::Vector2d& to, const SurfacePoint& point) {
  const auto it = std::find(move.faces.begin(), move.faces.end(), point.face);
  if (it == move.faces.end()) return point;
  const int k = static_cast<int>(move.ring.size());
  const int j = static_cast<int>(it - move.faces.begin());
  const int s = move.center_slot[j];
  if (point.bary[s] <= 0.0) return point;  // on the star's boundary, which the move fixes
  // Flattened position, then the affine maps fan(from) -> fan(to), then back to a star face.
  const Eigen::Vector2d flat =
      point.bary[(s + 1) % 3] * move.ring[j] + point.bary[(s + 2) % 3] * move.ring[(j + 1) % k];
  const auto [m, lambda] = locate_in_fan(move, move.from, flat);
  const Eigen::Vector2d moved =
      lambda[0] * to + lambda[1] * move.ring[m] + lambda[2] * move.ring[(m + 1) % k];
  const auto [n, mu] = locate_in_fan(move, Eigen::Vector2d::Zero(), moved);
  SurfacePoint result;
  result.face = move.faces[n];
  const int t = move.center_slot[n];
  result.bary[t] = mu[0];
  result.bary[(t + 1) % 3] = mu[1];
  result.bary[(t + 2) % 3] = mu[2];
  return result;
}

bool ring_moves_point(const RingMove& move, const SurfacePoint& point) {
  return find_in_disc(move, point).moved;
}

// One applied ring move: flatten, carry the from-triangulation onto the to-triangulation, and
// locate the result in the flattened disc again.
SurfacePoint apply_ring(const RingMove& move, const SurfacePoint& point) {
  const DiscHit hit = find_in_disc(move, point);
  if (!hit.moved) return point;
  const std::array<int, 3>& c = move.corners[hit.face];
  const Eigen::Vector2d flat =
      point.bary[0] * move.rest[c[0]] + point.bary[1] * move.rest[c[1]] + point.bary[2] * move.rest[c[2]];
  const auto [m, lambda] = locate_in_disc(move, move.from, flat);
  const std::array<int, 3>& d = move.corners[m];
  const Eigen::Vector2d moved =
      lambda[0] * move.to[d[0]] + lambda[1] * move.to[d[1]] + lambda[2] * move.to[d[2]];
  const auto [n, mu] = locate_in_disc(move, move.rest, moved);
  return SurfacePoint{move.faces[n], mu};
}

// Twice the signed area of disc face j with the vertices at `places`.
double disc_area2(const RingMove& move, const std::vector<Eigen::Vector2d>& places, int j) {
  const std::array<int, 3>& c = move.corners[j];
  return cross2(places[c[1]] - places[c[0]], places[c[2]] - places[c[0]]);
}

std::optional<RingMove> flatten_disc(const Mesh& mesh, VertexHandle center) {
  if (mesh.is_boundary(center)) return std::nullopt;
  RingMove disc;
  disc.center = center.idx();
  std::vector<int> ring;
  const HalfedgeHandle first = mesh.halfedge_handle(center);
  HalfedgeHandle h = first;
  do {
    ring.push_back(mesh.to_vertex_handle(h).idx());
    h = mesh.opposite_halfedge_handle(mesh.prev_halfedge_handle(h));
  } while (h != first);
  std::map<int, int> local{{center.idx(), 0}};
  disc.vertices.push_back(center.idx());
  for (int r : ring) {
    if (mesh.is_boundary(mesh.vertex_handle(r)) ||
        !local.emplace(r, static_cast<int>(disc.vertices.size())).second) {
      return std::nullopt;
    }
    disc.vertices.push_back(r);
    for (FaceHandle f : mesh.vf_range(mesh.vertex_handle(r))) disc.faces.push_back(f.idx());
  }
  std::sort(disc.faces.begin(), disc.faces.end());
  disc.faces.erase(std::unique(disc.faces.begin(), disc.faces.end()), disc.faces.end());
  const int n_inner = static_cast<int>(disc.vertices.size());
  // Boundary: the disc faces' halfedges whose opposite face is outside, one cycle.
  std::map<int, HalfedgeHandle> boundary_out;
  for (int f : disc.faces) {
    std::array<int, 3> c{};
    int k = 0;
    for (VertexHandle w : mesh.fv_range(mesh.face_handle(f))) {
      if (local.emplace(w.idx(), static_cast<int>(disc.vertices.size())).second)
        disc.vertices.push_back(w.idx());
      c[k++] = local.at(w.idx());
    }
    disc.corners.push_back(c);
    for (HalfedgeHandle e : mesh.fh_range(mesh.face_handle(f))) {
      const FaceHandle across = mesh.opposite_face_handle(e);
      if (across.is_valid() && std::binary_search(disc.faces.begin(), disc.faces.end(), across.idx()))
        continue;
      if (!boundary_out.emplace(mesh.from_vertex_handle(e).idx(), e).second) return std::nullopt;
    }
  }
  const int n_vertices = static_cast<int>(disc.vertices.size());
  if (static_cast<int>(boundary_out.size()) != n_vertices - n_inner) return std::nullopt;
  std::vector<int> cycle;
  std::vector<double> length{0.0};
  HalfedgeHandle e = boundary_out.begin()->second;
  for (int i = 0; i < n_vertices - n_inner; ++i) {
    const int from = mesh.from_vertex_handle(e).idx();
    if (local.at(from) < n_inner) return std::nullopt;
    cycle.push_back(local.at(from));
    length.push_back(length.back() + mesh.calc_edge_length(e));
    const auto next = boundary_out.find(mesh.to_vertex_handle(e).idx());
    if (next == boundary_out.end()) return std::nullopt;
    e = next->second;
  }
  if (e != boundary_out.begin()->second) return std::nullopt;  // more than one boundary cycle
  disc.rest.assign(n_vertices, Eigen::Vector2d::Zero());
  for (std::size_t i = 0; i < cycle.size(); ++i) {
    const double angle = 2.0 * std::numbers::pi * length[i] / length.back();
    disc.rest[cycle[i]] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
  }
  // Interior places: every inner vertex the mean-value combination of its neighbours.
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(n_inner, n_inner);
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n_inner, 2);
  for (int i = 0; i < n_inner; ++i) {
    for (HalfedgeHandle out : mesh.voh_range(mesh.vertex_handle(disc.vertices[i]))) {
      const double w = mean_value_weight(mesh, out);
      if (!(w > 0.0) || !std::isfinite(w)) return std::nullopt;
      const int j = local.at(mesh.to_vertex_handle(out).idx());
      system(i, i) += w;
      if (j < n_inner) {
        system(i, j) -= w;
      } else {
        rhs.row(i) += w * disc.rest[j].transpose();
      }
    }
  }
  const Eigen::MatrixX2d inner = system.partialPivLu().solve(rhs);
  for (int i = 0; i < n_inner; ++i) disc.rest[i] = inner.row(i).transpose();
  for (std::size_t j = 0; j < disc.faces.size(); ++j) {
    if (!(disc_area2(disc, disc.rest, static_cast<int>(j)) > 0.0)) return std::nullopt;
  }
  disc.from = disc.rest;
  disc.to = disc.rest;
  return disc;
}

std::optional<StarMove> flatten_star(const Mesh& mesh, VertexHandle v) {
  if (mesh.is_boundary(v)) return std::nullopt;
  StarMove star;
  star.center = v.idx();
  const Eigen::Vector3d x = position(mesh, v);
  std::vector<double> angles;
  std::vector<double> lengths;
  const HalfedgeHandle first = mesh.halfedge_handle(v);
  HalfedgeHandle h = first;
  do {
    const FaceHandle f = mesh.face_handle(h);
    int slot = 0;
    for (VertexHandle w : mesh.fv_range(f)) {
      if (w == v) break;
      ++slot;
    }
    star.faces.push_back(f.idx());
    star.center_slot.push_back(slot);
    const Eigen::Vector3d a = position(mesh, mesh.to_vertex_handle(h)) - x;
    const Eigen::Vector3d b = position(mesh, mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - x;
    angles.push_back(std::atan2(a.cross(b).norm(), a.dot(b)));
    lengths.push_back(a.norm());
    h = mesh.opposite_halfedge_handle(mesh.prev_halfedge_handle(h));
  } while (h != first);
  double sum = 0.0;
  for (double angle : angles) sum += angle;
  if (!(sum > 0.0)) return std::nullopt;
  const double scale = 2.0 * std::numbers::pi / sum;
  double direction = 0.0;
  for (std::size_t j = 0; j < angles.size(); ++j) {
    if (angles[j] * scale >= std::numbers::pi * (1.0 - 1e-6) || !(lengths[j] > 0.0)) return std::nullopt;
    star.ring.emplace_back(lengths[j] * std::cos(direction), lengths[j] * std::sin(direction));
    direction += angles[j] * scale;
  }
  return star;
}

SurfacePoint disc_point(const RingMove& move, const Eigen::Vector2d& flat) {
  const auto [face, bary] = locate_in_disc(move, move.rest, flat);
  return SurfacePoint{move.faces[face], bary};
}

SurfacePoint at_vertex(const Mesh& mesh, VertexHandle v) {
  FaceHandle best;
  for (FaceHandle f : mesh.vf_range(v)) {
    if (!best.is_valid() || f.idx() < best.idx()) best = f;
  }
  SurfacePoint point;
  point.face = best.idx();
  int corner = 0;
  for (VertexHandle w : mesh.fv_range(best)) point.bary[corner++] = (w == v) ? 1.0 : 0.0;
  return point;
}

SurfacePoint TemplateWarp::operator()(const SurfacePoint& point) const {
  SurfacePoint result = point;
  for (const auto& move : moves) result = apply_move(move, result);
  return result;
}

}  // namespace xparam
