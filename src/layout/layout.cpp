#include "layout/layout.h"

#include "core/errors.h"

#include <algorithm>

namespace xparam {
namespace {

constexpr const char* kPatchProperty = "xparam:patch";

OpenMesh::FPropHandleT<int> patch_handle(const Mesh& mesh) {
  OpenMesh::FPropHandleT<int> handle;
  if (!mesh.get_property_handle(handle, kPatchProperty)) {
    throw InternalError("mesh has no patch property: assign_patches was not called");
  }
  return handle;
}

// Mesh edges that some chain of `side` runs along.
std::vector<char> chain_edge_mask(const LayoutSide& side) {
  std::vector<char> mask(side.mesh.n_edges(), 0);
  for (const auto& chain : side.chains) {
    for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
      const HalfedgeHandle h = side.mesh.find_halfedge(chain[i], chain[i + 1]);
      if (h.is_valid()) mask[side.mesh.edge_handle(h).idx()] = 1;
    }
  }
  return mask;
}

// Whether two sides hold the same mesh (positions, faces in order, patches), anchor vertices
// and chains.
bool same_side(const LayoutSide& a, const LayoutSide& b) {
  if (a.mesh.n_vertices() != b.mesh.n_vertices() || a.mesh.n_faces() != b.mesh.n_faces() ||
      a.anchor_vertices != b.anchor_vertices || a.chains != b.chains)
    return false;
  for (VertexHandle v : a.mesh.vertices()) {
    if (a.mesh.point(v) != b.mesh.point(v)) return false;
  }
  const bool patches = has_patch_property(a.mesh);
  if (patches != has_patch_property(b.mesh)) return false;
  for (FaceHandle f : a.mesh.faces()) {
    const FaceHandle g = b.mesh.face_handle(f.idx());
    if (!std::equal(a.mesh.cfv_begin(f), a.mesh.cfv_end(f), b.mesh.cfv_begin(g), b.mesh.cfv_end(g)))
      return false;
    if (patches && patch_of(a.mesh, f) != patch_of(b.mesh, g)) return false;
  }
  return true;
}

}  // namespace

bool same_layout(const Layout& a, const Layout& b) {
  if (a.n_anchors != b.n_anchors || a.edges.size() != b.edges.size() || a.patches != b.patches) return false;
  for (std::size_t e = 0; e < a.edges.size(); ++e) {
    if (a.edges[e].anchors != b.edges[e].anchors) return false;
  }
  return same_side(a.sides[0], b.sides[0]) && same_side(a.sides[1], b.sides[1]);
}

std::vector<VertexHandle> halfedge_chain(const Layout& layout, int side, int h) {
  std::vector<VertexHandle> chain = layout.sides[side].chains[layout_edge_of(h)];
  if (h & 1) std::reverse(chain.begin(), chain.end());
  return chain;
}

bool has_patch_property(const Mesh& mesh) {
  OpenMesh::FPropHandleT<int> handle;
  return mesh.get_property_handle(handle, kPatchProperty);
}

int patch_of(const Mesh& mesh, FaceHandle f) { return mesh.property(patch_handle(mesh), f); }

void assign_patches(Layout& layout) {
  for (LayoutSide& side : layout.sides) {
    Mesh& mesh = side.mesh;
    OpenMesh::FPropHandleT<int> handle;
    if (!mesh.get_property_handle(handle, kPatchProperty)) mesh.add_property(handle, kPatchProperty);
    for (FaceHandle f : mesh.faces()) mesh.property(handle, f) = -1;
    const std::vector<char> on_chain = chain_edge_mask(side);
    std::vector<FaceHandle> stack;
    for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p) {
      const int g = layout.patches[p].front();
      const auto& chain = side.chains[layout_edge_of(g)];
      const VertexHandle start = (g & 1) ? chain.back() : chain.front();
      const VertexHandle next = (g & 1) ? chain[chain.size() - 2] : chain[1];
      const HalfedgeHandle seed = mesh.find_halfedge(start, next);
      if (!seed.is_valid() || mesh.is_boundary(seed)) continue;
      const FaceHandle first = mesh.face_handle(seed);
      if (mesh.property(handle, first) != -1) continue;
      mesh.property(handle, first) = p;
      stack.assign(1, first);
      while (!stack.empty()) {
        const FaceHandle f = stack.back();
        stack.pop_back();
        for (HalfedgeHandle h : mesh.fh_range(f)) {
          if (on_chain[mesh.edge_handle(h).idx()]) continue;
          const FaceHandle g_face = mesh.opposite_face_handle(h);
          if (!g_face.is_valid() || mesh.property(handle, g_face) != -1) continue;
          mesh.property(handle, g_face) = p;
          stack.push_back(g_face);
        }
      }
    }
  }
}

std::vector<int> mesh_rotation(const Layout& layout, int side, int anchor) {
  const LayoutSide& s = layout.sides[side];
  const Mesh& mesh = s.mesh;
  const VertexHandle a = s.anchor_vertices[anchor];
  // Second vertex of each chain leaving the anchor -> that layout halfedge.
  std::vector<std::pair<VertexHandle, int>> starts;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    const auto& chain = s.chains[e];
    if (chain.size() < 2) continue;
    if (layout.edges[e].anchors[0] == anchor && chain.front() == a) starts.emplace_back(chain[1], 2 * e);
    if (layout.edges[e].anchors[1] == anchor && chain.back() == a)
      starts.emplace_back(chain[chain.size() - 2], 2 * e + 1);
  }
  std::vector<int> rotation;
  if (starts.empty()) return rotation;
  const HalfedgeHandle first = mesh.halfedge_handle(a);
  HalfedgeHandle h = first;
  do {
    const VertexHandle x = mesh.to_vertex_handle(h);
    for (const auto& [vertex, halfedge] : starts) {
      if (vertex == x) rotation.push_back(halfedge);
    }
    h = mesh.ccw_rotated_halfedge_handle(h);
  } while (h != first);
  return rotation;
}

std::vector<std::vector<int>> faces_of_rotation(const Layout& layout,
                                                const std::vector<std::vector<int>>& rotations) {
  const int n_halfedges = 2 * static_cast<int>(layout.edges.size());
  // Position of each halfedge in its origin's rotation.
  std::vector<int> slot(n_halfedges, -1);
  for (const auto& rotation : rotations) {
    for (int i = 0; i < static_cast<int>(rotation.size()); ++i) slot[rotation[i]] = i;
  }
  std::vector<char> used(n_halfedges, 0);
  std::vector<std::vector<int>> faces;
  for (int start = 0; start < n_halfedges; ++start) {
    if (used[start] || slot[start] < 0) continue;
    std::vector<int> face;
    int h = start;
    while (!used[h]) {
      used[h] = 1;
      face.push_back(h);
      const int back = layout_opposite(h);
      const auto& rotation = rotations[layout_to(layout, h)];
      XP_ASSERT_MSG(slot[back] >= 0, "layout halfedge " << back << " missing from its anchor's rotation");
      const int k = static_cast<int>(rotation.size());
      h = rotation[(slot[back] + k - 1) % k];
    }
    XP_ASSERT_MSG(h == start, "rotation system does not close a face at halfedge " << start);
    faces.push_back(std::move(face));
  }
  return faces;
}

}  // namespace xparam
