#include "core/midpoint_subdivision.h"

#include "core/provenance.h"

#include <vector>

namespace xparam {

Mesh subdivide_midpoint(const Mesh& mesh) {
  Mesh fine;
  fine.reserve(mesh.n_vertices() + mesh.n_edges(), 2 * mesh.n_edges() + 3 * mesh.n_faces(), 4 * mesh.n_faces());
  for (VertexHandle v : mesh.vertices()) fine.add_vertex(mesh.point(v));
  std::vector<VertexHandle> midpoint(mesh.n_edges());
  for (EdgeHandle e : mesh.edges()) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    midpoint[e.idx()] =
        fine.add_vertex(0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))));
  }
  for (FaceHandle f : mesh.faces()) {
    VertexHandle c[3], m[3];
    int k = 0;
    for (HalfedgeHandle h : mesh.fh_range(f)) {
      c[k] = mesh.from_vertex_handle(h);
      m[k] = midpoint[mesh.edge_handle(h).idx()];  // midpoint of edge c[k] -> c[k+1]
      ++k;
    }
    fine.add_face(c[0], m[0], m[2]);
    fine.add_face(c[1], m[1], m[0]);
    fine.add_face(c[2], m[2], m[1]);
    fine.add_face(m[0], m[1], m[2]);
  }
  init_provenance(fine);
  return fine;
}

}  // namespace xparam
