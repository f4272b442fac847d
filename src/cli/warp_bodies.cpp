#include "cli/warp_bodies.h"

#include "batch/batch_driver.h"
#include "batch/target_reload.h"

#include <tbb/parallel_for.h>

namespace xparam::cli {
namespace {

TriangleSoup soup_of(const LoadedMesh& loaded, const std::string& source) {
  TriangleSoup soup;
  soup.source = source;
  for (const VertexHandle v : loaded.mesh.vertices()) soup.vertices.push_back(position(loaded.mesh, v));
  soup.triangles = triangles_of(loaded.mesh);
  return soup;
}

}  // namespace

std::vector<WarpBody> attach_surfaces(const ArchiveReader& reader, std::vector<WarpTarget>& images,
                                      const std::filesystem::path& search_folder) {
  std::vector<WarpBody> bodies(images.size());
  tbb::parallel_for(std::size_t{0}, images.size(), [&](std::size_t i) {
    const ArchiveTargetSummary& target = reader.targets()[*reader.find(images[i].name)];
    const ReloadedTarget reloaded = reload_target(target, recorded_intake(target.options_json), search_folder);
    if (!reloaded.loaded) {
      bodies[i].fallback = reloaded.explanation;
      return;
    }
    bodies[i].surface_file = reloaded.mesh_file.string();
    images[i].surface = soup_of(*reloaded.loaded, bodies[i].surface_file);
  });
  return bodies;
}

}  // namespace xparam::cli
