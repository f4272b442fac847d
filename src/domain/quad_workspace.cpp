#include "domain/quad_workspace.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "layout/chain_edit.h"

#include <algorithm>
#include <utility>

namespace xparam {
namespace {

// The property names of core/provenance.cpp and layout/layout.cpp: neither module offers a
// setter, and the workspace copies the values rather than recomputing them (the
// quad_workspace tests read them back through input_face and patch_of).
constexpr const char* kInputFaceProperty = "xparam:input_face";
constexpr const char* kPatchProperty = "xparam:patch";

// Sorted, distinct full-mesh indices; the position of an index in the list is its workspace index.
class IndexMap {
 public:
  explicit IndexMap(std::vector<int> indices) : global_(std::move(indices)) {
    std::sort(global_.begin(), global_.end());
    global_.erase(std::unique(global_.begin(), global_.end()), global_.end());
  }
  int size() const { return static_cast<int>(global_.size()); }
  const std::vector<int>& global() const { return global_; }
  bool has(int index) const { return std::binary_search(global_.begin(), global_.end(), index); }
  int local(int index) const {
    const auto it = std::lower_bound(global_.begin(), global_.end(), index);
    XP_ASSERT_MSG(it != global_.end() && *it == index, "element " << index << " is not in the quad");
    return static_cast<int>(it - global_.begin());
  }

 private:
  std::vector<int> global_;
};

// Copies one side's quad into `ws.layout.sides[side]` and closes it with the cap (file comment
// of the header for the order-isomorphism this keeps).
void copy_side(const Layout& layout, int side, QuadWorkspace& ws) {
  const LayoutSide& full = layout.sides[side];
  const Mesh& mesh = full.mesh;
  const IndexMap faces(patch_faces(mesh, ws.patches, full.chains[ws.edges[0]]));
  std::vector<int> vertex_ids, edge_ids;
  for (const int f : faces.global()) {
    for (const HalfedgeHandle h : mesh.fh_range(FaceHandle(f))) {
      vertex_ids.push_back(mesh.to_vertex_handle(h).idx());
      edge_ids.push_back(mesh.edge_handle(h).idx());
    }
  }
  const IndexMap vertices(std::move(vertex_ids));
  const IndexMap edges(std::move(edge_ids));
  // OpenMesh numbers the halfedges of edge k as 2k and 2k + 1.
  const auto halfedge = [&](HalfedgeHandle h) { return HalfedgeHandle(2 * edges.local(h.idx() / 2) + h.idx() % 2); };

  LayoutSide& out = ws.layout.sides[side];
  Mesh& local = out.mesh;
  // Room for the cap and for the splits of a swap, so they do not reallocate the arrays.
  local.reserve(2 * vertices.size() + 64, 2 * edges.size() + 64, 2 * faces.size() + 64);
  OpenMesh::FPropHandleT<int> input_face, patch, full_input_face;
  local.add_property(input_face, kInputFaceProperty);
  local.add_property(patch, kPatchProperty);
  XP_ASSERT_MSG(mesh.get_property_handle(full_input_face, kInputFaceProperty), "side " << side << " has no provenance");
  const auto full_patch = patch_property(mesh);

  for (const int v : vertices.global()) local.add_vertex(mesh.point(VertexHandle(v)));
  const VertexHandle apex = local.add_vertex(Mesh::Point(0.0, 0.0, 0.0));
  for (const int e : edges.global()) {
    const HalfedgeHandle h = mesh.halfedge_handle(EdgeHandle(e), 0);
    local.new_edge(VertexHandle(vertices.local(mesh.from_vertex_handle(h).idx())),
                   VertexHandle(vertices.local(mesh.to_vertex_handle(h).idx())));
  }
  for (const int f : faces.global()) {
    const FaceHandle g(f);
    const FaceHandle copy = local.new_face();
    local.set_halfedge_handle(copy, halfedge(mesh.halfedge_handle(g)));
    for (const HalfedgeHandle h : mesh.fh_range(g)) {
      local.set_face_handle(halfedge(h), copy);
      local.set_next_halfedge_handle(halfedge(h), halfedge(mesh.next_halfedge_handle(h)));
    }
    local.property(input_face, copy) = mesh.property(full_input_face, g);
    local.property(patch, copy) = mesh.property(full_patch, g) == ws.patches[0] ? 0 : 1;
  }

  // The halfedges left without a face run once around the boundary loop (the four side
  // chains, a simple loop): one cap face (h, to -> apex, apex -> from) on each.
  std::vector<HalfedgeHandle> loop;
  for (int h = 0; h < 2 * edges.size(); ++h) {
    if (!local.face_handle(HalfedgeHandle(h)).is_valid()) loop.emplace_back(h);
  }
  std::vector<int> leaving(vertices.size(), 0), entering(vertices.size(), 0);
  for (const HalfedgeHandle h : loop) {
    ++leaving[local.from_vertex_handle(h).idx()];
    ++entering[local.to_vertex_handle(h).idx()];
  }
  std::vector<HalfedgeHandle> spoke(vertices.size());  // apex -> v, for the loop's vertices
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int v = 0; v < vertices.size(); ++v) {
    if (leaving[v] == 0 && entering[v] == 0) continue;
    XP_ASSERT_MSG(leaving[v] == 1 && entering[v] == 1,
                  "side " << side << ": the quad's boundary passes vertex " << vertices.global()[v] << " "
                          << leaving[v] << " times");
    spoke[v] = local.new_edge(apex, VertexHandle(v));
    centroid += position(local, VertexHandle(v));
  }
  local.set_point(apex, to_point(centroid / static_cast<double>(loop.size())));
  local.set_halfedge_handle(apex, spoke[local.from_vertex_handle(loop.front()).idx()]);
  for (const HalfedgeHandle h : loop) {
    const HalfedgeHandle down = local.opposite_halfedge_handle(spoke[local.to_vertex_handle(h).idx()]);
    const HalfedgeHandle up = spoke[local.from_vertex_handle(h).idx()];
    const FaceHandle cap = local.new_face();
    local.set_halfedge_handle(cap, h);
    for (const HalfedgeHandle g : {h, down, up}) local.set_face_handle(g, cap);
    local.set_next_halfedge_handle(h, down);
    local.set_next_halfedge_handle(down, up);
    local.set_next_halfedge_handle(up, h);
    local.property(input_face, cap) = kCapInputFace;
    local.property(patch, cap) = QuadWorkspace::kCapPatch;
  }

