#include "map/tip_anchors.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "domain/patch_extraction.h"
#include "domain/patch_merging.h"
#include "map/map_optimization.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <optional>
#include <queue>
#include <utility>

namespace xparam {
namespace {

constexpr double kFar = std::numeric_limits<double>::infinity();

// The widest corner at `anchor` on `side`: its patch and its index in the patch's walk.
std::pair<int, int> widest_corner(const Layout& layout, const CornerAngles& angles, int side, int anchor) {
  std::pair<int, int> widest = {-1, -1};
  double widest_angle = -1.0;
  for (std::size_t p = 0; p < layout.patches.size(); ++p) {
    const std::vector<int>& walk = layout.patches[p];
    for (std::size_t i = 0; i < walk.size(); ++i) {
      if (layout_from(layout, walk[i]) == anchor && angles[side][p][i] > widest_angle) {
        widest_angle = angles[side][p][i];
        widest = {static_cast<int>(p), static_cast<int>(i)};
      }
    }
  }
  XP_ASSERT_MSG(widest.first >= 0, "anchor " << anchor << " has no corner");
  return widest;
}

// Edge-path distances from `sources` over the edges of patch `patch`'s faces, up to `reach`
// (kFar beyond).
std::vector<double> distances_in_patch(const Mesh& mesh, int patch, const std::vector<VertexHandle>& sources,
                                       double reach) {
  std::vector<double> distance(mesh.n_vertices(), kFar);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (const VertexHandle v : sources) {
    distance[v.idx()] = 0.0;
    queue.push({0.0, v.idx()});
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    for (const HalfedgeHandle h : mesh.voh_range(mesh.vertex_handle(v))) {
      const FaceHandle left = mesh.face_handle(h);
      const FaceHandle right = mesh.opposite_face_handle(h);
      if (patch_of(mesh, left) != patch && patch_of(mesh, right) != patch) continue;
      const VertexHandle w = mesh.to_vertex_handle(h);
      const double through = d + (position(mesh, w) - position(mesh, mesh.vertex_handle(v))).norm();
      if (through <= reach && through < distance[w.idx()]) {
        distance[w.idx()] = through;
        queue.push({through, w.idx()});
      }
    }
  }
  return distance;
}

// Whether an anchor at `point` on `input` would hold a vertex of `held`.
bool holds_any(const Mesh& input, const SurfacePoint& point, const std::vector<int>& held) {
  const std::vector<int> by_point = held_vertices(input, point);
  return std::any_of(by_point.begin(), by_point.end(),
                     [&](int v) { return std::find(held.begin(), held.end(), v) != held.end(); });
}

// The helper of `anchor` on `side`, on that side's input mesh, holding no vertex of `held`;
// nothing when the widest corner holds no such vertex off its curves within reach.
std::optional<SurfacePoint> helper_point(const Layout& layout, const CornerAngles& angles, const Mesh& input,
                                         int side, int anchor, double reach_fraction,
                                         const std::vector<int>& held) {
  const LayoutSide& s = layout.sides[side];
  const Mesh& mesh = s.mesh;
  const auto [patch, corner] = widest_corner(layout, angles, side, anchor);
  const std::vector<int>& walk = layout.patches[patch];
  const int leaving = walk[corner];
  const int arriving = walk[(corner + walk.size() - 1) % walk.size()];

  double shortest = kFar;
  for (std::size_t e = 0; e < layout.edges.size(); ++e) {
    const auto& ends = layout.edges[e].anchors;
    if (ends[0] == anchor || ends[1] == anchor)
      shortest = std::min(shortest, chain_length(layout, side, static_cast<int>(e)));
  }
  const double reach = reach_fraction * shortest;
  const std::vector<double> from_anchor = distances_in_patch(mesh, patch, {s.anchor_vertices[anchor]}, reach);
  const std::vector<double> from_leaving =
      distances_in_patch(mesh, patch, s.chains[layout_edge_of(leaving)], reach);
  const std::vector<double> from_arriving =
      distances_in_patch(mesh, patch, s.chains[layout_edge_of(arriving)], reach);
  std::vector<bool> on_boundary(mesh.n_vertices(), false);
  for (const int h : walk) {
    for (const VertexHandle v : s.chains[layout_edge_of(h)]) on_boundary[v.idx()] = true;
  }

  // Farthest from both curves of the corner; ties go to the smaller vertex index.
  std::vector<std::pair<double, int>> candidates;  // (-clearance, vertex)
  for (const VertexHandle v : mesh.vertices()) {
    if (on_boundary[v.idx()] || from_anchor[v.idx()] == kFar) continue;
    const double clearance = std::min(from_leaving[v.idx()], from_arriving[v.idx()]);
    if (clearance > 0.0) candidates.emplace_back(-clearance, v.idx());
  }
  std::sort(candidates.begin(), candidates.end());
  for (const auto& [clearance, index] : candidates) {
    const VertexHandle v = mesh.vertex_handle(index);
    std::optional<SurfacePoint> point;
    for (const FaceHandle f : mesh.vf_range(v)) {
      if (patch_of(mesh, f) == patch) {
        point = to_input_point(mesh, input, f, position(mesh, v));
        break;
      }
    }
    XP_ASSERT_MSG(point, "helper vertex " << index << " has no face in patch " << patch);
    if (!holds_any(input, *point, held)) return point;
  }
  return std::nullopt;
}

// `base` + " (behind)", with "'" appended until no name in `taken` has it.
std::string free_name(const std::string& base, const std::vector<std::string>& taken) {
  std::string name = base + " (behind)";
  while (std::find(taken.begin(), taken.end(), name) != taken.end()) name += "'";
  return name;
}

}  // namespace

std::vector<TipAnchor> tip_anchors(const Layout& layout, const std::array<const Mesh*, 2>& inputs,
                                   const std::vector<std::string>& names,
                                   const std::vector<CornerMismatch>& tips, double reach,
                                   std::optional<std::vector<int>> held_template_vertices) {
  if (static_cast<int>(names.size()) != layout.n_anchors) {
    throw ParamError("tip_anchors: " + std::to_string(names.size()) + " names for " +
                     std::to_string(layout.n_anchors) + " anchors");
  }
  const CornerAngles angles = corner_angles(layout);
  std::vector<std::string> taken = names;
  std::vector<TipAnchor> helpers;
  for (const CornerMismatch& tip : tips) {
    std::array<std::optional<SurfacePoint>, 2> points;
    for (int side = 0; side < 2; ++side)
      points[side] =
          helper_point(layout, angles, *inputs[side], side, tip.anchor, reach,
                       side == 0 && held_template_vertices ? *held_template_vertices : std::vector<int>{});
    if (!points[0] || !points[1]) continue;
    if (held_template_vertices) {
      const std::vector<int> held = held_vertices(*inputs[0], *points[0]);
      held_template_vertices->insert(held_template_vertices->end(), held.begin(), held.end());
    }
    TipAnchor helper;
    helper.tip = names[tip.anchor];
    const std::string name = free_name(helper.tip, taken);
    taken.push_back(name);
    for (int side = 0; side < 2; ++side) helper.specs[side] = {name, *points[side], "", 0};
    helpers.push_back(std::move(helper));
  }
  return helpers;
}

}  // namespace xparam
