#include "domain/patch_merging.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace xparam {
namespace {

// Angle at the origin of outgoing mesh halfedge h inside the face on its left.
double corner_angle(const Mesh& mesh, HalfedgeHandle h) {
  const Eigen::Vector3d apex = position(mesh, mesh.from_vertex_handle(h));
  const Eigen::Vector3d u = position(mesh, mesh.to_vertex_handle(h)) - apex;
  const Eigen::Vector3d w = position(mesh, mesh.to_vertex_handle(mesh.next_halfedge_handle(h))) - apex;
  // atan2 of |u x w| and u . w stays accurate for angles near 0 and pi, where acos does not.
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

// The patch left of each layout halfedge; -1 when no patch names it.
std::vector<int> patch_of_halfedges(const Layout& layout) {
  std::vector<int> owner(2 * layout.edges.size(), -1);
  for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p) {
    for (int h : layout.patches[p]) owner[h] = p;
  }
  return owner;
}

// Walk of patch `p` rotated to start at its halfedge `h`.
std::vector<int> walk_from(const Layout& layout, int p, int h) {
  std::vector<int> walk = layout.patches[p];
  const auto at = std::find(walk.begin(), walk.end(), h);
  XP_ASSERT_MSG(at != walk.end(), "layout halfedge " << h << " is not in patch " << p);
  std::rotate(walk.begin(), at, walk.end());
  return walk;
}

[[noreturn]] void refuse(int e, const std::string& why) {
  std::ostringstream message;
  message << "merge_patches: layout edge " << e << " " << why;
  throw LayoutError(message.str());
}

}  // namespace

std::vector<double> corner_surface_angles(const Layout& layout, int side, int p) {
  XP_ASSERT_MSG(p >= 0 && p < static_cast<int>(layout.patches.size()), "patch " << p << " does not exist");
  const LayoutSide& s = layout.sides[side];
  const Mesh& mesh = s.mesh;
  const std::vector<int>& walk = layout.patches[p];
  std::vector<double> angles;
  angles.reserve(walk.size());
  for (int g : walk) {
    const int anchor = layout_from(layout, g);
    const VertexHandle apex = s.anchor_vertices[anchor];
    // Second vertex of every chain leaving the anchor: the mesh halfedges where wedges end.
    std::vector<VertexHandle> chain_starts;
    for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
      const auto& chain = s.chains[e];
      if (chain.front() == apex) chain_starts.push_back(chain[1]);
      if (chain.back() == apex) chain_starts.push_back(chain[chain.size() - 2]);
    }
    const std::vector<VertexHandle> chain = halfedge_chain(layout, side, g);
    const HalfedgeHandle first = mesh.find_halfedge(chain[0], chain[1]);
    XP_ASSERT_MSG(first.is_valid(), "side " << side << ": chain of layout halfedge " << g << " leaves anchor "
                                             << anchor << " along no mesh edge");
    // Counter-clockwise from g's first mesh halfedge to the next one that starts a chain; the
    // faces swept are the corner's wedge (a lone chain sweeps the whole fan and stops at itself).
    double angle = 0.0;
    HalfedgeHandle h = first;
    do {
      XP_ASSERT_MSG(patch_of(mesh, mesh.face_handle(h)) == p,
                    "side " << side << ": face " << mesh.face_handle(h).idx() << " in the wedge of patch " << p
                            << " at anchor " << anchor << " has patch " << patch_of(mesh, mesh.face_handle(h)));
      angle += corner_angle(mesh, h);
      h = mesh.ccw_rotated_halfedge_handle(h);
    } while (std::find(chain_starts.begin(), chain_starts.end(), mesh.to_vertex_handle(h)) ==
             chain_starts.end());
    angles.push_back(angle);
  }
  return angles;
}

CornerAngles corner_angles(const Layout& layout) {
  CornerAngles angles;
  for (int side = 0; side < 2; ++side) {
    for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p)
      angles[side].push_back(corner_surface_angles(layout, side, p));
  }
  return angles;
}

