#include "map/extremity_anchors.h"

#include "core/closest_point.h"
#include "core/errors.h"
#include "layout/anchor_voronoi.h"
#include "map/tip_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <utility>
#include <variant>

namespace xparam {
namespace {

// Edge-path distances from `from` to every vertex within `radius` (others absent).
std::vector<std::pair<int, double>> ball(const Mesh& mesh, int from, double radius) {
  std::vector<std::pair<int, double>> reached;
  std::vector<double> distance;  // indexed through `slot`
  std::vector<int> slot(mesh.n_vertices(), -1);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  slot[from] = 0;
  distance.push_back(0.0);
  queue.push({0.0, from});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[slot[v]]) continue;
    reached.push_back({v, d});
    const VertexHandle vh = mesh.vertex_handle(v);
    for (VertexHandle u : mesh.vv_range(vh)) {
      const double through = d + (position(mesh, u) - position(mesh, vh)).norm();
      if (through > radius) continue;
      int& s = slot[u.idx()];
      if (s >= 0 && distance[s] <= through) continue;
      if (s < 0) {
        s = static_cast<int>(distance.size());
        distance.push_back(through);
      } else {
        distance[s] = through;
      }
      queue.push({through, u.idx()});
    }
  }
  return reached;
}

std::vector<VertexHandle> handles(const Mesh& mesh, const std::vector<int>& vertices) {
  std::vector<VertexHandle> result;
  for (int v : vertices) result.push_back(mesh.vertex_handle(v));
  return result;
}

// How much nearer its anchor than on the template a first map must put a tip's image for the
// tip to be matched through the anchor's cell (match_extremities_by_cell).
constexpr double kSqueezed = 0.5;

// How long a protrusion must be, in tip reaches from its anchor, for a blob without a tip on the
// other mesh to stand in for its tip.
constexpr double kBlobTipReaches = 3.0;

// A cell's next tip at least this share of the farthest tip's distance from the landmark makes a
// match by cell ambiguous (ExtremityAnchor::rival_target). The evaluation's hands: a right match's
// next finger at 0.96-0.99 of its distance, SHREC'19 18's target index fingertip 1/0.977 of its
// middle one's (the template's middle is the farthest).
constexpr double kAmbiguousCell = 0.95;

// Per anchor of one mesh: the unmatched tip in its Voronoi cell farthest from it, the next farthest
// and the cell's farthest end (Extremities::ends), -1 where there is none, and their distances from
// the anchor as fractions of sqrt(area).
struct FarthestInCells {
  std::vector<int> tip;
  std::vector<double> tip_distance;
  std::vector<int> next_tip;
  std::vector<double> next_tip_distance;
  std::vector<int> end;
  std::vector<double> end_distance;
};

// Landmarks nearer each other than this fraction of sqrt(area) on both meshes hold one limb between
// them, and their cells are searched as one. SHREC'19 15's right wrist and ulnar styloid, 0.03
// sqrt(area) apart, split the hand between their cells: the middle fingertip in the wrist's on the
// template and in the styloid's on the target, and the wrist's cell paired the template's middle
// fingertip with the target's index one, the farthest it held.
constexpr double kOneLimbLandmarks = 0.05;

}  // namespace

