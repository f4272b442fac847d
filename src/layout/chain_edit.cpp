#include "layout/chain_edit.h"

#include "core/errors.h"

#include <cstddef>
#include <vector>
#include <string>

namespace xparam {

OpenMesh::FPropHandleT<int> patch_property(const Mesh& mesh) {
  OpenMesh::FPropHandleT<int> handle;
  if (!mesh.get_property_handle(handle, "xparam:patch")) {
    throw InternalError("mesh has no patch property: assign_patches was not called");
  }
  return handle;
}

std::array<int, 2> patches_of_edge(const Layout& layout, int e) {
  std::array<int, 2> patches = {-1, -1};
  for (int p = 0; p < static_cast<int>(layout.patches.size()); ++p) {
    for (const int h : layout.patches[p]) {
      if (layout_edge_of(h) == e) patches[h & 1] = p;
    }
  }
  if (patches[0] < 0 || patches[1] < 0) {
    throw LayoutError("layout edge " + std::to_string(e) + " does not bound two patches");
  }
  return patches;
}

// patch_faces, patch_mask and relabel_region run once per stretched or swapped curve on meshes of
// up to a few hundred thousand faces (a refined target): they visit the region's faces only, from
// the faces beside the chain, so a curve costs what its two patches hold.

std::vector<int> patch_faces(const Mesh& mesh, const std::array<int, 2>& patches,
                             const std::vector<VertexHandle>& chain) {
  XP_ASSERT(chain.size() >= 2);
  const std::vector<int>& labels = mesh.property(patch_property(mesh)).data_vector();
  const auto in_patches = [&](FaceHandle f) {
    return labels[f.idx()] == patches[0] || labels[f.idx()] == patches[1];
  };
  const HalfedgeHandle seed = mesh.find_halfedge(chain[0], chain[1]);
  XP_ASSERT_MSG(seed.is_valid(), "the chain's first two vertices share no edge");
  std::vector<char> seen(mesh.n_faces(), 0);
  std::vector<int> faces;
  const std::array<FaceHandle, 2> beside = {mesh.face_handle(seed), mesh.opposite_face_handle(seed)};
  for (const FaceHandle f : beside) {
    XP_ASSERT_MSG(f.is_valid() && in_patches(f), "a face beside the chain is outside its two patches");
    seen[f.idx()] = 1;
    faces.push_back(f.idx());
  }
  for (std::size_t next = 0; next < faces.size(); ++next) {
    for (const HalfedgeHandle h : mesh.fh_range(FaceHandle(faces[next]))) {
      const FaceHandle g = mesh.opposite_face_handle(h);
      if (!g.is_valid() || seen[g.idx()] || !in_patches(g)) continue;
      seen[g.idx()] = 1;
      faces.push_back(g.idx());
    }
  }
  return faces;
}

std::vector<bool> patch_mask(const Mesh& mesh, const std::array<int, 2>& patches,
                             const std::vector<VertexHandle>& chain) {
  std::vector<bool> mask(mesh.n_faces(), false);
  for (const int f : patch_faces(mesh, patches, chain)) mask[f] = true;
  return mask;
}

int relabel_region(Mesh& mesh, const std::vector<bool>& region, const std::vector<VertexHandle>& chain,
                   const std::array<int, 2>& patches) {
  XP_ASSERT_EQ(region.size(), mesh.n_faces());
  XP_ASSERT(chain.size() >= 2);
  // Position of each chain vertex, so "is this mesh edge a chain edge" is O(1).
  std::vector<int> at(mesh.n_vertices(), -1);
  for (int k = 0; k < static_cast<int>(chain.size()); ++k) at[chain[k].idx()] = k;
  const auto on_chain = [&](HalfedgeHandle h) {
    const int i = at[mesh.from_vertex_handle(h).idx()];
    const int j = at[mesh.to_vertex_handle(h).idx()];
    return i >= 0 && j >= 0 && (i - j == 1 || j - i == 1);
  };
  // Each part of the region, flooded from its face beside the chain's first edge: the left part
  // without crossing the chain, then the right part through every face the left one left.
  std::vector<char> part(mesh.n_faces(), 0);  // 0: not reached, 1: left, 2: right
  const auto flood = [&](FaceHandle seed, char label, bool stop_at_chain) {
    std::vector<FaceHandle> faces{seed};
    part[seed.idx()] = label;
    for (std::size_t k = 0; k < faces.size(); ++k) {
      for (const HalfedgeHandle h : mesh.fh_range(faces[k])) {
        if (stop_at_chain && on_chain(h)) continue;
        const FaceHandle g = mesh.opposite_face_handle(h);
        if (!g.is_valid() || !region[g.idx()] || part[g.idx()] != 0) continue;
        part[g.idx()] = label;
        faces.push_back(g);
      }
    }
    return faces;
  };
  const HalfedgeHandle first = mesh.find_halfedge(chain[0], chain[1]);
  const FaceHandle seed = mesh.face_handle(first);
  XP_ASSERT_MSG(seed.is_valid() && region[seed.idx()],
                "the face left of the chain's first edge is outside the region");
  const std::vector<FaceHandle> left = flood(seed, 1, true);
  const FaceHandle right = mesh.opposite_face_handle(first);
  XP_ASSERT_MSG(right.is_valid() && region[right.idx()] && part[right.idx()] == 0,
                "the chain does not cut its region in two");
  const std::vector<FaceHandle> rest = flood(right, 2, false);
  const auto handle = patch_property(mesh);
  for (const FaceHandle f : left) mesh.property(handle, f) = patches[0];
  for (const FaceHandle f : rest) mesh.property(handle, f) = patches[1];
  return static_cast<int>(left.size());
}

}  // namespace xparam
