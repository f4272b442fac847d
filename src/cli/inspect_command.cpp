// `xparam inspect ARCHIVE [--json]`: what an archive holds, one line per target.
#include "cli/commands.h"
#include "cli/diagnosis_text.h"
#include "cli/text_format.h"
#include "cli/unknown_target.h"

#include "batch/summary_json.h"

#include "core/errors.h"
#include "io/archive_reader.h"
#include "io/archive_verify.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

namespace xparam::cli {
namespace {

struct InspectOptions {
  std::string archive;
  std::string target;  ///< --target NAME: that target's diagnosis
  bool json = false;
  bool verify = false;
};

std::string count(int value) { return value < 0 ? "-" : std::to_string(value); }

// A column `width` wide (separator included), and never without a space after it.
std::string padded(std::string text, std::size_t width) {
  text.append(text.size() < width ? width - text.size() : 1, ' ');
  return text;
}

std::string status_of(const ArchiveTargetSummary& t) { return !t.ok ? "failed" : t.suspect ? "suspect" : "ok"; }

// The scan intake's repairs of a target, and where the map lands on surface it filled in.
void print_intake(const TargetMetrics& m, bool per_vertex_recorded) {
  std::cout << "  intake: " << plural(static_cast<std::size_t>(m.dropped_faces), "face")
            << " of loose parts dropped, " << plural(static_cast<std::size_t>(m.holes_filled), "hole")
            << " filled; template vertices on filled-in surface: " << m.on_filled_vertices;
  if (m.on_filled_vertices > 0)
    std::cout << ", at most " << figure(m.max_distance_to_scan) << " from the scan";
  std::cout << (per_vertex_recorded ? " (each vertex's: export --out FILE.ply, distance_to_scan)"
                                    : " (each vertex's distance is not recorded in a schema 4 archive)")
            << "\n";
}

// `inspect --target NAME`: the target's row, its verdict's reasons and its diagnosis.
void print_target(const ArchiveReader& reader, const std::string& name, bool json) {
  const std::optional<std::size_t> row = reader.find(name);
  if (!row) refuse_unknown_target("inspect", reader, name, false);
  const ArchiveTargetSummary& t = reader.targets()[*row];
  const nlohmann::ordered_json diagnosis =
      t.diagnosis.empty() ? nlohmann::ordered_json::object() : nlohmann::ordered_json::parse(t.diagnosis, nullptr, false);
  if (json) {
    nlohmann::ordered_json out = target_json(outcome_of(t), false, reader.measurement_names());
    out["diagnosis"] = diagnosis;
    std::cout << out.dump(2) << "\n";
    return;
  }
  const TargetMetrics& m = t.metrics;
  std::cout << t.name << ": " << status_of(t) << "\n  mesh " << t.mesh_file << ", anchors " << t.anchors_file << "\n";
  if (!t.ok) {
    std::cout << "  error: " << t.error << "\n";
    return;
  }
  std::cout << "  E_L2 " << figure(m.e_l2) << ", E_ang " << figure(m.e_ang) << ", folded faces " << count(m.flipped_faces)
            << " (" << count(m.strictly_folded_faces) << " by the strict count), area ratio " << figure(m.area_ratio)
            << ", released anchors " << count(m.released_anchors) << ", " << seconds_text(t.seconds.back()) << "\n";
  if (m.dropped_faces > 0 || m.holes_filled > 0) print_intake(m, reader.records_distance_to_scan());
  const std::vector<std::string>& names = reader.measurement_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    std::cout << (i == 0 ? "  measurements: " : ", ") << names[i] << " " << figure(t.measurements[i]) << " "
              << reader.measurement_units()[i] << (i + 1 == names.size() ? "\n" : "");
  print_diagnosis(diagnosis, std::cout);
}

void run_inspect(const InspectOptions& options) {
  if (options.verify) {
    const ArchiveVerification verified = verify_archive(options.archive);
    std::cerr << options.archive << ": verified: " << verified.datasets << " datasets (" << verified.bytes
              << " bytes) read in full, every checksum matches\n";
  }
  const ArchiveReader reader(options.archive);
  if (!options.target.empty()) return print_target(reader, options.target, options.json);
  const TemplateRecord t = reader.read_template();
  const ArchiveProvenance& p = reader.provenance();
  std::size_t ok = 0;
  std::size_t suspect = 0;
  for (const ArchiveTargetSummary& target : reader.targets()) {
    ok += target.ok && !target.suspect;
    suspect += target.suspect;
  }
  const std::size_t failed = reader.targets().size() - ok - suspect;

  if (options.json) {
    nlohmann::ordered_json out;
    out["archive"] = options.archive;
    out["schema_version"] = reader.schema_version();
    out["xparam_version"] = p.xparam_version;
    out["git_revision"] = p.git_revision;
    const nlohmann::ordered_json parsed = nlohmann::ordered_json::parse(p.options_json, nullptr, false);
    out["options"] = parsed.is_discarded() ? nlohmann::ordered_json(p.options_json) : parsed;
    out["template"] = {{"mesh_file", t.mesh_file},
                       {"mesh_sha256", t.mesh_sha256},
                       {"vertices", reader.n_vertices()},
                       {"faces", reader.n_faces()},
                       {"anchors", t.anchor_names.size()},
                       {"curves", t.curves.size()},
                       {"measurements_file", t.measurements_file}};
    nlohmann::ordered_json measured = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < t.measurement_names.size(); ++i)
      measured[t.measurement_names[i]] = {{"value", t.measurement_values[static_cast<Eigen::Index>(i)]},
                                          {"unit", t.measurement_units[i]}};
    out["template"]["measurements"] = measured;
    // The counts under the summary's names (schemas/summary.schema.json): succeeded = ok + suspect.
    out["succeeded"] = ok + suspect;
    out["suspect"] = suspect;
    out["failed"] = failed;
    out["targets"] = nlohmann::ordered_json::array();
    for (const ArchiveTargetSummary& target : reader.targets())
      out["targets"].push_back(target_json(outcome_of(target), false, t.measurement_names));
    std::cout << out.dump(2) << "\n";
    return;
  }