std::vector<int> limb_groups(const TipsAndAnchors& source, const TipsAndAnchors& target) {
  const std::size_t n = source.anchors.size();
  std::vector<int> group(n);
  std::iota(group.begin(), group.end(), 0);
  const auto near = [&](const TipsAndAnchors& side, std::size_t a, std::size_t b, double scale) {
    return (position(side.mesh, side.mesh.vertex_handle(side.anchors[a])) -
            position(side.mesh, side.mesh.vertex_handle(side.anchors[b])))
               .norm() < kOneLimbLandmarks * scale;
  };
  const double source_scale = std::sqrt(surface_area(source.mesh));
  const double target_scale = std::sqrt(surface_area(target.mesh));
  // Union-find over the pairs near on both meshes, each group's root its lowest-numbered anchor.
  const auto root = [&](int k) {
    while (group[k] != k) k = group[k];
    return k;
  };
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = a + 1; b < n; ++b) {
      if (!near(source, a, b, source_scale) || !near(target, a, b, target_scale)) continue;
      const int ra = root(static_cast<int>(a));
      const int rb = root(static_cast<int>(b));
      group[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  for (std::size_t k = 0; k < n; ++k) group[k] = root(static_cast<int>(k));
  return group;
}

namespace {

FarthestInCells farthest_in_cells(const TipsAndAnchors& side, const std::vector<int>& matched_tips,
                                  double scale, const std::vector<int>& limb) {
  const AnchorVoronoi& cells = side.found.cells;
  const std::size_t n = side.anchors.size();
  FarthestInCells farthest{std::vector<int>(n, -1), std::vector<double>(n, 0.0),
                           std::vector<int>(n, -1), std::vector<double>(n, 0.0),
                           std::vector<int>(n, -1), std::vector<double>(n, 0.0)};
  // In vertex order: ties go to the lower index.
  for (int v : side.found.tips) {
    if (std::find(matched_tips.begin(), matched_tips.end(), v) != matched_tips.end()) continue;
    const int k = limb[cells.cell[v]];
    const double d = cells.distance[v] / scale;
    if (farthest.tip[k] < 0 || d > farthest.tip_distance[k]) {
      farthest.next_tip[k] = farthest.tip[k];
      farthest.next_tip_distance[k] = farthest.tip_distance[k];
      farthest.tip[k] = v;
      farthest.tip_distance[k] = d;
    } else if (farthest.next_tip[k] < 0 || d > farthest.next_tip_distance[k]) {
      farthest.next_tip[k] = v;
      farthest.next_tip_distance[k] = d;
    }
  }
  for (int v : side.found.ends) {
    const int k = limb[cells.cell[v]];
    const double d = cells.distance[v] / scale;
    if (farthest.end[k] < 0 || d > farthest.end_distance[k]) {
      farthest.end[k] = v;
      farthest.end_distance[k] = d;
    }
  }
  return farthest;
}

// Whether `map` squeezes template vertex s towards anchor k: its image lies nearer the anchor,
// relative to the target's size (target_scale: sqrt(area)), than kSqueezed times the vertex itself
// does on the template (source_scale).
bool squeezed_towards(const TipsAndAnchors& source, const TipsAndAnchors& target, const FirstMap& map, int s,
                      std::size_t k, double source_scale, double target_scale) {
  const double from_anchor = (position(source.mesh, source.mesh.vertex_handle(s)) -
                              position(source.mesh, source.mesh.vertex_handle(source.anchors[k])))
                                 .norm() /
                             source_scale;
  const double image_from_anchor =
      (map.images[s] - position(target.mesh, target.mesh.vertex_handle(target.anchors[k]))).norm() /
      target_scale;
  return image_from_anchor < kSqueezed * from_anchor;
}

// How near a pair's tip its neighbour must lie, on each mesh, as a fraction of sqrt(area), for the
// pair to be tried one over (one_over): a hand's next finger. The template's neighbouring fingertips
// lie 0.024-0.036 apart, its index fingertip 0.073 from the thumb's.
constexpr double kOneOverReach = 0.05;

// Tips matched by their distances to the references near them (match_extremities_by_distances):
// the references lie within kDescriptorRadius sqrt(area) of one of the two tips (a hand's span);
// a pair is matched below kMaxDescriptorMismatch, and under kDescriptorMargin times the mismatch
// of either tip's next best. The fingers and toes of the evaluation's human pairs match at
// 0.02-0.06, SHREC'19 21 [73 CAESAR]'s left little fingertip, pressed against the ring finger, at
// 0.101 (left out at 0.1, that finger was squeezed into a disc); a FAUST toe matched at 0.11 folded
// the foot.
constexpr double kDescriptorRadius = 0.2;
constexpr double kMaxDescriptorMismatch = 0.105;
constexpr double kDescriptorMargin = 0.6;

// Edge-path distances (fractions of sqrt(area)) from `tip` to each of `references`, infinite
// beyond 1.5 kDescriptorRadius, where neither tip of a pair can have the reference near.
std::vector<double> reference_distances(const Mesh& mesh, int tip, const std::vector<int>& references, double scale) {
  std::vector<double> distances(references.size(), std::numeric_limits<double>::infinity());
  std::vector<std::pair<int, double>> reached = ball(mesh, tip, 1.5 * kDescriptorRadius * scale);
  std::sort(reached.begin(), reached.end());
  for (std::size_t r = 0; r < references.size(); ++r) {
    const auto at = std::lower_bound(reached.begin(), reached.end(), std::pair<int, double>{references[r], -1.0});
    if (at != reached.end() && at->first == references[r]) distances[r] = at->second / scale;
  }
  return distances;
}

// The mismatch of two tips' reference distances: summed differences over the mean summed
// distance, over the references within kDescriptorRadius of either tip; infinite with fewer than
// two such references, with none among the matched tips (index >= first_matched_tip), or with one
// out of the other tip's reach.
double descriptor_mismatch(const std::vector<double>& a, const std::vector<double>& b, std::size_t first_matched_tip) {
  double difference = 0.0;
  double sum = 0.0;
  int references = 0;
  bool matched_tip = false;
  for (std::size_t r = 0; r < a.size(); ++r) {
    if (!(std::min(a[r], b[r]) <= kDescriptorRadius)) continue;
    if (!std::isfinite(a[r] + b[r])) return std::numeric_limits<double>::infinity();
    difference += std::abs(a[r] - b[r]);
    sum += 0.5 * (a[r] + b[r]);
    ++references;
    matched_tip = matched_tip || r >= first_matched_tip;
  }
  if (references < 2 || !matched_tip || !(sum > 0.0)) return std::numeric_limits<double>::infinity();
  return difference / sum;
}

// The radius, a fraction of sqrt(area), over which an anchor's surface normal is averaged, so one
// scan's facet does not turn it.
constexpr double kAnchorNormalRadius = 0.01;

// Area-weighted mean normal of the faces round the vertices within `radius` of `vertex`.
Eigen::Vector3d normal_near(const Mesh& mesh, int vertex, double radius) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::vector<FaceHandle> counted;
  for (const auto& [v, d] : ball(mesh, vertex, radius)) {
    for (FaceHandle f : mesh.vf_range(mesh.vertex_handle(v))) counted.push_back(f);
  }
  std::sort(counted.begin(), counted.end());
  counted.erase(std::unique(counted.begin(), counted.end()), counted.end());
  for (FaceHandle f : counted) {
    auto corner = mesh.cfv_begin(f);
    const Eigen::Vector3d a = position(mesh, *corner++);
    const Eigen::Vector3d b = position(mesh, *corner++);
    const Eigen::Vector3d c = position(mesh, *corner);
    sum += (b - a).cross(c - a);
  }
  return sum.normalized();
}

// One mesh's side of match_extremities_by_distances.
struct DistanceSide {
  const Mesh& mesh;
  double scale = 1.0;           // sqrt(area)
  std::vector<int> references;  // the anchors' vertices, then the matched tips'
  std::vector<int> tips;        // the tips not matched yet
  std::vector<Eigen::Vector3d> anchor_normals;  // of each anchor (normal_near), in references' order

  // The sine of `tip`'s angle off the plane through anchor reference `a`, its normal and
  // reference `b`: det[b - a, tip - a, n_a] / (|b - a| |tip - a|); which side of the line from a
  // to b the tip lies on, seen from outside the surface at a.
  double side_of(std::size_t a, std::size_t b, int tip) const {
    const Eigen::Vector3d at = position(mesh, mesh.vertex_handle(references[a]));
    const Eigen::Vector3d along = position(mesh, mesh.vertex_handle(references[b])) - at;
    const Eigen::Vector3d to_tip = position(mesh, mesh.vertex_handle(tip)) - at;
    const double lengths = along.norm() * to_tip.norm();
    return lengths > 0.0 ? along.cross(to_tip).dot(anchor_normals[a]) / lengths : 0.0;
  }
};

// A tip this far (a sine) to one side of a plane through an anchor (DistanceSide::side_of) lies
// clearly on that side. The evaluation's hands, seen from the wrist towards the middle fingertip:
// the template's index fingertip at -0.2, ring at +0.16; the targets' at -0.24 to -0.08 and +0.05
// to +0.2, but for fingers fused into a mitten (within 0.05 of 0).
constexpr double kClearSide = 0.1;

// Whether template tip s and target tip t, their descriptors resting on two references near both
// (descriptor_mismatch), one an anchor, lie clearly on opposite sides of the plane through them
// and the anchor's normal: each other's mirror image. Two references fix a tip by its distances
// only up to that mirror (an index and a ring fingertip lie as far from the wrist and the middle
// fingertip), so distances alone paired them (SHREC'19 20 [29]). Three or more fix it; there the
// sides are not read (a knuckle's normal turns with the finger).
bool mirrored(const DistanceSide& source, int s, const std::vector<double>& s_distances,
              const DistanceSide& target, int t, const std::vector<double>& t_distances,
              std::size_t first_matched_tip) {
  std::vector<std::size_t> near;
  for (std::size_t r = 0; r < s_distances.size(); ++r)
    if (std::min(s_distances[r], t_distances[r]) <= kDescriptorRadius) near.push_back(r);
  if (near.size() != 2) return false;
  for (int k = 0; k < 2; ++k) {
    const std::size_t a = near[k];
    const std::size_t b = near[1 - k];
    if (a >= first_matched_tip) continue;
    const double on_source = source.side_of(a, b, s);
    const double on_target = target.side_of(a, b, t);
    if (on_source * on_target < 0.0 && std::min(std::abs(on_source), std::abs(on_target)) > kClearSide)
      return true;
  }
  return false;
}

// One round of match_extremities_by_distances: the (template, target) tip pairs whose mismatch is
// below kMaxDescriptorMismatch and under kDescriptorMargin times every other choice of either tip,
// in template tip order.
std::vector<std::pair<int, int>> clear_distance_matches(const DistanceSide& source, const DistanceSide& target,
                                                        std::size_t first_matched_tip) {
  const std::size_t n_source = source.tips.size();
  const std::size_t n_target = target.tips.size();
  std::vector<std::vector<double>> target_distances;
  for (int t : target.tips)
    target_distances.push_back(reference_distances(target.mesh, t, target.references, target.scale));
  std::vector<double> cost(n_source * n_target);
  for (std::size_t s = 0; s < n_source; ++s) {
    const std::vector<double> distances = reference_distances(source.mesh, source.tips[s], source.references, source.scale);
    for (std::size_t t = 0; t < n_target; ++t) {
      const bool mirror = mirrored(source, source.tips[s], distances, target, target.tips[t],
                                   target_distances[t], first_matched_tip);
      cost[s * n_target + t] = mirror
                                   ? std::numeric_limits<double>::infinity()
                                   : descriptor_mismatch(distances, target_distances[t], first_matched_tip);
    }
  }
  const auto clear_best = [](std::size_t n, std::size_t best, const auto& cost_of) {
    for (std::size_t k = 0; k < n; ++k) {
      if (k != best && !(cost_of(best) < kDescriptorMargin * cost_of(k))) return false;
    }
    return cost_of(best) < kMaxDescriptorMismatch;
  };
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t s = 0; s < n_source; ++s) {
    const auto of_target = [&](std::size_t t) { return cost[s * n_target + t]; };
    std::size_t t = 0;
    for (std::size_t k = 1; k < n_target; ++k)
      if (of_target(k) < of_target(t)) t = k;
    const auto of_source = [&](std::size_t k) { return cost[k * n_target + t]; };
    if (clear_best(n_target, t, of_target) && clear_best(n_source, s, of_source))
      pairs.push_back({source.tips[s], target.tips[t]});
  }
  return pairs;
}

}  // namespace

