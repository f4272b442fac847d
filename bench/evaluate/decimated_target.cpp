#include "evaluate/decimated_target.h"

#include "io/mesh_writer.h"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace xparam::evaluate {

Mesh decimate(const Mesh& mesh, int vertices) {
  // A fresh mesh of the same points and faces: no provenance or other properties to carry.
  Mesh work;
  for (VertexHandle v : mesh.vertices()) work.add_vertex(mesh.point(v));
  for (FaceHandle f : mesh.faces()) {
    std::vector<VertexHandle> corners;
    for (VertexHandle v : mesh.fv_range(f)) corners.emplace_back(v.idx());
    work.add_face(corners);
  }
  work.request_face_normals();
  work.update_face_normals();

  using Decimater = OpenMesh::Decimater::DecimaterT<Mesh>;
  Decimater decimater(work);
  OpenMesh::Decimater::ModQuadricT<Mesh>::Handle quadric;
  decimater.add(quadric);
  decimater.module(quadric).unset_max_err();  // priority only: collapse the cheapest edges first
  OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle normals;
  decimater.add(normals);
  decimater.module(normals).set_max_normal_deviation(60.0);
  if (!decimater.initialize()) throw std::runtime_error("the OpenMesh decimater could not be initialised");
  const std::size_t wanted = work.n_vertices() - static_cast<std::size_t>(vertices);
  const std::size_t collapses = decimater.decimate_to(static_cast<std::size_t>(vertices));
  work.garbage_collection();
  work.release_face_normals();
  if (collapses < wanted)
    throw std::runtime_error("decimation stopped at " + std::to_string(work.n_vertices()) + " vertices, " +
                             std::to_string(vertices) + " asked for");
  return work;
}

LoadedMesh write_and_load_genus0(const Mesh& mesh, const std::filesystem::path& path) {
  write_obj(path, mesh);
  LoadedMesh loaded = load_mesh(path);
  const MeshReport& report = loaded.report;
  std::string problem;
  if (report.boundary_edges > 0) problem = std::to_string(report.boundary_loops) + " boundary loops";
  else if (report.components != 1) problem = std::to_string(report.components) + " components";
  else if (!report.genus) problem = "no genus (not a 2-manifold)";
  else if (*report.genus != 0) problem = "genus " + std::to_string(*report.genus);
  else if (!report.reoriented_faces.empty() || !report.split_vertices.empty())
    problem = "the loader had to repair it: " + describe_repairs(report);
  if (!problem.empty()) throw std::runtime_error(path.string() + ": decimated mesh refused: " + problem);
  return loaded;
}

}  // namespace xparam::evaluate
