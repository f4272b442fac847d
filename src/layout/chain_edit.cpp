#include "layout/chain_edit.h"

#include "core/errors.h"

#include <cstddef>
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

// patch_mask and relabel_region run once per stretched or swapped curve, over every face of a
// mesh of up to a few hundred thousand faces (a refined target): they read and write the patch
// property's array by index, which costs a few times less than the face range's per-face checks.
// The layout's meshes delete nothing, so every index is a face.

std::vector<bool> patch_mask(const Mesh& mesh, const std::array<int, 2>& patches) {
  const std::vector<int>& labels = mesh.property(patch_property(mesh)).data_vector();
  std::vector<bool> mask(labels.size(), false);
  for (std::size_t f = 0; f < labels.size(); ++f) {
    mask[f] = labels[f] == patches[0] || labels[f] == patches[1];
  }
  return mask;
}

int relabel_region(Mesh& mesh, const std::vector<bool>& region, const std::vector<VertexHandle>& chain,
                   const std::array<int, 2>& patches) {
  XP_ASSERT_EQ(region.size(), mesh.n_faces());
  XP_ASSERT(chain.size() >= 2);
  const auto handle = patch_property(mesh);
  // Position of each chain vertex, so "is this mesh edge a chain edge" is O(1).
  std::vector<int> at(mesh.n_vertices(), -1);
  for (int k = 0; k < static_cast<int>(chain.size()); ++k) at[chain[k].idx()] = k;
  const auto on_chain = [&](HalfedgeHandle h) {
    const int i = at[mesh.from_vertex_handle(h).idx()];
    const int j = at[mesh.to_vertex_handle(h).idx()];
    return i >= 0 && j >= 0 && (i - j == 1 || j - i == 1);
  };
  std::vector<char> left(mesh.n_faces(), 0);
  const FaceHandle seed = mesh.face_handle(mesh.find_halfedge(chain[0], chain[1]));
  XP_ASSERT_MSG(seed.is_valid() && region[seed.idx()],
                "the face left of the chain's first edge is outside the region");
  left[seed.idx()] = 1;
  std::vector<FaceHandle> stack{seed};
  int count = 1;
  while (!stack.empty()) {
    const FaceHandle f = stack.back();
    stack.pop_back();
    for (const HalfedgeHandle h : mesh.fh_range(f)) {
      if (on_chain(h)) continue;
      const FaceHandle g = mesh.opposite_face_handle(h);
      if (!g.is_valid() || !region[g.idx()] || left[g.idx()]) continue;
      left[g.idx()] = 1;
      ++count;
      stack.push_back(g);
    }
  }
  const FaceHandle right = mesh.opposite_face_handle(mesh.find_halfedge(chain[0], chain[1]));
  XP_ASSERT_MSG(right.is_valid() && !left[right.idx()], "the chain does not cut its region in two");
  std::vector<int>& labels = mesh.property(handle).data_vector();
  for (std::size_t f = 0; f < labels.size(); ++f) {
    if (region[f]) labels[f] = left[f] ? patches[0] : patches[1];
  }
  return count;
}

}  // namespace xparam
