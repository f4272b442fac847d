#include "map/remesh_untangling.h"

#include "core/errors.h"
#include "core/stopwatch.h"

#include <tbb/parallel_for.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>

namespace xparam {
namespace {

// A flipped face scores below this, however little it folds.
constexpr double kTiny = 1e-300;

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Twice the signed area of fan triangle j of `move` around centre x.
double fan_area2(const StarMove& move, int j, const Eigen::Vector2d& x) {
  const int k = static_cast<int>(move.ring.size());
  return cross2(move.ring[j] - x, move.ring[(j + 1) % k] - x);
}

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

// One applied move: p in the star's open interior is re-fanned, anything else stays.
SurfacePoint apply_move(const StarMove& move, const SurfacePoint& point) {
  const auto it = std::find(move.faces.begin(), move.faces.end(), point.face);
  if (it == move.faces.end()) return point;
  const int k = static_cast<int>(move.ring.size());
  const int j = static_cast<int>(it - move.faces.begin());
  const int s = move.center_slot[j];
  if (point.bary[s] <= 0.0) return point;  // on the star's boundary, which the move fixes
  // Flattened position, then the affine maps fan(from) -> fan(to), then back to a star face.
  const Eigen::Vector2d flat = point.bary[(s + 1) % 3] * move.ring[j] + point.bary[(s + 2) % 3] * move.ring[(j + 1) % k];
  const auto [m, lambda] = locate_in_fan(move, move.from, flat);
  const Eigen::Vector2d moved = lambda[0] * move.to + lambda[1] * move.ring[m] + lambda[2] * move.ring[(m + 1) % k];
  const auto [n, mu] = locate_in_fan(move, Eigen::Vector2d::Zero(), moved);
  SurfacePoint result;
  result.face = move.faces[n];
  const int t = move.center_slot[n];
  result.bary[t] = mu[0];
  result.bary[(t + 1) % 3] = mu[1];
  result.bary[(t + 2) % 3] = mu[2];
  return result;
}

// The flattened star of an interior vertex, or nothing when it has a boundary edge or a scaled
// angle is not below pi (the flat fan would not be positive).
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

// Vertex v as a surface point: its lowest-index face, barycentric 1 at v's corner.
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

// A candidate's verdict on the faces it touches.
struct Score {
  std::vector<int> flipped;  // ascending face ids
  double worst = -std::numeric_limits<double>::infinity();  // smallest face quality
};

class Untangler {
 public:
  Untangler(const Mesh& source, std::vector<MappedPoint> images, const SurfaceMap& gamma, const Mesh& target,
            const std::vector<SurfacePoint>& fixed_points, const UntangleSettings& settings)
      : source_(source), gamma_(gamma), reference_(target), settings_(settings), images_(std::move(images)) {
    const int n = static_cast<int>(source.n_vertices());
    if (static_cast<int>(images_.size()) != n) {
      throw ParamError("untangle remesh: " + std::to_string(images_.size()) + " images for " + std::to_string(n) +
                       " template vertices");
    }
    points_.resize(n);
    for (VertexHandle v : source.vertices()) points_[v.idx()] = at_vertex(source, v);
    double source_area = 0.0;
    for (FaceHandle f : source.faces()) {
      std::array<int, 3> t{};
      int c = 0;
      for (VertexHandle v : source.fv_range(f)) t[c++] = v.idx();
      faces_.push_back(t);
      face_area_.push_back(source.calc_face_area(f));
      source_area += face_area_.back();
    }
    scale_ = reference_.target_area() / source_area;
    blocked_.assign(n, false);
    for (const SurfacePoint& p : fixed_points) {
      int corner = 0;
      for (VertexHandle v : source.fv_range(source.face_handle(p.face))) {
        if (p.bary[corner++] > 0.0) blocked_[v.idx()] = true;
      }
    }
    moved_.assign(n, false);
    flipped_.assign(faces_.size(), false);
    for (std::size_t f = 0; f < faces_.size(); ++f) flipped_[f] = quality(static_cast<int>(f), {}) < 0.0;
  }

  UntangleResult run() {
    UntangleResult result;
    result.settings = settings_;
    result.flipped_before = static_cast<int>(std::count(flipped_.begin(), flipped_.end(), true));
    for (int round = 0; round < settings_.rounds; ++round) {
      std::vector<int> vertices;
      for (std::size_t f = 0; f < faces_.size(); ++f) {
        if (flipped_[f]) vertices.insert(vertices.end(), faces_[f].begin(), faces_[f].end());
      }
      if (vertices.empty()) break;
      std::sort(vertices.begin(), vertices.end());
      vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
      ++result.rounds;
      bool changed = false;
      for (int v : vertices) changed = try_vertex(v) || changed;
      if (!changed) break;
    }
    result.flipped_after = static_cast<int>(std::count(flipped_.begin(), flipped_.end(), true));
    double sum = 0.0;
    for (VertexHandle v : source_.vertices()) {
      if (!moved_[v.idx()]) continue;
      const double move = (position(source_, points_[v.idx()]) - position(source_, v)).norm();
      ++result.moved_vertices;
      sum += move;
      result.max_move = std::max(result.max_move, move);
    }
    result.mean_move = result.moved_vertices > 0 ? sum / result.moved_vertices : 0.0;
    result.warp = std::move(warp_);
    result.template_points = std::move(points_);
    result.images = std::move(images_);
    return result;
  }

