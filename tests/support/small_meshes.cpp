#include "support/small_meshes.h"

namespace xparam::test {

TriangleSoup tetrahedron_soup() {
  TriangleSoup soup;
  soup.source = "tet.obj";
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  soup.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  return soup;
}

Mesh tetrahedron_mesh() {
  const TriangleSoup soup = tetrahedron_soup();
  Mesh mesh;
  for (const auto& p : soup.vertices) mesh.add_vertex({p[0], p[1], p[2]});
  for (const auto& t : soup.triangles) {
    mesh.add_face(mesh.vertex_handle(t[0]), mesh.vertex_handle(t[1]), mesh.vertex_handle(t[2]));
  }
  return mesh;
}

}  // namespace xparam::test
