// `xparam inspect ARCHIVE [--json]`: what an archive holds, one line per target.
#include "cli/commands.h"

#include "core/errors.h"
#include "io/archive_reader.h"
#include "io/archive_verify.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

namespace xparam::cli {
namespace {

struct InspectOptions {
  std::string archive;
  bool json = false;
  bool verify = false;
};

// NaN (no value) prints as "-".
std::string number(double value) {
  if (std::isnan(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  return text;
}

std::string count(int value) { return value < 0 ? "-" : std::to_string(value); }

// A column `width` wide (separator included), and never without a space after it.
std::string padded(std::string text, std::size_t width) {
  text.append(text.size() < width ? width - text.size() : 1, ' ');
  return text;
}

nlohmann::json target_json(const ArchiveTargetSummary& t) {
  nlohmann::json seconds;
  for (std::size_t s = 0; s < kTimingStages.size(); ++s) seconds[kTimingStages[s]] = t.seconds[s];
  const TargetMetrics& m = t.metrics;
  // nlohmann writes NaN as null: "no value".
  return {{"name", t.name},
          {"status", t.ok ? "ok" : "failed"},
          {"error", t.error},
          {"mesh_file", t.mesh_file},
          {"anchors_file", t.anchors_file},
          {"mesh_sha256", t.mesh_sha256},
          {"anchors_sha256", t.anchors_sha256},
          {"metrics",
           {{"E_L2", m.e_l2},
            {"E_ang", m.e_ang},
            {"stretch_max_sv", m.stretch_max_sv},
            {"flipped_faces", m.flipped_faces},
            {"area_ratio", m.area_ratio},
            {"gt_error", m.gt_error},
            {"swaps", m.swaps},
            {"merges", m.merges},
            {"released_anchors", m.released_anchors},
            {"dropped_faces", m.dropped_faces},
            {"dropped_area", m.dropped_area},
            {"holes_filled", m.holes_filled},
            {"filled_area", m.filled_area},
            {"on_filled_vertices", m.on_filled_vertices},
            {"max_distance_to_scan", m.max_distance_to_scan},
            {"file_faces", m.file_faces}}},
          {"seconds", seconds}};
}

void run_inspect(const InspectOptions& options) {
  if (options.verify) {
    const ArchiveVerification verified = verify_archive(options.archive);
    std::cerr << options.archive << ": verified: " << verified.datasets << " datasets (" << verified.bytes
              << " bytes) read in full, every checksum matches\n";
  }
  const ArchiveReader reader(options.archive);
  const TemplateRecord t = reader.read_template();
  const ArchiveProvenance& p = reader.provenance();
  std::size_t ok = 0;
  for (const ArchiveTargetSummary& target : reader.targets()) ok += target.ok;
  const std::size_t failed = reader.targets().size() - ok;

  if (options.json) {
    nlohmann::json out;
    out["archive"] = options.archive;
    out["schema_version"] = reader.schema_version();
    out["xparam_version"] = p.xparam_version;
    out["git_revision"] = p.git_revision;
    const nlohmann::json parsed = nlohmann::json::parse(p.options_json, nullptr, false);
    out["options"] = parsed.is_discarded() ? nlohmann::json(p.options_json) : parsed;
    out["template"] = {{"mesh_file", t.mesh_file},
                       {"mesh_sha256", t.mesh_sha256},
                       {"vertices", reader.n_vertices()},
                       {"faces", reader.n_faces()},
                       {"anchors", t.anchor_names.size()},
                       {"curves", t.curves.size()}};
    out["ok"] = ok;
    out["failed"] = failed;
    out["targets"] = nlohmann::json::array();
    for (const ArchiveTargetSummary& target : reader.targets()) out["targets"].push_back(target_json(target));
    std::cout << out.dump(2) << "\n";
    return;
  }

  std::cout << options.archive << ": xparam archive, schema " << reader.schema_version() << ", written by xparam "
            << p.xparam_version << " (" << p.git_revision << ")\n"
            << "options: " << p.options_json << "\n"
            << "template: " << t.mesh_file << ", " << reader.n_vertices() << " vertices, " << reader.n_faces()
            << " faces, " << t.anchor_names.size() << " anchors, " << t.curves.size() << " curves\n"
            << reader.targets().size() << " targets: " << ok << " ok, " << failed << " failed\n";
  if (reader.targets().empty()) return;
  std::size_t width = 4;
  for (const ArchiveTargetSummary& target : reader.targets()) width = std::max(width, target.name.size() + 2);
  std::cout << padded("name", width) << "status  " << padded("E_L2", 10) << padded("E_ang", 10)
            << padded("flipped", 8) << padded("released", 9) << padded("gt_error", 10) << padded("seconds", 9) << "error\n";
  for (const ArchiveTargetSummary& target : reader.targets()) {
    const TargetMetrics& m = target.metrics;
    std::cout << padded(target.name, width) << padded(target.ok ? "ok" : "failed", 8)
              << padded(number(m.e_l2), 10) << padded(number(m.e_ang), 10) << padded(count(m.flipped_faces), 8)
              << padded(count(m.released_anchors), 9)
              << padded(number(m.gt_error), 10) << padded(number(target.seconds.back()), 9) << target.error << "\n";
  }
}

}  // namespace

void add_inspect_command(CLI::App& app) {
  auto options = std::make_shared<InspectOptions>();
  CLI::App* inspect = app.add_subcommand(
      "inspect", "List what an xparam archive holds: provenance, template, and per target its status, "
                 "metrics (E_L2, E_ang, flipped faces, released anchors, ground-truth error), seconds and error text.");
  inspect->add_option("archive", options->archive, "Archive (.h5) written by xparam batch or merge")
      ->required()
      ->check(CLI::ExistingFile);
  inspect->add_flag("--json", options->json, "Print one JSON object (NaN as null) instead of a table");
  inspect->add_flag("--verify", options->verify,
                    "First read every dataset in full, checking every chunk's checksum (exit 3 naming the first "
                    "damaged dataset)");
  inspect->callback([options] { run_inspect(*options); });
}

}  // namespace xparam::cli
