#include "map/remesh_untangling.h"

#include "core/errors.h"
#include "core/planar.h"
#include "core/stopwatch.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <tuple>
#include <variant>

namespace xparam {
namespace {

// A flipped face scores below this, however little it folds.
constexpr double kTiny = 1e-300;

// A candidate's verdict on the faces it touches.
struct Score {
  int flipped = 0;                                          // how many are flipped
  double worst = -std::numeric_limits<double>::infinity();  // smallest face quality
};

// A ring move's cost over some remesh faces, compared lexicographically: flipped faces, then
// how far they fold, then slack (faces barely positive, and how far the ring vertices slide).
struct RingCost {
  int flips = 0;
  double fold = 0.0;
  double slack = 0.0;

  RingCost operator+(const RingCost& o) const { return {flips + o.flips, fold + o.fold, slack + o.slack}; }
  bool operator<(const RingCost& o) const {
    return std::tie(flips, fold, slack) < std::tie(o.flips, o.fold, o.slack);
  }
};

// Ring-move constants: a cost at or above kInvalid flips marks a choice that does not embed the
// disc; a flat face keeps at least kMinArea of its rest area; remesh faces of quality below
// kComfort count as slack; a slide across the whole ring radius counts kMoveWeight.
constexpr int kInvalid = 1 << 20;
constexpr double kMinArea = 1e-3;
constexpr double kComfort = 0.1;
constexpr double kMoveWeight = 0.01;

class Untangler {
 public:
  Untangler(const Mesh& source, std::vector<MappedPoint> images, const SurfaceMap& gamma, const Mesh& target,
            const std::vector<SurfacePoint>& fixed_points, const UntangleSettings& settings)
      : source_(source), gamma_(gamma), reference_(target), settings_(settings), images_(std::move(images)) {
    const int n = static_cast<int>(source.n_vertices());
    if (static_cast<int>(images_.size()) != n) {
      throw ParamError("untangle remesh: " + std::to_string(images_.size()) + " images for " +
                       std::to_string(n) + " template vertices");
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
    changed_.assign(n, 0);
    ring_failed_.assign(n, -1);
    star_failed_.assign(n, {-1, {}});
    flipped_.assign(faces_.size(), false);
    for (std::size_t f = 0; f < faces_.size(); ++f)
      flipped_[f] = quality(static_cast<int>(f), Replacements{}) < 0.0;
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
      if (settings_.star_moves) {
        for (int v : vertices) changed = try_vertex(v) || changed;
      }
      // What single vertices cannot undo (the star sweep stalled), their centres' rings may.
      if (!changed && settings_.ring_moves) {
        for (int v : vertices) changed = try_ring(v) || changed;
      }
      if (!changed) break;
    }
    result.flipped_after = static_cast<int>(std::count(flipped_.begin(), flipped_.end(), true));
    for (const auto& move : warp_.moves)
      result.ring_moves += static_cast<int>(std::holds_alternative<RingMove>(move));
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
  // Images standing in for a few vertices' (those a trial move carries: a handful, so a linear
  // search), and the image of v with them.
  using Replacements = std::vector<std::pair<int, const MappedPoint*>>;
  const MappedPoint* image_of(int v, const Replacements& replaced) const {
    for (const auto& [u, image] : replaced) {
      if (u == v) return image;
    }
    return &images_[v];
  }

  // Quality of remesh face f, with the images of some vertices replaced: rho, its signed area
  // along the reference normal over the template face's area scaled to the target's, folded so
  // 1 is best (min(rho, 1/rho)) when positive; rho itself when flipped (negative, so a face
  // that folds less scores higher), 0 when degenerate.
  double quality(int f, const Replacements& replaced) const {
    const std::array<int, 3>& t = faces_[f];
    const MappedPoint* corner[3];
    for (int c = 0; c < 3; ++c) corner[c] = image_of(t[c], replaced);
    const Eigen::Vector3d normal =
        (corner[1]->position - corner[0]->position).cross(corner[2]->position - corner[0]->position);
    if (normal.norm() == 0.0) return 0.0;
    const Eigen::Vector3d reference =
        reference_.normal(corner[0]->on_input, corner[1]->on_input, corner[2]->on_input);
    const double dot = normal.dot(reference);
    const double length = reference.norm();
    if (dot < 0.0) return std::min(0.5 * dot / length / (face_area_[f] * scale_), -kTiny);
    if (length == 0.0) return 0.0;
    const double rho = 0.5 * dot / length / (face_area_[f] * scale_);
    return rho > 0.0 ? std::min(rho, 1.0 / rho) : 0.0;
  }

  Score score(const std::vector<int>& faces, const Replacements& replaced) const {
    Score s;
    s.worst = std::numeric_limits<double>::infinity();
    for (int f : faces) {
      const double q = quality(f, replaced);
      s.flipped += q < 0.0;
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
    if (star_unchanged_since_failure(v, *star)) return false;

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
      for (int i = 0; i < k && inside; ++i)
        inside = fan_area2(probe, i, c) > 1e-3 * fan_area2(probe, i, Eigen::Vector2d::Zero());
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
    const Score before = score(check, Replacements{});

    const std::vector<Eigen::Vector2d> targets = candidates(*star);
    // Each trial's points and images in one block of `carried` slots: this runs for every
    // candidate of every star tried, and vectors per trial were most of the untangling's
    // allocations.
    const std::size_t carried = affected.size();
    std::vector<SurfacePoint> trial_points(targets.size() * carried);
    std::vector<MappedPoint> trial_images(targets.size() * carried);
    std::vector<Score> trial_scores(targets.size());
    tbb::parallel_for(tbb::blocked_range<int>(0, static_cast<int>(targets.size())),
                      [&](const tbb::blocked_range<int>& range) {
                        Replacements replaced(carried);
                        for (int i = range.begin(); i != range.end(); ++i) {
                          for (std::size_t a = 0; a < carried; ++a) {
                            SurfacePoint& point = trial_points[i * carried + a];
                            MappedPoint& image = trial_images[i * carried + a];
                            point = apply_star(*star, targets[i], points_[affected[a]]);
                            image = gamma_(point);
                            replaced[a] = {affected[a], &image};
                          }
                          trial_scores[i] = score(check, replaced);
                        }
                      });

    // Fewest flips, then the best worst face.
    int best = -1;
    for (int i = 0; i < static_cast<int>(trial_scores.size()); ++i) {
      const Score& s = trial_scores[i];
      if (best < 0 || s.flipped < trial_scores[best].flipped ||
          (s.flipped == trial_scores[best].flipped && s.worst > trial_scores[best].worst)) {
        best = i;
      }
    }
    if (best < 0 || !improves(before, trial_scores[best])) {
      std::vector<int> read;  // the corners of the faces scored: what the trials read
      for (int f : check) read.insert(read.end(), faces_[f].begin(), faces_[f].end());
      std::sort(read.begin(), read.end());
      read.erase(std::unique(read.begin(), read.end()), read.end());
      star_failed_[v] = {commits_, std::move(read)};
      return false;
    }

    star->to = targets[best];
    const auto slots = [&](const auto& all) {
      return std::vector(all.begin() + best * carried, all.begin() + (best + 1) * carried);
    };
    commit(std::move(*star), affected, slots(trial_points), slots(trial_images), check);
    return true;
  }

  // Candidate places of a ring move: for each radius (a fraction of the ring's mean flat radius
  // `radius`), settings_.ring_angles evenly spaced angles about the disc's centre, then
  // bisected where the images turn about the centre's image by more than twice that spacing (or
  // backwards), a few times: where Gamma squeezes a wide wedge of the template into a narrow one
  // on the target, the ring needs places the even grid steps over.
  void ring_places(const RingMove& move, const MappedPoint& centre, double radius,
                   std::vector<Eigen::Vector2d>& places, std::vector<MappedPoint>& images,
                   std::vector<double>& turns) const {
    const Eigen::Vector3d reference = reference_.normal(centre.on_input, centre.on_input, centre.on_input);
    if (!(reference.norm() > 0.0)) return;  // no tangent plane to measure turns in: no places
    const Eigen::Vector3d normal = reference.normalized();
    const Eigen::Vector3d e1 = normal.unitOrthogonal();
    const Eigen::Vector3d e2 = normal.cross(e1);
    auto turn = [&](const MappedPoint& image) {
      const Eigen::Vector3d d = image.position - centre.position;
      return std::atan2(d.dot(e2), d.dot(e1));
    };
    const double spacing = 2.0 * std::numbers::pi / settings_.ring_angles;
    for (double fraction : settings_.ring_radii) {
      std::vector<double> angles;
      for (int i = 0; i < settings_.ring_angles; ++i) angles.push_back(spacing * i);
      const std::size_t first = places.size();
      for (int level = 0;; ++level) {
        // Evaluate the new angles (in parallel, each into its slot).
        const std::size_t base = places.size();
        places.resize(base + angles.size());
        images.resize(places.size());
        tbb::parallel_for(0, static_cast<int>(angles.size()), [&](int i) {
          const double angle = angles[i];
          places[base + i] =
              move.rest[0] + fraction * radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
          images[base + i] = gamma_(disc_point(move, places[base + i]));
        });
        // Angles sorted with their sample index; refine the gaps that turn too far.
        std::vector<std::pair<double, std::size_t>> order;
        for (std::size_t i = first; i < places.size(); ++i) {
          const Eigen::Vector2d d = places[i] - move.rest[0];
          double angle = std::atan2(d.y(), d.x());
          if (angle < 0.0) angle += 2.0 * std::numbers::pi;
          order.emplace_back(angle, i);
        }
        std::sort(order.begin(), order.end());
        if (level == settings_.ring_refinements) break;
        angles.clear();
        for (std::size_t i = 0; i < order.size(); ++i) {
          const auto& [a, ia] = order[i];
          const auto& [b, ib] = order[(i + 1) % order.size()];
          double step = turn(images[ib]) - turn(images[ia]);
          step = std::remainder(step, 2.0 * std::numbers::pi);
          if (step >= 0.0 && step <= 2.0 * spacing) continue;
          const double gap = i + 1 < order.size() ? b - a : b + 2.0 * std::numbers::pi - a;
          angles.push_back(a + 0.5 * gap);
        }
        if (angles.empty()) break;
      }
    }
    turns.clear();
    for (const MappedPoint& image : images) turns.push_back(turn(image));
  }

  // Whether the last star move tried at v failed and nothing it read has changed since: no image
  // of a corner of the faces it scored, and no moved point into `star`. It would fail the same way
  // (a vertex whose neighbourhood stays folded is visited in every round).
  bool star_unchanged_since_failure(int v, const StarMove& star) const {
    const auto& [failed, read] = star_failed_[v];
    if (failed < 0) return false;
    for (int u : read) {
      if (changed_[u] > failed) return false;
    }
    for (int u : moved_list_) {
      if (changed_[u] > failed && apply_touches(star, points_[u])) return false;
    }
    return true;
  }

  // Record a kept move: the new points and images of the vertices it carries, and which of the
  // faces it changed (`check`) are flipped now.
  void commit(std::variant<StarMove, RingMove> move, const std::vector<int>& affected,
              const std::vector<SurfacePoint>& points, const std::vector<MappedPoint>& images,
              const std::vector<int>& check) {
    warp_.moves.push_back(std::move(move));
    ++commits_;
    for (std::size_t a = 0; a < affected.size(); ++a) {
      const int u = affected[a];
      changed_[u] = commits_;
      points_[u] = points[a];
      images_[u] = images[a];
      if (!moved_[u]) {
        moved_[u] = true;
        moved_list_.insert(std::lower_bound(moved_list_.begin(), moved_list_.end(), u), u);
      }
    }
    for (int f : check) flipped_[f] = quality(f, Replacements{}) < 0.0;
  }

  // Faces around any of `vertices`, ascending.
  std::vector<int> faces_around(const std::vector<int>& vertices) const {
    std::vector<int> faces;
    for (int u : vertices) {
      for (FaceHandle f : source_.vf_range(source_.vertex_handle(u))) faces.push_back(f.idx());
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    return faces;
  }

  // A ring move around v: v stays, its one-ring vertices (those free to move) are re-placed
  // jointly inside v's flattened two-ring disc.
  bool try_ring(int v) {
    const VertexHandle vh = source_.vertex_handle(v);
    bool touches_flip = false;
    for (FaceHandle f : source_.vf_range(vh)) touches_flip = touches_flip || flipped_[f.idx()];
    if (!touches_flip) return false;
    std::optional<RingMove> disc = flatten_disc(source_, vh);
    if (!disc) return false;
    RingMove& move = *disc;
    // Not again while nothing it looks at (the disc's vertices, points moved into the disc) has
    // changed since it last failed here: it would fail the same way.
    if (ring_failed_[v] >= 0) {
      bool changed = false;
      for (int u : move.vertices) changed = changed || changed_[u] > ring_failed_[v];
      for (int u : moved_list_) {
        changed = changed || (changed_[u] > ring_failed_[v] &&
                              std::binary_search(move.faces.begin(), move.faces.end(), points_[u].face));
      }
      if (!changed) return false;
    }
    ring_failed_[v] = commits_;
    const int k = static_cast<int>(source_.valence(vh));  // ring vertices are local ids 1..k

    // Current places of the ring vertices (earlier moves may have slid them inside the disc).
    for (int j = 1; j <= k; ++j) {
      const SurfacePoint& p = points_[move.vertices[j]];
      const auto it = std::find(move.faces.begin(), move.faces.end(), p.face);
      if (it == move.faces.end()) return false;
      const std::array<int, 3>& c = move.corners[it - move.faces.begin()];
      move.from[j] = p.bary[0] * move.rest[c[0]] + p.bary[1] * move.rest[c[1]] + p.bary[2] * move.rest[c[2]];
    }
    const int n_faces = static_cast<int>(move.faces.size());
    for (int j = 0; j < n_faces; ++j) {
      if (!(disc_area2(move, move.from, j) > kMinArea * disc_area2(move, move.rest, j))) return false;
    }

    // Each disc face depends on one ring vertex (slot j-1) or two consecutive ones (the pair
    // starting at slot j-1); anything else breaks the chain the search relies on.
    std::vector<std::vector<int>> single(k);
    std::vector<std::vector<int>> pair(k);
    for (int j = 0; j < n_faces; ++j) {
      std::vector<int> slots;
      for (int u : move.corners[j]) {
        if (u >= 1 && u <= k) slots.push_back(u - 1);
      }
      std::sort(slots.begin(), slots.end());
      if (slots.size() == 1) {
        single[slots[0]].push_back(j);
      } else if (slots.size() == 2 && slots[1] == slots[0] + 1) {
        pair[slots[0]].push_back(j);
      } else if (slots.size() == 2 && slots[0] == 0 && slots[1] == k - 1) {
        pair[k - 1].push_back(j);
      } else {
        return false;
      }
    }

    // Candidate places: circles about the centre, each sampled where Gamma turns fast.
    double radius = 0.0;
    for (int j = 1; j <= k; ++j) radius += (move.rest[j] - move.rest[0]).norm() / k;
    std::vector<Eigen::Vector2d> places;
    std::vector<MappedPoint> place_images;
    std::vector<double> place_turns;  // direction of each place's image about the centre's, in [-pi, pi]
    ring_places(move, images_[v], radius, places, place_images, place_turns);

    // Options of ring slot j: stay (option 0), or any grid place (option 1 + i) when free.
    const int n_options = 1 + static_cast<int>(places.size());
    // The search scores remesh faces with the reference normal summed from the corners'
    // interpolated normals (measure_remesh_quality's rule where the corners share no target
    // face); the move it picks is then judged by the exact test.
    const int n_disc = static_cast<int>(move.vertices.size());
    std::vector<Eigen::Vector3d> stay_normal(n_disc);
    for (int u = 0; u < n_disc; ++u)
      stay_normal[u] = reference_.interpolated_normal(images_[move.vertices[u]].on_input);
    std::vector<Eigen::Vector3d> place_normal(places.size());
    for (std::size_t i = 0; i < places.size(); ++i)
      place_normal[i] = reference_.interpolated_normal(place_images[i].on_input);
    // Where the search has the disc's vertices: their flat places, images and image normals. Each
    // parallel task of the search has its own.
    struct DiscState {
      std::vector<Eigen::Vector2d> trial;
      std::vector<const Eigen::Vector3d*> at;
      std::vector<const Eigen::Vector3d*> normal;
    };
    auto reset = [&](DiscState& state, int u) {
      state.trial[u] = move.from[u];
      state.at[u] = &images_[move.vertices[u]].position;
      state.normal[u] = &stay_normal[u];
    };
    auto staying = [&]() {
      DiscState state{std::vector<Eigen::Vector2d>(n_disc), std::vector<const Eigen::Vector3d*>(n_disc),
                      std::vector<const Eigen::Vector3d*>(n_disc)};
      for (int u = 0; u < n_disc; ++u) reset(state, u);
      return state;
    };
    auto approximate_quality = [&](const DiscState& state, int f) {
      const std::array<int, 3>& c = move.corners[f];
      const Eigen::Vector3d n = (*state.at[c[1]] - *state.at[c[0]]).cross(*state.at[c[2]] - *state.at[c[0]]);
      const Eigen::Vector3d reference = *state.normal[c[0]] + *state.normal[c[1]] + *state.normal[c[2]];
      const double dot = n.dot(reference);
      const double length = reference.norm();
      if (n.norm() == 0.0 || length == 0.0) return 0.0;
      const double rho = 0.5 * dot / length / (face_area_[move.faces[f]] * scale_);
      if (dot < 0.0) return std::min(rho, -kTiny);
      return std::min(rho, 1.0 / rho);
    };
    // Cost of the given disc faces with ring slot j at option o for each (j, o); infinite when a
    // flat face is not positive. `state` is left as it was.
    auto cost_of = [&](DiscState& state, const std::vector<int>& faces,
                       std::initializer_list<std::pair<int, int>> slot_options) {
      RingCost cost;
      for (const auto& [j, o] : slot_options) {
        if (o == 0) continue;
        state.trial[j + 1] = places[o - 1];
        state.at[j + 1] = &place_images[o - 1].position;
        state.normal[j + 1] = &place_normal[o - 1];
        cost.slack += kMoveWeight * (state.trial[j + 1] - move.from[j + 1]).norm() / radius;
      }
      for (int f : faces) {
        if (!(disc_area2(move, state.trial, f) > kMinArea * disc_area2(move, move.rest, f)))
          cost.flips = kInvalid;
      }
      for (int f : faces) {
        if (cost.flips >= kInvalid) break;
        const double q = approximate_quality(state, f);
        if (q < 0.0) {
          ++cost.flips;
          cost.fold -= q;
        } else {
          cost.slack += std::max(0.0, kComfort - q);
        }
      }
      for (const auto& [j, o] : slot_options) reset(state, j + 1);
      return cost;
    };
    DiscState state = staying();
    std::vector<std::vector<int>> options(k);
    std::vector<std::vector<RingCost>> unary(k);
    std::vector<std::vector<int>> direction(k);  // per option: its image's direction bucket, -1 staying
    for (int j = 0; j < k; ++j) {
      const int last = blocked_[move.vertices[j + 1]] ? 1 : n_options;
      std::vector<std::pair<RingCost, int>> ranked;
      for (int o = 0; o < last; ++o) {
        const RingCost c = cost_of(state, single[j], {{j, o}});
        if (c.flips < kInvalid) ranked.emplace_back(c, o);
      }
      if (ranked.empty()) return false;
      // Staying is always an option (when valid); then, in every direction about the centre's
      // image, the places cheapest on the slot's own faces (the fan needs images all around).
      const auto by_cost = [](const auto& a, const auto& b) {
        return std::tie(a.first, a.second) < std::tie(b.first, b.second);
      };
      const auto rest = ranked.begin() + (ranked.front().second == 0 ? 1 : 0);
      std::sort(rest, ranked.end(), by_cost);
      std::vector<int> per_direction(settings_.ring_angles, 0);
      for (const auto& [c, o] : ranked) {
        int bucket = -1;  // staying
        if (o != 0) {
          const double turn = place_turns[o - 1] / (2.0 * std::numbers::pi) + 0.5;
          bucket = std::clamp(static_cast<int>(turn * settings_.ring_angles), 0, settings_.ring_angles - 1);
          if (per_direction[bucket]++ >= settings_.ring_options) continue;
        }
        options[j].push_back(o);
        unary[j].push_back(c);
        direction[j].push_back(bucket);
      }
    }
    // binary[j][a][b]: the faces of slots j and j+1 with option a of j and option b of j+1.
    std::vector<std::vector<std::vector<RingCost>>> binary(k);
    for (int j = 0; j < k; ++j) {
      const int next = (j + 1) % k;
      binary[j].assign(options[j].size(), std::vector<RingCost>(options[next].size()));
      tbb::parallel_for(0, static_cast<int>(options[j].size()), [&](int a) {
        DiscState row = staying();
        for (std::size_t b = 0; b < options[next].size(); ++b)
          binary[j][a][b] = cost_of(row, pair[j], {{j, options[j][a]}, {next, options[next][b]}});
      });
    }

    // Cheapest choice around the cycle: fix an option of the slot with the fewest (only the
    // cheapest in each direction: the exact enumeration would cost options^3 per slot), chain
    // through the other slots in order, close the cycle.
    int start = 0;
    for (int j = 1; j < k; ++j) {
      if (options[j].size() < options[start].size()) start = j;
    }
    std::vector<std::size_t> firsts;
    std::vector<bool> seen(settings_.ring_angles + 1, false);
    for (std::size_t a = 0; a < options[start].size(); ++a) {
      const int bucket = direction[start][a];
      if (seen[bucket + 1]) continue;
      seen[bucket + 1] = true;
      firsts.push_back(a);
    }
    auto slot = [&](int t) { return (start + t) % k; };
    // The chains from different first options are independent: they run in parallel, and the
    // cheapest is taken in the order of `firsts`, the earliest on a tie, as one loop over them would.
    struct Chain {
      RingCost cost{kInvalid, 0.0, 0.0};
      std::vector<int> choice;  // per slot, an index into its options
    };
    std::vector<Chain> chains(firsts.size());
    tbb::parallel_for(0, static_cast<int>(firsts.size()), [&](int f) {
      const std::size_t first = firsts[f];
      std::vector<std::vector<RingCost>> total(k);
      std::vector<std::vector<int>> back(k);
      total[0].assign(options[start].size(), RingCost{kInvalid, 0.0, 0.0});
      total[0][first] = unary[start][first];
      for (int t = 1; t < k; ++t) {
        const int j = slot(t);
        const int i = slot(t - 1);
        total[t].assign(options[j].size(), RingCost{kInvalid, 0.0, 0.0});
        back[t].assign(options[j].size(), -1);
        for (std::size_t a = 0; a < options[i].size(); ++a) {
          if (total[t - 1][a].flips >= kInvalid) continue;
          for (std::size_t b = 0; b < options[j].size(); ++b) {
            if (binary[i][a][b].flips >= kInvalid) continue;
            const RingCost c = total[t - 1][a] + binary[i][a][b] + unary[j][b];
            if (c < total[t][b]) {
              total[t][b] = c;
              back[t][b] = static_cast<int>(a);
            }
          }
        }
      }
      const int last = slot(k - 1);
      Chain& chain = chains[f];
      for (std::size_t b = 0; b < options[last].size(); ++b) {
        if (total[k - 1][b].flips >= kInvalid || binary[last][b][first].flips >= kInvalid) continue;
        const RingCost c = total[k - 1][b] + binary[last][b][first];
        if (!(c < chain.cost)) continue;
        chain.cost = c;
        chain.choice.assign(k, 0);
        int choice = static_cast<int>(b);
        for (int t = k - 1; t >= 0; --t) {
          chain.choice[slot(t)] = choice;
          if (t > 0) choice = back[t][choice];
        }
      }
    });
    RingCost best_total{kInvalid, 0.0, 0.0};
    std::vector<int> best_choice;  // per slot, an index into its options
    for (Chain& chain : chains) {
      if (!(chain.cost < best_total)) continue;
      best_total = chain.cost;
      best_choice = std::move(chain.choice);
    }
    if (best_total.flips >= kInvalid) return false;
    bool any = false;
    for (int j = 0; j < k; ++j) {
      const int o = options[j][best_choice[j]];
      move.to[j + 1] = o == 0 ? move.from[j + 1] : places[o - 1];
      any = any || o != 0;
    }
    if (!any) return false;

    // The move carries the ring vertices and any moved vertex inside the disc: the exact verdict.
    std::vector<int> affected;
    std::vector<int> candidates = moved_list_;
    for (int j = 1; j <= k; ++j) candidates.push_back(move.vertices[j]);
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (int u : candidates) {
      if (ring_moves_point(move, points_[u])) affected.push_back(u);
    }
    const std::vector<int> check = faces_around(affected);
    const Score before = score(check, Replacements{});
    std::vector<SurfacePoint> points(affected.size());
    std::vector<MappedPoint> images(affected.size());
    tbb::parallel_for(0, static_cast<int>(affected.size()), [&](int a) {
      points[a] = apply_ring(move, points_[affected[a]]);
      images[a] = gamma_(points[a]);
    });
    Replacements after_images;
    for (std::size_t a = 0; a < affected.size(); ++a) after_images.emplace_back(affected[a], &images[a]);
    const Score after = score(check, after_images);
    if (!improves(before, after)) return false;
    commit(std::move(move), affected, points, images, check);
    return true;
  }

  // A move is kept when it leaves fewer flipped faces among those it changes (a fold may move
  // to a face where another vertex can undo it), or (a step towards removing them with a later
  // move of a neighbour) as many, clearly less folded.
  bool improves(const Score& before, const Score& after) const {
    if (after.flipped != before.flipped) return after.flipped < before.flipped;
    return after.worst > before.worst + settings_.min_gain;
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
  std::vector<MappedPoint> images_;   // #V: Gamma(phi(x_i))
  std::vector<SurfacePoint> points_;  // #V: phi(x_i)
  std::vector<std::array<int, 3>> faces_;
  std::vector<double> face_area_;  // #F template face areas
  double scale_ = 1.0;             // target area / template area
  std::vector<bool> blocked_;      // #V: an anchor in the open star
  std::vector<bool> moved_;        // #V: phi(x_i) != x_i
  std::vector<int> moved_list_;    // the moved vertices, ascending
  int commits_ = 0;                // moves kept so far
  std::vector<int> changed_;       // #V: moves kept when phi(x_i) last changed
  std::vector<int> ring_failed_;   // #V: moves kept when a ring move about it last failed, or -1
  // #V: moves kept when a star move about it last failed (or -1), and the vertices it read.
  std::vector<std::pair<int, std::vector<int>>> star_failed_;
  std::vector<bool> flipped_;      // #F: remesh face flipped now
  TemplateWarp warp_;
};

}  // namespace

UntangleResult untangle_remesh(const Mesh& source, std::vector<MappedPoint> images, const SurfaceMap& gamma,
                               const Mesh& target, const std::vector<SurfacePoint>& fixed_points,
                               const UntangleSettings& settings) {
  Stopwatch watch;
  Untangler untangler(source, std::move(images), gamma, target, fixed_points, settings);
  UntangleResult result = untangler.run();
  result.seconds = watch.lap();
  return result;
}

RemeshQualityResult measure_remesh_quality(const std::vector<std::array<int, 3>>& faces,
                                           const std::vector<MappedPoint>& images, const Mesh& target) {
  std::vector<Eigen::Vector3d> positions;
  std::vector<SurfacePoint> locations;
  for (const MappedPoint& image : images) {
    positions.push_back(image.position);
    locations.push_back(image.on_input);
  }
  return measure_remesh_quality(faces, positions, locations, target);
}

}  // namespace xparam