 private:
  // Quality of remesh face f, with the images of some vertices replaced: rho, its signed area
  // along the reference normal over the template face's area scaled to the target's, folded so
  // 1 is best (min(rho, 1/rho)) when positive; rho itself when flipped (negative, so a face
  // that folds less scores higher), 0 when degenerate.
  double quality(int f, const std::map<int, const MappedPoint*>& replaced) const {
    const std::array<int, 3>& t = faces_[f];
    const MappedPoint* corner[3];
    for (int c = 0; c < 3; ++c) {
      const auto it = replaced.find(t[c]);
      corner[c] = it != replaced.end() ? it->second : &images_[t[c]];
    }
    const Eigen::Vector3d normal =
        (corner[1]->position - corner[0]->position).cross(corner[2]->position - corner[0]->position);
    if (normal.norm() == 0.0) return 0.0;
    const Eigen::Vector3d reference = reference_.normal(corner[0]->on_input, corner[1]->on_input, corner[2]->on_input);
    const double dot = normal.dot(reference);
    const double length = reference.norm();
    if (dot < 0.0) return std::min(0.5 * dot / length / (face_area_[f] * scale_), -kTiny);
    if (length == 0.0) return 0.0;
    const double rho = 0.5 * dot / length / (face_area_[f] * scale_);
    return rho > 0.0 ? std::min(rho, 1.0 / rho) : 0.0;
  }

  Score score(const std::vector<int>& faces, const std::map<int, const MappedPoint*>& replaced) const {
    Score s;
    s.worst = std::numeric_limits<double>::infinity();
    for (int f : faces) {
      const double q = quality(f, replaced);
      if (q < 0.0) s.flipped.push_back(f);
      s.worst = std::min(s.worst, q);
    }
    return s;
  }

  // Try star moves of vertex v; apply the best one that removes flips and creates none.
  bool try_vertex(int v) {
    const VertexHandle vh = source_.vertex_handle(v);
    if (blocked_[v]) return false;
    bool touches_flip = false;
    for (FaceHandle f : source_.vf_range(vh)) touches_flip = touches_flip || flipped_[f.idx()];
    if (!touches_flip) return false;
    std::optional<StarMove> star = flatten_star(source_, vh);
    if (!star) return false;

    // The fan centre: where phi puts v now when that is inside the star's kernel.
    const SurfacePoint current = points_[v];
    const StarMove probe = *star;
    const auto face_it = std::find(probe.faces.begin(), probe.faces.end(), current.face);
    if (face_it != probe.faces.end()) {
      const int j = static_cast<int>(face_it - probe.faces.begin());
      const int s = probe.center_slot[j];
      const int k = static_cast<int>(probe.ring.size());
      const Eigen::Vector2d c =
          current.bary[(s + 1) % 3] * probe.ring[j] + current.bary[(s + 2) % 3] * probe.ring[(j + 1) % k];
      bool inside = current.bary[s] > 0.0;
      for (int i = 0; i < k && inside; ++i) inside = fan_area2(probe, i, c) > 1e-3 * fan_area2(probe, i, Eigen::Vector2d::Zero());
      if (inside) star->from = c;
    }

    // Vertices whose point the move carries: v and any moved vertex inside v's open star.
    std::vector<int> affected;
    for (int u : moved_list_) {
      if (u != v && apply_touches(*star, points_[u])) affected.push_back(u);
    }
    affected.push_back(v);
    std::sort(affected.begin(), affected.end());
    std::vector<int> check;
    for (int u : affected) {
      for (FaceHandle f : source_.vf_range(source_.vertex_handle(u))) check.push_back(f.idx());
    }
    std::sort(check.begin(), check.end());
    check.erase(std::unique(check.begin(), check.end()), check.end());
    const Score before = score(check, {});

    const std::vector<Eigen::Vector2d> targets = candidates(*star);
    struct Trial {
      std::vector<SurfacePoint> points;
      std::vector<MappedPoint> images;
      Score score;
    };
    std::vector<Trial> trials(targets.size());
    tbb::parallel_for(0, static_cast<int>(targets.size()), [&](int i) {
      StarMove move = *star;
      move.to = targets[i];
      Trial& trial = trials[i];
      std::map<int, const MappedPoint*> replaced;
      trial.points.reserve(affected.size());
      trial.images.reserve(affected.size());
      for (int u : affected) {
        trial.points.push_back(apply_move(move, points_[u]));
        trial.images.push_back(gamma_(trial.points.back()));
      }
      for (std::size_t a = 0; a < affected.size(); ++a) replaced[affected[a]] = &trial.images[a];
      trial.score = score(check, replaced);
    });

    // Fewest flips, never a face that was not flipped before; then the best worst face.
    int best = -1;
    for (int i = 0; i < static_cast<int>(trials.size()); ++i) {
      const Score& s = trials[i].score;
      if (!std::includes(before.flipped.begin(), before.flipped.end(), s.flipped.begin(), s.flipped.end())) continue;
      if (best < 0 || s.flipped.size() < trials[best].score.flipped.size() ||
          (s.flipped.size() == trials[best].score.flipped.size() && s.worst > trials[best].score.worst)) {
        best = i;
      }
    }
    // Kept when it removes flips, or (a step towards removing them with a later move of a
    // neighbour) when it leaves the same flips folded clearly less.
    if (best < 0) return false;
    const Score& chosen = trials[best].score;
    const bool fewer = chosen.flipped.size() < before.flipped.size();
    const bool less_folded = chosen.flipped.size() == before.flipped.size() &&
                             chosen.worst > before.worst + settings_.min_gain;
    if (!fewer && !less_folded) return false;

    star->to = targets[best];
    warp_.moves.push_back(std::move(*star));
    for (std::size_t a = 0; a < affected.size(); ++a) {
      const int u = affected[a];
      points_[u] = trials[best].points[a];
      images_[u] = trials[best].images[a];
      if (!moved_[u]) {
        moved_[u] = true;
        moved_list_.insert(std::lower_bound(moved_list_.begin(), moved_list_.end(), u), u);
      }
    }
    for (int f : check) flipped_[f] = false;
    for (int f : trials[best].score.flipped) flipped_[f] = true;
    return true;
  }

