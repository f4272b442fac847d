#include "io/mesh_loader.h"

#include "core/errors.h"
#include "core/mesh_builder.h"
#include "core/provenance.h"
#include "io/mesh_reader.h"

#include <string>

namespace xparam {

LoadedMesh load_mesh(const std::filesystem::path& path, const ValidationSettings& settings) {
  return load_soup(path, read_triangle_soup(path), settings);
}

LoadedMesh load_soup(const std::filesystem::path& path, TriangleSoup soup, const ValidationSettings& settings) {
  MeshReport report = validate_soup(soup, settings);
  return load_validated_soup(path, std::move(soup), std::move(report));
}

LoadedMesh load_validated_soup(const std::filesystem::path& path, TriangleSoup soup, MeshReport report) {
  LoadedMesh loaded{path, Mesh(), std::move(report), {}, {}};
  if (!loaded.report.usable) {
    // One line (the batch driver records it per target) with the first problems, each of
    // which names the file and the element.
    const auto errors = loaded.report.errors();
    std::string message = soup.source + " is not usable:";
    for (size_t i = 0; i < errors.size() && i < static_cast<size_t>(kProblemsInLoadError); ++i)
      message += (i == 0 ? " " : "; ") + errors[i]->message;
    if (errors.size() > static_cast<size_t>(kProblemsInLoadError)) message += "; ...";
    throw InputError(message);
  }
  const auto file_vertices = static_cast<int>(soup.vertices.size());
  FileOrder& order = loaded.file_order;
  order = FileOrder::identity(static_cast<int>(soup.triangles.size()), file_vertices);
  if (!loaded.report.reoriented_faces.empty() || !loaded.report.split_vertices.empty()) {
    SoupRepair repair = repair_soup(soup);
    order.reversed = std::move(repair.reversed);
    order.copy_of.resize(repair.soup.vertices.size() - soup.vertices.size());
    for (const VertexSplit& split : repair.split_vertices)
      for (int copy : split.copies) order.copy_of[copy - file_vertices] = split.vertex;
    soup = std::move(repair.soup);
  }
  loaded.mesh = build_mesh(soup);
  if (signed_volume(loaded.mesh) < 0.0) {
    loaded.mesh = build_mesh(soup, TriangleOrder::Reversed);
    order.reversed.flip();
  }
  init_provenance(loaded.mesh);
  return loaded;
}

}  // namespace xparam
