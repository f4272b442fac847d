#include "evaluate/decimated_target.h"

#include "io/mesh_writer.h"

#include "map/decimation.h"

#include <stdexcept>
#include <string>

namespace xparam::evaluate {

Mesh decimate(const Mesh& mesh, int vertices) {
  Mesh decimated = xparam::decimate(mesh, vertices).mesh;
  if (decimated.n_vertices() > static_cast<std::size_t>(vertices))
    throw std::runtime_error("decimation stopped at " + std::to_string(decimated.n_vertices()) + " vertices, " +
                             std::to_string(vertices) + " asked for");
  return decimated;
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