TipDistances tip_distances(const Mesh& mesh, int root, const std::vector<int>& anchors) {
  return {anchor_cells(mesh, {mesh.vertex_handle(root)}).distance,
          anchor_cells(mesh, handles(mesh, anchors))};
}

Extremities extremities(const Mesh& mesh, const TipDistances& distances, double reach) {
  const std::vector<double>& from_root = distances.from_root;
  Extremities found;
  found.cells = distances.cells;
  const std::vector<double>& from_anchors = found.cells.distance;
  for (VertexHandle v : mesh.vertices()) {
    const double here = from_root[v.idx()];
    if (from_anchors[v.idx()] <= reach) continue;
    bool highest = true;  // in the one-ring first: most vertices fail there
    for (VertexHandle u : mesh.vv_range(v)) highest = highest && from_root[u.idx()] <= here;
    if (!highest) continue;
    double rim_highest = -std::numeric_limits<double>::infinity();
    for (const auto& [u, d] : ball(mesh, v.idx(), reach)) {
      // Ties go to the lower index, so a flat top gives one tip.
      if (from_root[u] > here || (from_root[u] == here && u < v.idx())) {
        highest = false;
        break;
      }
      if (d >= 0.8 * reach) rim_highest = std::max(rim_highest, from_root[u]);
    }
    if (!highest) continue;
    found.ends.push_back(v.idx());
    if (rim_highest <= here - 0.5 * reach) found.tips.push_back(v.idx());
  }
  return found;
}

