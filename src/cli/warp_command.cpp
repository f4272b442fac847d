// `xparam warp --archive A.h5 --garment G.obj --out DIR|OUT.h5`: a garment made for the template,
// warped onto the targets of an archive through their maps.
#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/text_format.h"
#include "cli/unknown_target.h"
#include "cli/warp_bodies.h"
#include "cli/warp_report.h"

#include "core/errors.h"
#include "core/version.h"
#include "io/archive_lock.h"
#include "io/archive_reader.h"
#include "io/garment_obj.h"
#include "io/output_paths.h"
#include "io/text_file.h"
#include "io/warp_archive.h"
#include "warp/garment_warp.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace xparam::cli {
namespace {

namespace fs = std::filesystem;

struct WarpOptions {
  std::string archive;
  std::string garment;
  std::vector<std::string> targets;  ///< --target; empty: every target of the archive
  std::string out;                   ///< a folder, or a file ending in .h5
  std::string summary;               ///< --summary; default DIR/summary.json in folder mode
  std::string targets_folder;        ///< --targets: where moved target files are looked for by name
  std::optional<double> clearance;   ///< --clearance E
  std::string frame = "gradient";    ///< --frame
  int threads = tbb::info::default_concurrency();
  bool force = false;
  bool quiet = false;
};

[[noreturn]] void exit_with(int code, const std::string& message) {
  std::cerr << "xparam warp: " << message << "\n";
  throw CLI::RuntimeError(code);
}

bool is_h5(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".h5";
}

// The archive rows to warp: every target, or those --target names (each must exist).
std::vector<std::size_t> chosen_rows(const ArchiveReader& reader, const WarpOptions& options) {
  std::vector<std::size_t> rows;
  if (options.targets.empty()) {
    for (std::size_t row = 0; row < reader.targets().size(); ++row) rows.push_back(row);
    return rows;
  }
  for (const std::string& name : options.targets) {
    const std::optional<std::size_t> row = reader.find(name);
    if (!row) refuse_unknown_target("warp", reader, name, true);
    if (std::find(rows.begin(), rows.end(), *row) == rows.end()) rows.push_back(*row);
  }
  std::sort(rows.begin(), rows.end());  // the archive's order, whatever order they were named in
  return rows;
}

// Every file the run writes, checked before any work; an existing one needs --force.
std::vector<fs::path> outputs_of(const WarpOptions& options, const std::vector<std::string>& names) {
  std::vector<fs::path> files;
  if (is_h5(options.out)) {
    files.push_back(options.out);
  } else {
    for (const std::string& name : names) files.push_back(fs::path(options.out) / (name + ".obj"));
  }
  if (!options.summary.empty()) files.push_back(options.summary);
  return files;
}

// `files` are checked for existence; `options.summary` for writability when it is outside --out
// (the default one is inside the folder, which may not exist yet).
void check_outputs(const WarpOptions& options, const std::vector<fs::path>& files) {
  try {
    if (is_h5(options.out)) {
      check_writable_file(options.out, "--out");
    } else {
      check_writable_directory(options.out, "--out");
    }
    if (!options.summary.empty()) check_writable_file(options.summary, "--summary");
  } catch (const InputError& e) {
    exit_with(kExitFatal, e.what());
  }
  if (options.force) return;
  std::vector<std::string> existing;
  for (const fs::path& file : files) {
    if (fs::exists(file)) existing.push_back(file.string());
  }
  if (existing.empty()) return;
  std::string list = existing.front();
  if (existing.size() > 1) list += " (and " + std::to_string(existing.size() - 1) + " more)";
  exit_with(kExitUsage, list + " already exist" + (existing.size() == 1 ? "s" : "") +
                            "; give --force to replace the outputs of an earlier warp, or another --out");
}

TriangleSoup template_soup(const ArchiveReader& reader) {
  const TemplateRecord t = reader.read_template();
  TriangleSoup soup;
  soup.source = reader.path().string() + ":/template";
  for (Eigen::Index v = 0; v < t.vertices.rows(); ++v) soup.vertices.emplace_back(t.vertices.row(v).transpose());
  for (Eigen::Index f = 0; f < t.faces.rows(); ++f) soup.triangles.push_back({t.faces(f, 0), t.faces(f, 1), t.faces(f, 2)});
  return soup;
}

// The targets to warp onto: each one's remesh on the template's faces. A target that failed
// in the archive has no map; it is reported as failed here too.
std::vector<WarpTarget> read_images(const ArchiveReader& reader, const TriangleSoup& body_template,
                                    const std::vector<std::size_t>& rows, std::vector<WarpedGarment>& unmapped) {
  std::vector<WarpTarget> images;
  for (const std::size_t row : rows) {
    const ArchiveTargetSummary& summary = reader.targets()[row];
    if (!summary.ok) {
      WarpedGarment failed;
      failed.name = summary.name;
      failed.error = "failed in the archive, so it has no map (" + summary.error + ")";
      unmapped.push_back(std::move(failed));
      continue;
    }
    const TargetRecord record = reader.read_target(row);
    if (record.remesh_vertices.rows() != static_cast<Eigen::Index>(body_template.vertices.size()))
      throw ArchiveError(reader.path().string() + ": target " + summary.name + " has " +
                         std::to_string(record.remesh_vertices.rows()) + " remesh vertices but the template " +
                         std::to_string(body_template.vertices.size()) + "; the archive is damaged (xparam inspect --verify)");
    WarpTarget image{summary.name, body_template};
    image.body.source = reader.path().string() + ": target " + summary.name;
    for (Eigen::Index v = 0; v < record.remesh_vertices.rows(); ++v)
      image.body.vertices[v] = record.remesh_vertices.row(v).transpose();
    images.push_back(std::move(image));
  }
  return images;
}

nlohmann::ordered_json options_json(const WarpOptions& options, const WarpSettings& settings) {
  nlohmann::ordered_json json;
  json["frame"] = options.frame;
  if (settings.clearance) {
    json["clearance"] = settings.clearance->clearance;
    json["smoothing_sweeps"] = settings.clearance->smoothing_sweeps;
    json["rounds"] = settings.clearance->rounds;
    json["final_passes"] = settings.clearance->final_passes;
  } else {
    json["clearance"] = nullptr;
  }
  return json;
}

WarpArchiveRecord warp_record(const WarpOptions& options, const std::string& settings_json, const GarmentObj& garment,
                              const GarmentBinding& binding, const std::vector<WarpedGarment>& warped,
                              const std::map<std::string, WarpBody>& bodies) {
  WarpArchiveRecord record;
  record.archive_file = options.archive;
  record.garment_file = options.garment;
  record.options_json = settings_json;
  record.xparam_version = kVersion;
  record.rest_vertices = garment.mesh.vertices;
  record.triangles = garment.mesh.triangles;
  record.uvs = garment.uvs;
  record.triangle_uvs = garment.triangle_uvs;
  record.bound_face = binding.face;
  record.bound_bary = binding.bary;
  record.bound_offset = binding.offset;
  record.figure_names = warp_figure_names();
  const std::size_t n = garment.mesh.vertices.size();
  const Eigen::Vector3d nan_point = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (const WarpedGarment& g : warped) {
    record.target_names.push_back(g.name);
    record.target_errors.push_back(g.error);
    const bool ok = g.error.empty();
    record.target_bodies.push_back(ok ? (g.against_surface ? "surface" : "remesh") : "");
    record.target_body_notes.push_back(ok ? body_note(bodies.at(g.name)) : "");
    record.warped_vertices.push_back(ok ? g.vertices : std::vector<Eigen::Vector3d>(n, nan_point));
    std::vector<double> moves(n, ok ? 0.0 : std::numeric_limits<double>::quiet_NaN());
    if (ok && g.clearance) moves = g.clearance->displacement;
    record.clearance_moves.push_back(std::move(moves));
    record.figures.push_back(warp_figures(g));
  }
  return record;
}

int run_warp(const WarpOptions& options) {
  const bool to_h5 = is_h5(options.out);
  std::optional<ArchiveReader> reader;
  try {
    reader.emplace(options.archive);
  } catch (const ArchiveError& e) {
    exit_with(kExitFatal, e.what());
  }
  if (reader->is_part())
    usage_error("warp", options.archive + " is a part file of a batch run, not an archive; give the archive");
  const std::vector<std::size_t> rows = chosen_rows(*reader, options);
  std::vector<std::string> names;
  for (const std::size_t row : rows) names.push_back(reader->targets()[row].name);
  WarpOptions resolved = options;
  if (!to_h5 && resolved.summary.empty()) resolved.summary = (fs::path(options.out) / "summary.json").string();
  check_outputs(options, outputs_of(resolved, names));
  std::optional<ArchiveLock> lock;  // one writer of OUT.h5 at a time
  if (to_h5) lock.emplace(options.out);

  WarpSettings settings;
  if (options.clearance) settings.clearance = ClearanceSettings{*options.clearance};
  const BindSettings bind{options.frame == "rigid" ? OffsetFrame::rigid : OffsetFrame::gradient};

  const GarmentObj garment = read_garment_obj(options.garment);
  check_rest_garment(garment.mesh);
  const TriangleSoup body_template = template_soup(*reader);
  std::vector<WarpedGarment> unmapped;
  std::vector<WarpTarget> images = read_images(*reader, body_template, rows, unmapped);
  for (const WarpedGarment& g : unmapped) std::cerr << "xparam warp: " << g.name << ": " << g.error << "\n";

  tbb::task_arena arena(options.threads);
  GarmentBinding binding;
  std::vector<WarpedGarment> warped;
  std::map<std::string, WarpBody> bodies;
  std::mutex print;
  std::size_t done = 0;
  std::vector<WarpBody> found(images.size());
  arena.execute([&] {
    binding = bind_garment(body_template, garment.mesh.vertices, bind);
    if (!options.quiet)
      std::cerr << "bound " << garment.mesh.vertices.size() << " garment vertices to the template (farthest "
                << figure(binding.max_distance) << " off it); warping onto " << plural(images.size(), "target")
                << "\n";
    warped = warp_garment_onto(garment.mesh, binding, images, settings, [&](std::size_t, const WarpedGarment& g) {
      const std::lock_guard<std::mutex> guard(print);
      ++done;
      if (!options.quiet) std::cerr << warp_progress_line(done, images.size(), g) << "\n";
    }, [&](std::size_t i) { return load_surface(*reader, images[i].name, options.targets_folder, found[i]); });
  });
  for (std::size_t i = 0; i < images.size(); ++i) {
    bodies[images[i].name] = found[i];
    if (found[i].surface_file.empty() && !found[i].fallback.empty())
      std::cerr << "xparam warp: warning: " << images[i].name
                << ": penetration and clearance measured against its remesh, not its own surface: " << found[i].fallback
                << (options.targets_folder.empty() ? " (give --targets DIR, the folder now holding the batch's target files)"
                                                   : "")
                << "\n";
  }
  // Targets without a map, in the archive's order among the others.
  warped.insert(warped.end(), unmapped.begin(), unmapped.end());
  std::sort(warped.begin(), warped.end(), [](const WarpedGarment& a, const WarpedGarment& b) { return a.name < b.name; });

  const nlohmann::ordered_json settings_json = options_json(options, settings);
  nlohmann::ordered_json summary;
  summary["archive"] = options.archive;
  summary["garment"] = options.garment;
  summary["garment_vertices"] = garment.mesh.vertices.size();
  summary["garment_triangles"] = garment.mesh.triangles.size();
  summary["bind_max_distance"] = binding.max_distance;
  summary["options"] = settings_json;
  summary["targets"] = nlohmann::ordered_json::array();
  try {
    if (to_h5) write_warp_archive(options.out, warp_record(options, settings_json.dump(), garment, binding, warped, bodies));
    else fs::create_directories(options.out);
    for (const WarpedGarment& g : warped) {
      std::string obj;
      if (!to_h5 && g.error.empty()) {
        obj = (fs::path(options.out) / (g.name + ".obj")).string();
        write_garment_obj(obj, garment, g.vertices);
      }
      summary["targets"].push_back(warp_target_json(g, obj, g.error.empty() ? bodies.at(g.name) : WarpBody{}));
    }
    if (!resolved.summary.empty()) write_text_atomically(resolved.summary, summary.dump(2) + "\n");
  } catch (const Error& e) {
    exit_with(kExitFatal, e.what());
  }
  if (!options.quiet) print_warp_table(warped, std::cout);
  const auto failed = std::count_if(warped.begin(), warped.end(), [](const WarpedGarment& g) { return !g.error.empty(); });
  if (!options.quiet)
    std::cerr << "warped " << plural(warped.size() - static_cast<std::size_t>(failed), "target") << ", "
              << failed << " failed; " << (to_h5 ? "file " : "folder ") << options.out << "\n";
  return failed > 0 ? kExitSomeFailed : 0;
}

}  // namespace

