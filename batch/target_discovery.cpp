#include "batch/target_discovery.h"

#include "core/errors.h"
#include "io/anchor_reader.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <map>
#include <string_view>
#include <system_error>

namespace xparam {
namespace {

enum class FileRole { Mesh, Anchors, GroundTruth };

// Suffixes of the folder convention, matched case-insensitively at the end of a file name.
struct Suffix {
  std::string_view text;
  FileRole role;
};
constexpr std::array<Suffix, 8> kSuffixes = {{{".anchors.json", FileRole::Anchors},
                                              {".anchors.txt", FileRole::Anchors},
                                              {".pp", FileRole::Anchors},
                                              {".gt.txt", FileRole::GroundTruth},
                                              {".obj", FileRole::Mesh},
                                              {".ply", FileRole::Mesh},
                                              {".off", FileRole::Mesh},
                                              {".stl", FileRole::Mesh}}};

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// The files found for one name in a folder, each list sorted.
struct NamedFiles {
  std::vector<std::filesystem::path> meshes;
  std::vector<std::filesystem::path> anchors;
  std::filesystem::path ground_truth;
};

std::string join_file_names(const std::vector<std::filesystem::path>& files) {
  std::string text;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (i > 0) text += i + 1 == files.size() ? " and " : ", ";
    text += files[i].string();
  }
  return text;
}

void add_problem(TargetSpec& target, const std::string& problem) {
  if (!target.problem.empty()) target.problem += "; ";
  target.problem += problem;
}

// Target `name` of a folder from the files found for it; `anchors_beside`: its anchors are among
// them (the convention), so their absence or doubling is a problem.
TargetSpec target_from_files(const std::string& name, NamedFiles files, const std::filesystem::path& folder,
                             bool anchors_beside) {
  std::sort(files.meshes.begin(), files.meshes.end());
  std::sort(files.anchors.begin(), files.anchors.end());
  TargetSpec target;
  target.name = name;
  target.ground_truth = files.ground_truth;
  if (!files.meshes.empty()) target.mesh = files.meshes.front();
  if (!files.anchors.empty()) target.anchors = files.anchors.front();

  if (files.meshes.size() > 1)
    add_problem(target, "two meshes for target \"" + name + "\": " + join_file_names(files.meshes));
  if (files.meshes.empty())
    add_problem(target, "no mesh for target \"" + name + "\" in " + folder.string() + " (expected " + name +
                            ".obj, .ply, .off or .stl beside " +
                            (files.anchors.empty() ? files.ground_truth : files.anchors.front()).string() + ")");
  if (!anchors_beside) return target;
  if (files.anchors.size() > 1)
    add_problem(target, "two anchor files for target \"" + name + "\": " + join_file_names(files.anchors));
  if (files.anchors.empty())
    add_problem(target, "no anchors for " + target.mesh.string() + " (expected " + name + ".anchors.json, " +
                            name + ".anchors.txt or " + name + ".pp beside it)");
  return target;
}

// The anchor file of mesh NAME through a non-default lookup: the pattern's file in its folder, or
// the convention's names there.
void look_up_anchors(TargetSpec& target, const std::filesystem::path& folder, const AnchorLookup& lookup) {
  const std::filesystem::path where = lookup.folder.empty() ? folder : lookup.folder;
  std::vector<std::filesystem::path> candidates;
  if (!lookup.pattern.empty()) {
    std::string file = lookup.pattern;
    for (std::size_t at = file.find("{stem}"); at != std::string::npos; at = file.find("{stem}", at + target.name.size()))
      file.replace(at, 6, target.name);
    candidates.push_back(where / file);
  } else {
    for (const char* suffix : {".anchors.json", ".anchors.txt", ".pp"}) candidates.push_back(where / (target.name + suffix));
  }
  std::vector<std::filesystem::path> found;
  std::error_code error;
  for (const std::filesystem::path& candidate : candidates)
    if (std::filesystem::is_regular_file(candidate, error)) found.push_back(candidate);
  if (found.size() > 1)
    add_problem(target, "two anchor files for target \"" + target.name + "\": " + join_file_names(found));
  if (found.empty())
    add_problem(target, "no anchors for " + target.mesh.string() + " (expected " + join_file_names(candidates) +
                            (lookup.pattern.empty() ? "" : ", from --anchors-pattern '" + lookup.pattern + "'") + ")");
  else
    target.anchors = found.front();
}

std::vector<TargetSpec> discover_folder(const std::filesystem::path& folder, const AnchorLookup& lookup) {
  std::map<std::string, NamedFiles> by_name;
  std::error_code error;
  std::filesystem::directory_iterator it(folder, error);
  if (error) throw InputError(folder.string() + ": cannot list the folder: " + error.message());
  for (; it != std::filesystem::directory_iterator(); it.increment(error)) {
    if (error) throw InputError(folder.string() + ": cannot list the folder: " + error.message());
    if (!it->is_regular_file()) continue;
    const std::string file_name = it->path().filename().string();
    const std::string lowered = lower(file_name);
    for (const Suffix& suffix : kSuffixes) {
      if (lowered.size() <= suffix.text.size() || !lowered.ends_with(suffix.text)) continue;
      NamedFiles& files = by_name[file_name.substr(0, file_name.size() - suffix.text.size())];
      const std::filesystem::path path = folder / file_name;
      if (suffix.role == FileRole::Anchors && !lookup.is_default()) break;  // anchors are looked up elsewhere
      switch (suffix.role) {
        case FileRole::Mesh: files.meshes.push_back(path); break;
        case FileRole::Anchors: files.anchors.push_back(path); break;
        case FileRole::GroundTruth: files.ground_truth = path; break;
      }
      break;
    }
  }
  std::vector<TargetSpec> targets;
  for (auto& [name, files] : by_name) {
    // A lone ground-truth file is not a target: it only describes one.
    if (files.meshes.empty() && files.anchors.empty()) continue;
    if (lookup.is_default()) {
      targets.push_back(target_from_files(name, std::move(files), folder, true));
      continue;
    }
    if (files.meshes.empty()) continue;  // a ground truth alone
    TargetSpec target = target_from_files(name, std::move(files), folder, false);
    look_up_anchors(target, folder, lookup);
    targets.push_back(std::move(target));
  }
  if (targets.empty())
    throw InputError(folder.string() + ": no target meshes (.obj, .ply, .off or .stl) in the folder; --targets takes "
                     "a folder of meshes with their anchor files, or a manifest (README, \"Your own data\")");
  return targets;  // std::map iteration: already sorted by name
}

std::filesystem::path relative_to(const std::filesystem::path& manifest, const std::string& file) {
  const std::filesystem::path path(file);
  return path.is_absolute() ? path : manifest.parent_path() / path;
}

}  // namespace