std::vector<ExtremityAnchor> match_extremities(const Mesh& source, const std::vector<int>& source_tips,
                                               const Mesh& target, const std::vector<int>& target_tips,
                                               const FirstMap& map, const std::vector<std::string>& taken,
                                               double max_mismatch) {
  std::vector<ExtremityAnchor> matched;
  if (source_tips.empty() || target_tips.empty()) return matched;
  const TipMismatch mismatch(source, target, map);
  std::vector<Eigen::Vector3d> target_tip_preimage;
  for (int t : target_tips) target_tip_preimage.push_back(mismatch.preimage(t));
  const int n_source = static_cast<int>(source_tips.size());
  const int n_target = static_cast<int>(target_tips.size());
  std::vector<int> best_target(n_source, -1);
  std::vector<int> best_source(n_target, -1);
  std::vector<double> cost(static_cast<std::size_t>(n_source) * n_target);
  for (int s = 0; s < n_source; ++s) {
    for (int t = 0; t < n_target; ++t) {
      cost[s * n_target + t] = mismatch(source_tips[s], target_tips[t], target_tip_preimage[t]);
      if (best_target[s] < 0 || cost[s * n_target + t] < cost[s * n_target + best_target[s]]) best_target[s] = t;
      if (best_source[t] < 0 || cost[s * n_target + t] < cost[best_source[t] * n_target + t]) best_source[t] = s;
    }
  }
  std::vector<std::string> names = taken;
  for (int s = 0; s < n_source; ++s) {
    const int t = best_target[s];
    if (best_source[t] != s || !(cost[s * n_target + t] < max_mismatch)) continue;
    matched.push_back(tip_anchor(source_tips[s], target_tips[t],
                                 mismatch.misses(source_tips[s], target_tips[t], target_tip_preimage[t]),
                                 matched.size() + 1, names));
  }
  return matched;
}