  std::cout << options.archive << ": xparam archive, schema " << reader.schema_version() << ", written by xparam "
            << p.xparam_version << " (" << p.git_revision << ")\n"
            << "options: " << p.options_json << "\n"
            << "template: " << t.mesh_file << ", " << reader.n_vertices() << " vertices, " << reader.n_faces()
            << " faces, " << t.anchor_names.size() << " anchors, " << t.curves.size() << " curves, "
            << plural(t.measurement_names.size(), "measurement")
            << (t.measurements_file.empty() ? "" : " (" + t.measurements_file + "; per target: --target NAME, or "
                                                   "export --measurements)")
            << "\n"
            << plural(reader.targets().size(), "target") << ": " << ok << " ok, " << suspect << " suspect, " << failed
            << " failed\n";
  if (reader.targets().empty()) return;
  std::size_t width = 4;
  for (const ArchiveTargetSummary& target : reader.targets()) width = std::max(width, target.name.size() + 2);
  std::cout << padded("name", width) << "status   " << padded("E_L2", 10) << padded("E_ang", 10)
            << padded("folds", 7) << padded("strict", 7) << padded("area", 7) << padded("released", 9)
            << padded("gt_error", 10) << padded("seconds", 9) << "error or reasons\n";
  for (const ArchiveTargetSummary& target : reader.targets()) {
    const TargetMetrics& m = target.metrics;
    std::cout << padded(target.name, width) << padded(status_of(target), 9) << padded(figure(m.e_l2), 10)
              << padded(figure(m.e_ang), 10) << padded(count(m.flipped_faces), 7)
              << padded(count(m.strictly_folded_faces), 7) << padded(figure(m.area_ratio), 7)
              << padded(count(m.released_anchors), 9) << padded(figure(m.gt_error), 10)
              << padded(figure(target.seconds.back()), 9)
              << (target.ok ? joined_reasons(target.diagnosis) : target.error) << "\n";
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
  inspect->add_option("--target", options->target,
                      "Show one target: its figures, why it is suspect, folds by nearest anchor, disagreeing "
                      "corners, swapped-looking landmarks, released and helper anchors, warnings");
  inspect->add_flag("--json", options->json,
                    "Print JSON instead of a table (NaN as null; keys: schemas/target.schema.json)");
  inspect->add_flag("--verify", options->verify,
                    "First read every dataset in full, checking every chunk's checksum (exit 3 naming the first "
                    "damaged dataset)");
  inspect->footer("Examples: xparam inspect results.h5    xparam inspect results.h5 --target woman    "
                  "xparam inspect results.h5 --json > results.json");
  inspect->callback([options] { run_inspect(*options); });
}

}  // namespace xparam::cli
