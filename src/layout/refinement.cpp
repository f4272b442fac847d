#include "layout/refinement.h"

#include "core/errors.h"
#include "core/provenance.h"

#include <algorithm>

namespace xparam {

int make_room(LayoutSide& side, VertexLabels& labels, const std::vector<VertexHandle>& around) {
  Mesh& mesh = side.mesh;
  std::vector<EdgeHandle> to_split;
  for (const VertexHandle v : around) {
    if (!labels.blocked(v)) continue;
    for (const HalfedgeHandle h : mesh.voh_range(v)) {
      const VertexHandle w = mesh.to_vertex_handle(h);
      if (labels.blocked(w) && !is_chain_edge(side, labels, v, w)) to_split.push_back(mesh.edge_handle(h));
    }
  }
  std::sort(to_split.begin(), to_split.end());
  to_split.erase(std::unique(to_split.begin(), to_split.end()), to_split.end());
  // Splitting keeps the other collected edges intact (same handle, same ends).
  for (const EdgeHandle e : to_split) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    const Eigen::Vector3d midpoint =
        0.5 * (position(mesh, mesh.from_vertex_handle(h)) + position(mesh, mesh.to_vertex_handle(h)));
    split_edge_keeping_provenance(mesh, e, midpoint);
  }
  labels.resize(mesh.n_vertices());
  for (const VertexHandle v : around) {
    for (const FaceHandle f : mesh.vf_range(v)) {
      bool all_blocked = true;
      for (const VertexHandle c : mesh.fv_range(f)) all_blocked = all_blocked && labels.blocked(c);
      XP_ASSERT_MSG(!all_blocked, "face " << f.idx() << " has three blocked corners after refinement");
    }
  }
  return static_cast<int>(to_split.size());
}

}  // namespace xparam