std::vector<ExtremityAnchor> match_extremities_by_cell(const TipsAndAnchors& source, const TipsAndAnchors& target,
                                                       const FirstMap& map,
                                                       const std::vector<ExtremityAnchor>& matched,
                                                       const std::vector<std::string>& taken) {
  std::vector<ExtremityAnchor> by_cell;
  if (source.found.tips.empty() && target.found.tips.empty()) return by_cell;  // a blob stands in only for a tip
  std::vector<int> matched_source, matched_target;
  std::vector<std::string> names = taken;
  for (const ExtremityAnchor& tip : matched) {
    matched_source.push_back(std::get<AnchorVertex>(tip.specs[0].location).index);
    matched_target.push_back(std::get<AnchorVertex>(tip.specs[1].location).index);
    names.push_back(tip.specs[0].name);
  }
  const double source_scale = std::sqrt(surface_area(source.mesh));
  const double target_scale = std::sqrt(surface_area(target.mesh));
  const std::vector<int> limb = limb_groups(source, target);
  const FarthestInCells on_source = farthest_in_cells(source, matched_source, source_scale, limb);
  const FarthestInCells on_target = farthest_in_cells(target, matched_target, target_scale, limb);
  const TipMismatch mismatch(source.mesh, target.mesh, map);
  // Elsewhere than where the first map squeezes, it has put the protrusion where it belongs and
  // its through-map matches (or none) stand.
  const auto squeezed = [&](int s, std::size_t k) {
    return squeezed_towards(source, target, map, s, k, source_scale, target_scale);
  };
  // Whether a matched tip lies within `distance` (a fraction of sqrt(area)) of anchor k: the limb
  // there already has a helper (the hand may span the cells of two wrist landmarks), and the
  // farthest tips of a half-matched hand need not be the same finger on both meshes.
  const auto near_matched = [](const TipsAndAnchors& side, const std::vector<int>& matched_tips, std::size_t k,
                               double distance, double scale) {
    const Eigen::Vector3d anchor = position(side.mesh, side.mesh.vertex_handle(side.anchors[k]));
    return std::any_of(matched_tips.begin(), matched_tips.end(), [&](int v) {
      return (position(side.mesh, side.mesh.vertex_handle(v)) - anchor).norm() <= distance * scale;
    });
  };
  for (std::size_t k = 0; k < source.anchors.size(); ++k) {
    if (limb[k] != static_cast<int>(k)) continue;  // searched with its group's first anchor
    if (near_matched(source, matched_source, k, std::max(on_source.tip_distance[k], on_source.end_distance[k]),
                     source_scale) ||
        near_matched(target, matched_target, k, std::max(on_target.tip_distance[k], on_target.end_distance[k]),
                     target_scale))
      continue;
    if (on_source.tip[k] < 0 && on_target.tip[k] < 0) continue;
    // A tip on one mesh only: the other's protrusion is a blob (a fist), whose farthest point
    // from the anchor stands for the tip when the tip ends a long protrusion.
    const auto stand_in = [&](const FarthestInCells& with, const FarthestInCells& without, double reach) {
      return with.tip[k] >= 0 && with.tip_distance[k] >= kBlobTipReaches * reach ? without.end[k] : -1;
    };
    const int s = on_source.tip[k] >= 0 ? on_source.tip[k] : stand_in(on_target, on_source, target.reach);
    const int t = on_target.tip[k] >= 0 ? on_target.tip[k] : stand_in(on_source, on_target, source.reach);
    if (s < 0 || t < 0) continue;
    const double ratio = (on_source.tip[k] >= 0 ? on_source.tip_distance[k] : on_source.end_distance[k]) /
                         (on_target.tip[k] >= 0 ? on_target.tip_distance[k] : on_target.end_distance[k]);
    if (!(ratio >= 0.5 && ratio <= 2.0) || !squeezed(s, k)) continue;
    by_cell.push_back(tip_anchor(s, t, mismatch.misses(s, t, mismatch.preimage(t)),
                                 matched.size() + by_cell.size() + 1, names));
    by_cell.back().matched_by = TipMatching::by_cell;
    if (t == on_target.tip[k] && on_target.next_tip[k] >= 0 &&
        on_target.next_tip_distance[k] >= kAmbiguousCell * on_target.tip_distance[k])
      by_cell.back().rival_target = on_target.next_tip[k];
  }
  return by_cell;
}