  // Outgoing halfedges: the full mesh's where it lies in the quad, else the one to the apex
  // (only a loop vertex can have its halfedge outside; the apex stands for the outside arc).
  for (int v = 0; v < vertices.size(); ++v) {
    const HalfedgeHandle h = mesh.halfedge_handle(VertexHandle(vertices.global()[v]));
    if (edges.has(h.idx() / 2)) {
      local.set_halfedge_handle(VertexHandle(v), halfedge(h));
    } else {
      XP_ASSERT(spoke[v].is_valid());
      local.set_halfedge_handle(VertexHandle(v), local.opposite_halfedge_handle(spoke[v]));
    }
  }

  for (const int a : ws.anchors) out.anchor_vertices.emplace_back(vertices.local(full.anchor_vertices[a].idx()));
  for (const int e : ws.edges) {
    std::vector<VertexHandle>& chain = out.chains.emplace_back();
    for (const VertexHandle v : full.chains[e]) chain.emplace_back(vertices.local(v.idx()));
  }
  ws.vertices[side] = vertices.global();
  ws.faces[side] = faces.global();
  ws.apex[side] = apex;
}

}  // namespace

QuadHalfedges quad_halfedges(const Layout& layout, const SwapQuad& quad) {
  const auto after = [&](int patch, int h, int steps) {
    const std::vector<int>& walk = layout.patches[patch];
    const auto at = std::find(walk.begin(), walk.end(), h) - walk.begin();
    return walk[(at + steps) % 3];
  };
  QuadHalfedges q;
  q.bl = after(quad.left_patch, 2 * quad.edge, 1);
  q.la = after(quad.left_patch, 2 * quad.edge, 2);
  q.ar = after(quad.right_patch, 2 * quad.edge + 1, 1);
  q.rb = after(quad.right_patch, 2 * quad.edge + 1, 2);
  return q;
}

QuadWorkspace make_quad_workspace(const Layout& layout, const SwapQuad& quad) {
  XP_ASSERT_MSG(quad.l != quad.r, "the quad of edge " << quad.edge << " has l == r");
  const QuadHalfedges q = quad_halfedges(layout, quad);
  QuadWorkspace ws;
  ws.anchors = {quad.a, quad.b, quad.l, quad.r};
  ws.edges = {quad.edge, q.bl / 2, q.la / 2, q.ar / 2, q.rb / 2};
  ws.patches = {quad.left_patch, quad.right_patch};
  const auto local_anchor = [&](int anchor) {
    const auto at = std::find(ws.anchors.begin(), ws.anchors.end(), anchor);
    XP_ASSERT(at != ws.anchors.end());
    return static_cast<int>(at - ws.anchors.begin());
  };
  const auto local_halfedge = [&](int h) {
    const auto at = std::find(ws.edges.begin(), ws.edges.end(), layout_edge_of(h));
    XP_ASSERT(at != ws.edges.end());
    return 2 * static_cast<int>(at - ws.edges.begin()) + (h & 1);
  };

  Layout& out = ws.layout;
  out.n_anchors = 4;
  for (const int e : ws.edges) {
    const auto& ends = layout.edges[e].anchors;
    out.edges.push_back({{local_anchor(ends[0]), local_anchor(ends[1])}});
  }
  for (const int p : ws.patches) {
    std::vector<int>& walk = out.patches.emplace_back();
    for (const int h : layout.patches[p]) walk.push_back(local_halfedge(h));
  }
  // The cap has the quad's boundary on its left the other way round: a -> l -> b -> r.
  out.patches.push_back({local_halfedge(layout_opposite(q.la)), local_halfedge(layout_opposite(q.bl)),
                         local_halfedge(layout_opposite(q.rb)), local_halfedge(layout_opposite(q.ar))});
  ws.quad.edge = 0;
  ws.quad.a = 0;
  ws.quad.b = 1;
  ws.quad.l = 2;
  ws.quad.r = 3;
  ws.quad.left_patch = 0;
  ws.quad.right_patch = 1;
  for (int side = 0; side < 2; ++side) copy_side(layout, side, ws);
  return ws;
}

}  // namespace xparam
