#include "map/patch_extraction.h"

#include "core/errors.h"

#include <string>

namespace xparam {
namespace {

double polyline_length(const Mesh& mesh, const std::vector<VertexHandle>& chain) {
  double length = 0.0;
  for (size_t i = 1; i < chain.size(); ++i) length += (position(mesh, chain[i]) - position(mesh, chain[i - 1])).norm();
  return length;
}

// The patch's polygon: its LPBD when that is a proper triangle, else the chord triangle.
Lpbd patch_polygon(const Layout& layout, int side, const std::vector<int>& walk, Lpbd& lpbd) {
  const Mesh& mesh = layout.sides[side].mesh;
  std::array<double, 3> curve{};
  std::array<double, 3> chord{};
  for (int j = 0; j < 3; ++j) {
    curve[j] = chain_length(layout, side, layout_edge_of(walk[j]));
    const VertexHandle from = layout.sides[side].anchor_vertices[layout_from(layout, walk[j])];
    const VertexHandle to = layout.sides[side].anchor_vertices[layout_to(layout, walk[j])];
    chord[j] = (position(mesh, to) - position(mesh, from)).norm();
  }
  lpbd = triangle_lpbd(curve[0], curve[1], curve[2]);
  if (lpbd.valid) return lpbd;
  return triangle_lpbd(chord[0], chord[1], chord[2]);
}

}  // namespace

double chain_length(const Layout& layout, int side, int e) {
  return polyline_length(layout.sides[side].mesh, layout.sides[side].chains[e]);
}

SidePatches extract_patches(const Layout& layout, int side) {
  const Mesh& mesh = layout.sides[side].mesh;
  const int n_patches = static_cast<int>(layout.patches.size());
  SidePatches result;
  result.patches.resize(n_patches);
  result.lpbds.resize(n_patches);
  result.local_to_mesh.resize(n_patches);
  result.triangle_faces.resize(n_patches);
  result.face_corners.assign(mesh.n_faces(), {-1, -1, -1});

  // Local ids in order of first appearance over the faces, so they do not depend on anything
  // but the mesh: one scan over faces, one per-patch map from mesh vertex to local id.
  for (FaceHandle f : mesh.faces()) {
    const int p = patch_of(mesh, f);
    XP_ASSERT_MSG(p >= 0 && p < n_patches, "side " << side << " face " << f.idx() << " has patch " << p);
    result.triangle_faces[p].push_back(f.idx());
  }
  std::vector<int> local(mesh.n_vertices(), -1);
  for (int p = 0; p < n_patches; ++p) {
    XP_ASSERT_MSG(layout.patches[p].size() == 3, "patch " << p << " has " << layout.patches[p].size() << " sides");
    DiskPatch& patch = result.patches[p];
    patch.name = "side " + std::to_string(side) + " patch " + std::to_string(p);
    std::vector<int>& to_mesh = result.local_to_mesh[p];
    auto local_id = [&](VertexHandle v) {
      if (local[v.idx()] < 0) {
        local[v.idx()] = static_cast<int>(to_mesh.size());
        to_mesh.push_back(v.idx());
        patch.positions.push_back(position(mesh, v));
      }
      return local[v.idx()];
    };
    for (int f : result.triangle_faces[p]) {
      std::array<int, 3> corners{};
      int k = 0;
      for (VertexHandle v : mesh.fv_range(mesh.face_handle(f))) corners[k++] = local_id(v);
      patch.triangles.push_back(corners);
      result.face_corners[f] = corners;
    }
    // Boundary: the chains of the patch's walk, each without its last vertex (the next one's first).
    for (int h : layout.patches[p]) {
      patch.corner_positions.push_back(static_cast<int>(patch.boundary_loop.size()));
      const std::vector<VertexHandle> chain = halfedge_chain(layout, side, h);
      for (size_t i = 0; i + 1 < chain.size(); ++i) patch.boundary_loop.push_back(local_id(chain[i]));
    }
    const Lpbd polygon = patch_polygon(layout, side, layout.patches[p], result.lpbds[p]);
    if (!result.lpbds[p].valid) ++result.fallback_polygons;
    patch.polygon = polygon.corners;
    for (int v : to_mesh) local[v] = -1;
  }
  return result;
}

}  // namespace xparam