std::vector<TargetSpec> read_manifest(const std::filesystem::path& manifest) {
  const std::string source = manifest.string();
  const LocatedJson json = parse_located_json(read_text_file(manifest), source);
  if (!json.value.is_array())
    throw InputError(source + ": a manifest is a JSON array of {\"name\", \"mesh\", \"anchors\"} objects");

  std::map<std::string, std::size_t> first_entry;  // name -> index into targets
  std::vector<TargetSpec> targets;
  for (std::size_t i = 0; i < json.value.size(); ++i) {
    std::string pointer = "/";  // built by appending: GCC 12 misreports "literal" + std::string&& (-Wrestrict)
    pointer += std::to_string(i);
    const std::string where = source + ":" + std::to_string(json.line(pointer)) + ": entry " + std::to_string(i);
    const auto& entry = json.value[i];
    if (!entry.is_object()) throw InputError(where + ": not an object");
    for (const auto& member : entry.items())
      if (member.key() != "name" && member.key() != "mesh" && member.key() != "anchors" &&
          member.key() != "ground_truth")
        throw InputError(where + ": unknown member \"" + member.key() +
                         "\" (expected name, mesh, anchors, ground_truth)");
    const auto text = [&](const char* key, bool required) -> std::string {
      if (!entry.contains(key)) {
        if (required) throw InputError(where + ": missing \"" + std::string(key) + "\"");
        return {};
      }
      if (!entry[key].is_string() || entry[key].get<std::string>().empty())
        throw InputError(where + ": \"" + std::string(key) + "\" must be a non-empty string");
      return entry[key].get<std::string>();
    };

    TargetSpec target;
    target.name = text("name", true);
    target.mesh = relative_to(manifest, text("mesh", true));
    const std::string anchors = text("anchors", false);
    const std::string ground_truth = text("ground_truth", false);
    if (!anchors.empty()) target.anchors = relative_to(manifest, anchors);
    if (!ground_truth.empty()) target.ground_truth = relative_to(manifest, ground_truth);
    if (anchors.empty()) add_problem(target, "no anchors for " + target.mesh.string() + " (" + where + ")");

    const auto [it, inserted] = first_entry.emplace(target.name, targets.size());
    if (inserted) {
      targets.push_back(std::move(target));
    } else {
      add_problem(targets[it->second], "target \"" + target.name + "\" listed twice in " + source +
                                           " (another entry: " + where + ", mesh " + target.mesh.string() + ")");
    }
  }
  std::sort(targets.begin(), targets.end(), [](const TargetSpec& a, const TargetSpec& b) { return a.name < b.name; });
  return targets;
}