void merge_patches(Layout& layout, const std::vector<int>& edges) {
  const int n_edges = static_cast<int>(layout.edges.size());
  const int n_patches = static_cast<int>(layout.patches.size());
  const std::vector<int> owner = patch_of_halfedges(layout);

  // Check every edge before changing anything; the quad of each as a new walk.
  std::vector<char> edge_removed(n_edges, 0);
  std::vector<int> merged_into(n_patches, -1);  // removed patch -> the patch id its quad keeps
  std::vector<char> patch_taken(n_patches, 0);
  std::vector<std::pair<int, std::vector<int>>> quads;  // (kept patch id, walk in old halfedges)
  for (int e : edges) {
    if (e < 0 || e >= n_edges) refuse(e, "does not exist (" + std::to_string(n_edges) + " edges)");
    if (edge_removed[e]) refuse(e, "is given twice");
    const int left = owner[2 * e];
    const int right = owner[2 * e + 1];
    if (left < 0 || right < 0 || left == right) refuse(e, "does not separate two patches");
    if (layout.patches[left].size() != 3 || layout.patches[right].size() != 3) {
      refuse(e, "is not between two triangles (patches " + std::to_string(left) + " and " + std::to_string(right) +
                    ")");
    }
    for (int p : {left, right}) {
      if (patch_taken[p]) refuse(e, "borders patch " + std::to_string(p) + ", which another merged edge borders too");
    }
    // Left: a -> b, b -> l, l -> a; right: b -> a, a -> r, r -> b.
    const std::vector<int> l_walk = walk_from(layout, left, 2 * e);
    const std::vector<int> r_walk = walk_from(layout, right, 2 * e + 1);
    if (layout_to(layout, l_walk[1]) == layout_to(layout, r_walk[1])) {
      refuse(e, "has the same third anchor " + std::to_string(layout_to(layout, l_walk[1])) + " on both sides");
    }
    edge_removed[e] = 1;
    patch_taken[left] = patch_taken[right] = 1;
    const int kept = std::min(left, right);
    merged_into[std::max(left, right)] = kept;
    quads.push_back({kept, {r_walk[1], r_walk[2], l_walk[1], l_walk[2]}});
  }

  // Compact numbering of the surviving edges and patches, in their old order.
  std::vector<int> new_edge(n_edges, -1);
  int next_edge = 0;
  for (int e = 0; e < n_edges; ++e) {
    if (!edge_removed[e]) new_edge[e] = next_edge++;
  }
  std::vector<int> new_patch(n_patches, -1);
  int next_patch = 0;
  for (int p = 0; p < n_patches; ++p) {
    if (merged_into[p] < 0) new_patch[p] = next_patch++;
  }
  auto renumbered = [&](int h) {
    XP_ASSERT_MSG(!edge_removed[layout_edge_of(h)], "a merged walk keeps removed halfedge " << h);
    return 2 * new_edge[layout_edge_of(h)] + (h & 1);
  };

  for (auto& [kept, walk] : quads) layout.patches[kept] = std::move(walk);
  std::vector<std::vector<int>> patches;
  patches.reserve(next_patch);
  for (int p = 0; p < n_patches; ++p) {
    if (new_patch[p] < 0) continue;
    std::vector<int> walk;
    for (int h : layout.patches[p]) walk.push_back(renumbered(h));
    patches.push_back(std::move(walk));
  }
  layout.patches = std::move(patches);

  std::vector<LayoutEdge> kept_edges;
  std::array<std::vector<std::vector<VertexHandle>>, 2> kept_chains;
  for (int e = 0; e < n_edges; ++e) {
    if (edge_removed[e]) continue;
    kept_edges.push_back(layout.edges[e]);
    for (int side = 0; side < 2; ++side) kept_chains[side].push_back(std::move(layout.sides[side].chains[e]));
  }
  layout.edges = std::move(kept_edges);
  for (int side = 0; side < 2; ++side) layout.sides[side].chains = std::move(kept_chains[side]);

  // The fill from each patch's first halfedge relabels every face; the removed chains no
  // longer stop it, so each quad's fill covers both of its triangles.
  assign_patches(layout);
}

}  // namespace xparam