std::vector<ExtremityAnchor> outside_squeezed_cells(const TipsAndAnchors& source,
                                                    const TipsAndAnchors& target, const FirstMap& map,
                                                    std::vector<ExtremityAnchor> through_map) {
  const double source_scale = std::sqrt(surface_area(source.mesh));
  const double target_scale = std::sqrt(surface_area(target.mesh));
  const std::vector<int> limb = limb_groups(source, target);
  const FarthestInCells farthest = farthest_in_cells(source, {}, source_scale, limb);
  std::erase_if(through_map, [&](const ExtremityAnchor& tip) {
    const int k = limb[source.found.cells.cell[std::get<AnchorVertex>(tip.specs[0].location).index]];
    const int cell_tip = farthest.tip[k];
    return cell_tip >= 0 && squeezed_towards(source, target, map, cell_tip, k, source_scale, target_scale);
  });
  return through_map;
}

ExtremityAnchor matched_with_rival(const ExtremityAnchor& tip, const Mesh& source, const Mesh& target,
                                   const FirstMap& map) {
  XP_ASSERT(tip.rival_target >= 0);
  const TipMismatch mismatch(source, target, map);
  const int s = std::get<AnchorVertex>(tip.specs[0].location).index;
  ExtremityAnchor rival = tip;
  rival.specs[1].location = AnchorVertex{tip.rival_target};
  rival.miss = mismatch.misses(s, tip.rival_target, mismatch.preimage(tip.rival_target));
  rival.rival_target = -1;
  return rival;
}