  // True when the move would carry `point` (it lies in the star's open interior).
  static bool apply_touches(const StarMove& star, const SurfacePoint& point) {
    const auto it = std::find(star.faces.begin(), star.faces.end(), point.face);
    return it != star.faces.end() && point.bary[star.center_slot[it - star.faces.begin()]] > 0.0;
  }

  // New fan centres: steps from the current centre towards the kernel's boundary, along the
  // spokes, the ring edges' midpoints and evenly spaced directions.
  std::vector<Eigen::Vector2d> candidates(const StarMove& star) const {
    const int k = static_cast<int>(star.ring.size());
    std::vector<Eigen::Vector2d> directions;
    for (int j = 0; j < k; ++j) {
      directions.push_back(star.ring[j] - star.from);
      directions.push_back(0.5 * (star.ring[j] + star.ring[(j + 1) % k]) - star.from);
    }
    for (int i = 0; i < settings_.extra_directions; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / settings_.extra_directions;
      directions.emplace_back(std::cos(angle), std::sin(angle));
    }
    std::vector<Eigen::Vector2d> points;
    for (const Eigen::Vector2d& direction : directions) {
      if (!(direction.norm() > 0.0)) continue;
      const Eigen::Vector2d d = direction.normalized();
      // Fan triangle j's doubled area along from + t d is linear: area_j(from) - t cross(d, e_j).
      double t_max = std::numeric_limits<double>::infinity();
      for (int j = 0; j < k; ++j) {
        const double rate = cross2(d, star.ring[(j + 1) % k] - star.ring[j]);
        if (rate > 0.0) t_max = std::min(t_max, fan_area2(star, j, star.from) / rate);
      }
      if (!std::isfinite(t_max)) continue;
      for (double step : settings_.steps) points.push_back(star.from + step * t_max * d);
    }
    return points;
  }

  const Mesh& source_;
  const SurfaceMap& gamma_;
  const RemeshReference reference_;
  const UntangleSettings settings_;
  std::vector<MappedPoint> images_;    // #V: Gamma(phi(x_i))
  std::vector<SurfacePoint> points_;   // #V: phi(x_i)
  std::vector<std::array<int, 3>> faces_;
  std::vector<double> face_area_;      // #F template face areas
  double scale_ = 1.0;                 // target area / template area
  std::vector<bool> blocked_;          // #V: an anchor in the open star
  std::vector<bool> moved_;            // #V: phi(x_i) != x_i
  std::vector<int> moved_list_;        // the moved vertices, ascending
  std::vector<bool> flipped_;          // #F: remesh face flipped now
  TemplateWarp warp_;
};

}  // namespace

SurfacePoint TemplateWarp::operator()(const SurfacePoint& point) const {
  SurfacePoint result = point;
  for (const StarMove& move : moves) result = apply_move(move, result);
  return result;
}

UntangleResult untangle_remesh(const Mesh& source, std::vector<MappedPoint> images, const SurfaceMap& gamma,
                               const Mesh& target, const std::vector<SurfacePoint>& fixed_points,
                               const UntangleSettings& settings) {
  Stopwatch watch;
  Untangler untangler(source, std::move(images), gamma, target, fixed_points, settings);
  UntangleResult result = untangler.run();
  result.seconds = watch.lap();
  return result;
}

}  // namespace xparam