void add_warp_command(CLI::App& app) {
  auto options = std::make_shared<WarpOptions>();
  CLI::App* warp = app.add_subcommand(
      "warp", "Warp a garment made for the template onto the targets of an archive through their maps: bound to "
              "the template once, placed on every target's remesh, optionally pushed out of the body; OBJ per target "
              "(vertex order, faces and UVs kept) and figures (penetration, edge-length ratio, stretch).");
  warp->add_option("--archive", options->archive, "Archive written by xparam batch (.h5)")
      ->required()
      ->check(CLI::ExistingFile);
  warp->add_option("--garment", options->garment, "Garment OBJ made for the archive's template (triangles, v/vt)")
      ->required()
      ->check(CLI::ExistingFile);
  warp->add_option("--target", options->targets, "Warp onto this target only (repeatable; default: every target)");
  warp->add_option("--out", options->out,
                   "A folder (NAME.obj per target and summary.json) or a file ending in .h5 (everything in one "
                   "HDF5 file, schemas/warp_archive.md)")
      ->required();
  warp->add_option("--summary", options->summary, "Summary JSON (default in folder mode: OUT/summary.json)");
  warp->add_option("--targets", options->targets_folder,
                   "Folder holding the batch's target mesh and anchor files, looked in by file name when one is not "
                   "where the archive recorded it (moved); penetration and clearance are measured against a target's "
                   "own surface when its files are found unchanged, else against its remesh")
      ->check(CLI::ExistingDirectory);
  warp->add_option("--clearance", options->clearance,
                   "Push garment vertices inside the body or closer than E to it out to E, body units (e.g. 0.002 "
                   "for 2 mm on metres)")
      ->check(at_least(0.0, false));
  warp->add_option("--frame", options->frame,
                   "How offsets follow the body: gradient (the face's deformation gradient, Sumner-Popovic: a scaled "
                   "body scales the gap) or rigid (offsets keep their length)")
      ->check(CLI::IsMember({"gradient", "rigid"}))
      ->capture_default_str();
  warp->add_option("-j,--threads", options->threads, "Targets warped in parallel (default: the cores)")
      ->check(at_least(1));
  warp->add_flag("--force", options->force, "Replace the outputs of an earlier warp");
  warp->add_flag("-q,--quiet", options->quiet, "No progress and no table (errors still)");
  warp->footer(
      "Exit status: 0 every chosen target warped, 2 some could not be (failed in the archive), 1 usage error (also: "
      "an output exists and --force is not given), 3 fatal (unreadable garment or archive, unwritable output).\n"
      "Example: xparam warp --archive sample.h5 --garment tests/data/garment_torso.obj --clearance 0.002 --out "
      "warped/");
  warp->callback([options] {
    int status = 0;
    try {
      status = run_warp(*options);
    } catch (const InputError& e) {
      exit_with(kExitFatal, e.what());
    } catch (const ArchiveError& e) {
      exit_with(kExitFatal, e.what());
    }
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

}  // namespace xparam::cli