std::optional<std::array<ExtremityAnchor, 2>> one_over(const TipsAndAnchors& source,
                                                       const TipsAndAnchors& target, const FirstMap& map,
                                                       const ExtremityAnchor& pair,
                                                       const std::vector<ExtremityAnchor>& matched,
                                                       const std::vector<std::string>& taken) {
  const std::array<const TipsAndAnchors*, 2> sides = {&source, &target};
  const std::array<int, 2> tip = {std::get<AnchorVertex>(pair.specs[0].location).index,
                                  std::get<AnchorVertex>(pair.specs[1].location).index};
  const auto at = [&](int side, int v) {
    return position(sides[side]->mesh, sides[side]->mesh.vertex_handle(v));
  };
  const auto apart = [&](int side, int a, int b) { return (at(side, a) - at(side, b)).norm(); };
  // On each mesh the unmatched found tip nearest the pair's, when it lies near.
  std::array<int, 2> beside{-1, -1};
  for (int side = 0; side < 2; ++side) {
    const auto is_matched = [&](int v) {
      return std::any_of(matched.begin(), matched.end(), [&](const ExtremityAnchor& other) {
        return std::get<AnchorVertex>(other.specs[side].location).index == v;
      });
    };
    for (int v : sides[side]->found.tips) {
      if (v != tip[side] && !is_matched(v) &&
          (beside[side] < 0 || apart(side, v, tip[side]) < apart(side, beside[side], tip[side])))
        beside[side] = v;
    }
    if (beside[side] < 0 ||
        apart(side, beside[side], tip[side]) > kOneOverReach * std::sqrt(surface_area(sides[side]->mesh)))
      return std::nullopt;
  }
  // The reference nearest the template tip, an anchor or a matched tip, and its partner.
  std::vector<std::array<int, 2>> references;
  for (std::size_t k = 0; k < source.anchors.size(); ++k)
    references.push_back({source.anchors[k], target.anchors[k]});
  for (const ExtremityAnchor& other : matched)
    references.push_back({std::get<AnchorVertex>(other.specs[0].location).index,
                          std::get<AnchorVertex>(other.specs[1].location).index});
  std::erase_if(references, [&](const std::array<int, 2>& reference) { return reference[0] == tip[0]; });
  if (references.empty()) return std::nullopt;
  const std::array<int, 2> reference = *std::min_element(
      references.begin(), references.end(),
      [&](const auto& a, const auto& b) { return apart(0, a[0], tip[0]) < apart(0, b[0], tip[0]); });
  const auto beyond = [&](int side) {
    return apart(side, beside[side], reference[side]) > apart(side, tip[side], reference[side]);
  };
  if (beyond(0) == beyond(1)) return std::nullopt;
  const TipMismatch mismatch(source.mesh, target.mesh, map);
  std::array<ExtremityAnchor, 2> over{pair, pair};
  over[0].specs[1].location = AnchorVertex{beside[1]};
  over[0].miss = mismatch.misses(tip[0], beside[1], mismatch.preimage(beside[1]));
  std::vector<std::string> names = names_taken(taken, matched);
  over[1] = tip_anchor(beside[0], tip[1], mismatch.misses(beside[0], tip[1], mismatch.preimage(tip[1])),
                       matched.size() + 1, names);
  for (ExtremityAnchor& shifted : over) {
    shifted.matched_by = TipMatching::one_over;
    shifted.rival_target = -1;
  }
  return over;
}

