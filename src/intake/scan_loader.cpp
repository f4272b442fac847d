#include "intake/scan_loader.h"

#include "core/errors.h"
#include "io/mesh_reader.h"

#include <algorithm>
#include <utility>
#include <variant>

namespace xparam {

std::vector<IntakeLandmark> landmarks_on_file(const AnchorSet& anchors, const TriangleSoup& soup) {
  std::vector<IntakeLandmark> landmarks;
  const auto n_vertices = static_cast<int>(soup.vertices.size());
  const auto n_faces = static_cast<int>(soup.triangles.size());
  for (const AnchorSpec& anchor : anchors.anchors) {
    if (const auto* vertex = std::get_if<AnchorVertex>(&anchor.location)) {
      if (vertex->index >= 0 && vertex->index < n_vertices) landmarks.push_back({anchor.name, soup.vertices[vertex->index]});
    } else if (const auto* point = std::get_if<AnchorPosition>(&anchor.location)) {
      landmarks.push_back({anchor.name, point->point});
    } else if (const auto* on_face = std::get_if<SurfacePoint>(&anchor.location)) {
      if (on_face->face < 0 || on_face->face >= n_faces) continue;
      const auto& t = soup.triangles[on_face->face];
      landmarks.push_back({anchor.name, on_face->bary[0] * soup.vertices[t[0]] + on_face->bary[1] * soup.vertices[t[1]] +
                                            on_face->bary[2] * soup.vertices[t[2]]});
    }
  }
  return landmarks;
}

namespace {

// --intake strict: the file as it is. Degenerate triangles are common in STL exports and the intake
// drops them, so a refusal for them leads with their count and that fix.
LoadedMesh load_strictly(const std::filesystem::path& path, TriangleSoup soup) {
  MeshReport report = validate_soup(soup);
  const auto first = std::find_if(report.problems.begin(), report.problems.end(),
                                  [](const Problem& p) { return p.kind == ProblemKind::DegenerateFace; });
  if (report.usable || first == report.problems.end())
    return load_validated_soup(path, std::move(soup), std::move(report));
  const std::size_t count = report.degenerate_faces.size();
  const std::string prefix = soup.source + ": ";
  throw InputError(
      prefix + std::to_string(count) + (count == 1 ? " degenerate face" : " degenerate faces") +
      " (zero area, or corners at one position; the first: " + first->message.substr(prefix.size()) +
      "): the intake drops them: leave out --intake strict, or delete them in a mesh editor");
}

}  // namespace

LoadedMesh load_scan_soup(const std::filesystem::path& path, TriangleSoup soup, const AnchorSet& anchors,
                          const IntakeSettings& settings) {
  if (settings.mode == IntakeMode::Strict) return load_strictly(path, std::move(soup));
  MeshReport report = validate_soup(soup);
  // A usable file of genus > 0 goes through the intake too: its handles are cut (step 4).
  if (report.usable && report.genus.value_or(0) == 0)
    return load_validated_soup(path, std::move(soup), std::move(report));
  const auto file_vertices = static_cast<int>(soup.vertices.size());
  const auto file_faces = static_cast<int>(soup.triangles.size());
  PreparedScan prepared = prepare_scan(soup, landmarks_on_file(anchors, soup), settings);
  LoadedMesh loaded;
  try {
    loaded = load_soup(path, std::move(prepared.soup));
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + " (after the intake: " + std::to_string(prepared.record.describe().size()) +
                     " kinds of repair; --intake strict shows the file's own problems)");
  }
  // Compose the loader's order (outward flip, pinch copies) with the intake's renumbering.
  FileOrder& order = loaded.file_order;
  const int mesh_vertices = static_cast<int>(loaded.mesh.n_vertices());
  std::vector<int> vertex_source(static_cast<std::size_t>(mesh_vertices));
  for (int v = 0; v < mesh_vertices; ++v) vertex_source[v] = prepared.vertex_source[order.file_vertex(v)];
  for (std::size_t f = 0; f < order.reversed.size(); ++f)
    order.reversed[f] = order.reversed[f] != prepared.reversed[f];
  order.copy_of.clear();
  order.vertex_source = std::move(vertex_source);
  order.face_source = std::move(prepared.face_source);
  order.file_vertices = file_vertices;
  order.file_faces = file_faces;
  order.mesh_face_of_file = std::move(prepared.prepared_face_of_file);
  order.mesh_vertex_of_file = std::move(prepared.prepared_vertex_of_file);
  loaded.intake = std::move(prepared.record);
  return loaded;
}

LoadedMesh load_scan(const std::filesystem::path& path, const AnchorSet& anchors, const IntakeSettings& settings) {
  return load_scan_soup(path, read_triangle_soup(path), anchors, settings);
}

}  // namespace xparam
