#include "cli/warp_bodies.h"

#include "batch/batch_driver.h"
#include "batch/target_reload.h"
#include "core/mesh_builder.h"

namespace xparam::cli {

std::optional<TriangleSoup> load_surface(const ArchiveReader& reader, const std::string& name,
                                         const std::filesystem::path& search_folder, WarpBody& body) {
  const ArchiveTargetSummary& target = reader.targets()[*reader.find(name)];
  const ReloadedTarget reloaded = reload_target(target, recorded_intake(target.options_json), search_folder);
  if (!reloaded.loaded) {
    body.fallback = reloaded.explanation;
    return std::nullopt;
  }
  body.surface_file = reloaded.mesh_file.string();
  return soup_of(reloaded.loaded->mesh, body.surface_file);
}

}  // namespace xparam::cli
