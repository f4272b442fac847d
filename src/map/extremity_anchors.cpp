#include "map/extremity_anchors.h"

#include "core/closest_point.h"
#include "layout/anchor_voronoi.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

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

}  // namespace

std::vector<int> protrusion_tips(const Mesh& mesh, int root, const std::vector<int>& anchors, double reach) {
  const std::vector<double> from_root = anchor_voronoi(mesh, {mesh.vertex_handle(root)}).distance;
  const std::vector<double> from_anchors = anchor_voronoi(mesh, handles(mesh, anchors)).distance;
  std::vector<int> tips;
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
    if (highest && rim_highest <= here - 0.5 * reach) tips.push_back(v.idx());
  }
  return tips;
}

std::vector<ExtremityAnchor> match_extremities(const Mesh& source, const std::vector<int>& source_tips,
                                               const Mesh& target, const std::vector<int>& target_tips,
                                               const FirstMap& map, const std::vector<std::string>& taken,
                                               double max_mismatch) {
  std::vector<ExtremityAnchor> matched;
  if (source_tips.empty() || target_tips.empty()) return matched;
  const double source_scale = std::sqrt(surface_area(source));
  const double target_scale = std::sqrt(surface_area(target));
  // Each target tip taken back onto the template: its nearest remesh point, at the same
  // barycentrics of the template face.
  const ClosestPointIndex remesh(map.images, map.faces);
  std::vector<Eigen::Vector3d> target_tip_preimage;
  for (int t : target_tips) {
    const ClosestPoint nearest = remesh.closest(position(target, target.vertex_handle(t)));
    const auto& face = map.faces[nearest.location.face];
    Eigen::Vector3d back = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c) back += nearest.location.bary[c] * position(source, source.vertex_handle(face[c]));
    target_tip_preimage.push_back(back);
  }
  const auto mismatch = [&](int s, int t) {
    const double on_target =
        (map.images[source_tips[s]] - position(target, target.vertex_handle(target_tips[t]))).norm() / target_scale;
    const double on_source =
        (position(source, source.vertex_handle(source_tips[s])) - target_tip_preimage[t]).norm() / source_scale;
    return on_target + on_source;
  };
  const int n_source = static_cast<int>(source_tips.size());
  const int n_target = static_cast<int>(target_tips.size());
  std::vector<int> best_target(n_source, -1);
  std::vector<int> best_source(n_target, -1);
  std::vector<double> cost(static_cast<std::size_t>(n_source) * n_target);
  for (int s = 0; s < n_source; ++s) {
    for (int t = 0; t < n_target; ++t) {
      cost[s * n_target + t] = mismatch(s, t);
      if (best_target[s] < 0 || cost[s * n_target + t] < cost[s * n_target + best_target[s]]) best_target[s] = t;
      if (best_source[t] < 0 || cost[s * n_target + t] < cost[best_source[t] * n_target + t]) best_source[t] = s;
    }
  }
  std::vector<std::string> names = taken;
  for (int s = 0; s < n_source; ++s) {
    const int t = best_target[s];
    if (best_source[t] != s || !(cost[s * n_target + t] < max_mismatch)) continue;
    std::string name = "tip " + std::to_string(matched.size() + 1);
    while (std::find(names.begin(), names.end(), name) != names.end()) name += "'";
    names.push_back(name);
    ExtremityAnchor anchor;
    anchor.specs[0] = {name, AnchorVertex{source_tips[s]}, "", 0};
    anchor.specs[1] = {name, AnchorVertex{target_tips[t]}, "", 0};
    anchor.mismatch = cost[s * n_target + t];
    matched.push_back(std::move(anchor));
  }
  return matched;
}

}  // namespace xparam