std::vector<TargetSpec> discover_targets(const std::filesystem::path& source, const AnchorLookup& anchors) {
  std::error_code error;
  std::filesystem::path manifest = source;
  if (!std::filesystem::is_regular_file(source, error)) {
    if (!std::filesystem::is_directory(source, error))
      throw InputError(source.string() + ": no such folder or manifest file");
    manifest = source / kManifestFileName;
  }
  if (std::filesystem::is_regular_file(manifest, error)) {
    if (!anchors.is_default())
      throw InputError(manifest.string() + ": a manifest names each target's anchors; --anchors-dir and "
                       "--anchors-pattern apply to a folder of meshes");
    return read_manifest(manifest);
  }
  if (!anchors.folder.empty() && !std::filesystem::is_directory(anchors.folder, error))
    throw InputError("--anchors-dir " + anchors.folder.string() + ": no such folder");
  if (!anchors.pattern.empty() &&
      (anchors.pattern.find("{stem}") == std::string::npos || anchors.pattern.find('/') != std::string::npos))
    throw InputError("--anchors-pattern '" + anchors.pattern +
                     "': a file name with {stem} for the mesh's name without extension, e.g. "
                     "'{stem}_landmarks.json' (no '/': the folder is --anchors-dir)");
  return discover_folder(source, anchors);
}

Shard parse_shard(const std::string& text) {
  const auto malformed = [&](const std::string& why) {
    return InputError("--shard " + text + ": " + why + " (expected i/N with 0 <= i < N, e.g. 0/4)");
  };
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) throw malformed("no '/'");
  const auto parse = [&](std::string_view digits) {
    int value = 0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || value < 0)
      throw malformed(std::string(digits) + " is not a non-negative integer");
    return value;
  };
  const std::string_view view(text);
  Shard shard{parse(view.substr(0, slash)), parse(view.substr(slash + 1))};
  if (shard.count < 1) throw malformed("N must be at least 1");
  if (shard.index >= shard.count) throw malformed("i must be below N");
  return shard;
}

std::vector<TargetSpec> select_shard(const std::vector<TargetSpec>& targets, const Shard& shard) {
  XP_ASSERT(shard.count >= 1 && shard.index >= 0 && shard.index < shard.count);
  std::vector<TargetSpec> selected;
  for (std::size_t i = static_cast<std::size_t>(shard.index); i < targets.size();
       i += static_cast<std::size_t>(shard.count))
    selected.push_back(targets[i]);
  return selected;
}

}  // namespace xparam
