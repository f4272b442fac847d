#include "batch/target_reload.h"

#include "core/errors.h"
#include "intake/scan_loader.h"
#include "io/anchor_reader.h"
#include "io/sha256.h"

#include <system_error>
#include <vector>

namespace xparam {
namespace {

namespace fs = std::filesystem;

// Where one recorded file is now: the first place holding the recorded bytes; else what is wrong.
struct Found {
  fs::path path;  // empty when not found with the recorded bytes
  ReloadProblem problem = ReloadProblem::none;
  std::string explanation;
};

Found find_recorded(const std::string& recorded, const std::string& sha256, const fs::path& search_folder,
                    const std::string& what) {
  std::vector<fs::path> places{recorded};
  if (!search_folder.empty()) places.push_back(search_folder / fs::path(recorded).filename());
  std::vector<fs::path> different;
  for (const fs::path& place : places) {
    std::error_code error;
    if (!fs::is_regular_file(place, error)) continue;
    if (sha256_file_hex_or_empty(place) == sha256) return {place, ReloadProblem::none, {}};
    different.push_back(place);
  }
  std::string looked = recorded;
  if (places.size() > 1) looked += " or " + places.back().string();
  if (different.empty()) return {{}, ReloadProblem::missing, "its " + what + " " + looked + " is missing"};
  return {{}, ReloadProblem::changed,
          "its " + what + " " + different.front().string() +
              " changed since the batch mapped it (its SHA-256 is not the recorded one)"};
}

}  // namespace

ReloadedTarget reload_target(const ArchiveTargetSummary& target, const IntakeSettings& intake,
                             const fs::path& search_folder) {
  ReloadedTarget result;
  const Found mesh = find_recorded(target.mesh_file, target.mesh_sha256, search_folder, "mesh file");
  // The anchors choose the part the intake keeps, so they must be the batch's too.
  const Found anchors = mesh.path.empty()
                            ? Found{}
                            : find_recorded(target.anchors_file, target.anchors_sha256, search_folder, "anchor file");
  for (const Found* found : {&mesh, &anchors}) {
    if (found->problem == ReloadProblem::none) continue;
    result.problem = found->problem;
    result.explanation = found->explanation;
    return result;
  }
  try {
    result.loaded = load_scan(mesh.path, read_anchors(anchors.path), intake);
    result.mesh_file = mesh.path;
  } catch (const InputError& e) {
    result.problem = ReloadProblem::refused;
    result.explanation = std::string("its files could not be loaded as the batch loaded them: ") + e.what();
  }
  return result;
}

}  // namespace xparam