std::vector<ExtremityAnchor> match_extremities_by_distances(const TipsAndAnchors& source, const TipsAndAnchors& target,
                                                            const FirstMap& map,
                                                            const std::vector<ExtremityAnchor>& matched,
                                                            const std::vector<std::string>& taken) {
  std::vector<ExtremityAnchor> by_distances;
  if (matched.empty()) return by_distances;
  DistanceSide on_source{source.mesh, std::sqrt(surface_area(source.mesh)), source.anchors, {}, {}};
  DistanceSide on_target{target.mesh, std::sqrt(surface_area(target.mesh)), target.anchors, {}, {}};
  for (DistanceSide* side : {&on_source, &on_target}) {
    for (int anchor : side->references)
      side->anchor_normals.push_back(normal_near(side->mesh, anchor, kAnchorNormalRadius * side->scale));
  }
  std::vector<std::string> names = taken;
  for (const ExtremityAnchor& tip : matched) {
    on_source.references.push_back(std::get<AnchorVertex>(tip.specs[0].location).index);
    on_target.references.push_back(std::get<AnchorVertex>(tip.specs[1].location).index);
    names.push_back(tip.specs[0].name);
  }
  const auto unmatched = [](const std::vector<int>& tips, const std::vector<int>& references) {
    std::vector<int> left;
    for (int v : tips)
      if (std::find(references.begin(), references.end(), v) == references.end()) left.push_back(v);
    return left;
  };
  on_source.tips = unmatched(source.found.tips, on_source.references);
  on_target.tips = unmatched(target.found.tips, on_target.references);
  const TipMismatch mismatch(source.mesh, target.mesh, map);
  while (!on_source.tips.empty() && !on_target.tips.empty()) {
    const std::vector<std::pair<int, int>> pairs = clear_distance_matches(on_source, on_target, source.anchors.size());
    if (pairs.empty()) break;
    for (const auto& [s, t] : pairs) {
      by_distances.push_back(tip_anchor(s, t, mismatch.misses(s, t, mismatch.preimage(t)),
                                        matched.size() + by_distances.size() + 1, names));
      by_distances.back().matched_by = TipMatching::by_distances;
      on_source.references.push_back(s);
      on_target.references.push_back(t);
    }
    on_source.tips = unmatched(on_source.tips, on_source.references);
    on_target.tips = unmatched(on_target.tips, on_target.references);
  }
  return by_distances;
}

}  // namespace xparam
