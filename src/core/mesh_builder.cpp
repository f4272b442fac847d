#include "core/mesh_builder.h"

#include "core/errors.h"

#include <sstream>
#include <utility>

namespace xparam {

Mesh build_mesh(const TriangleSoup& soup, TriangleOrder order) {
  Mesh mesh;
  mesh.reserve(soup.vertices.size(), 3 * soup.triangles.size() / 2, soup.triangles.size());
  for (const Eigen::Vector3d& p : soup.vertices) mesh.add_vertex(to_point(p));
  const auto n_vertices = static_cast<int>(soup.vertices.size());
  for (size_t j = 0; j < soup.triangles.size(); ++j) {
    const auto& t = soup.triangles[j];
    for (int v : t)
      if (v < 0 || v >= n_vertices)
        throw InputError(soup.source + ": face " + std::to_string(j) + " refers to vertex " + std::to_string(v) +
                         " but there are " + std::to_string(n_vertices) + " vertices");
    const int second = order == TriangleOrder::AsInFile ? t[1] : t[2];
    const int third = order == TriangleOrder::AsInFile ? t[2] : t[1];
    // add_face returns an invalid handle (and OpenMesh prints to its log) for a face that
    // would make the mesh non-manifold; a validated soup never does that.
    const FaceHandle f =
        mesh.add_face(mesh.vertex_handle(t[0]), mesh.vertex_handle(second), mesh.vertex_handle(third));
    if (!f.is_valid() || f.idx() != static_cast<int>(j)) {
      std::ostringstream message;
      message << soup.source << ": face " << j << " (" << t[0] << ", " << t[1] << ", " << t[2]
              << ") could not be added to the mesh (non-manifold or inconsistently oriented there)";
      throw InputError(message.str());
    }
  }
  return mesh;
}

TriangleSoup soup_of(const Mesh& mesh, std::string source) {
  TriangleSoup soup;
  soup.source = std::move(source);
  soup.vertices.reserve(mesh.n_vertices());
  for (VertexHandle v : mesh.vertices()) soup.vertices.push_back(position(mesh, v));
  soup.triangles = triangles_of(mesh);
  return soup;
}

}  // namespace xparam
