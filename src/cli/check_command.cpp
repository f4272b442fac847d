// `xparam check MESH...`: validate mesh files and say whether the pipeline can use them.
#include "cli/commands.h"
#include "cli/intake_options.h"

#include "core/errors.h"
#include "core/mesh_builder.h"
#include "core/orientation.h"
#include "core/validation.h"
#include "intake/intake_json.h"
#include "intake/scan_intake.h"
#include "io/mesh_reader.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace xparam::cli {
namespace {

struct CheckOptions {
  std::vector<std::string> meshes;
  bool json = false;
  bool no_repair = false;
  IntakeSettings intake;  ///< --intake, --max-dropped-area, --max-hole
};

// What checking one file found: a report, or the error that stopped reading it.
struct CheckedFile {
  std::string file;
  std::optional<MeshReport> report;
  std::optional<double> signed_volume;  // only for usable meshes (closed, so it is meaningful)
  std::string error;                    // reading or building failed
  // The intake's verdict on a file validation refuses or of genus > 0 (IntakeMode::Repair): what
  // it would do and the validation of its result, or why it refuses.
  std::optional<IntakeRecord> intake;
  std::optional<MeshReport> after_intake;
  std::string intake_error;
  // A file of genus > 0 whose handles the intake cuts is usable after the intake; one whose handle
  // it refuses stays usable as it is (for a template of its genus), with a note.
  bool usable_as_is() const { return report && report->usable && error.empty() && !intake; }
  bool usable() const { return usable_as_is() || (after_intake && after_intake->usable); }
};

CheckedFile check_file(const std::string& file, const ValidationSettings& settings, const IntakeSettings& intake) {
  CheckedFile checked{file, std::nullopt, std::nullopt, "", std::nullopt, std::nullopt, ""};
  try {
    const TriangleSoup soup = read_triangle_soup(file);
    checked.report = validate_soup(soup, settings);
    const MeshReport& report = *checked.report;
    // Building proves OpenMesh accepts what validation called usable (repaired as the loader does).
    const bool repaired = !report.reoriented_faces.empty() || !report.split_vertices.empty();
    if (report.usable) checked.signed_volume = signed_volume(build_mesh(repaired ? repair_soup(soup).soup : soup));
    // A usable file of genus > 0 goes through the intake too, which cuts its handles.
    const bool has_handles = report.usable && report.genus.value_or(0) > 0;
    if ((!report.usable || has_handles) && intake.mode == IntakeMode::Repair && settings.repair) {
      try {
        // Without anchors the largest part is kept, as a target's anchors usually choose it.
        const PreparedScan prepared = prepare_scan(soup, {}, intake);
        checked.intake = prepared.record;
        checked.after_intake = validate_soup(prepared.soup, settings);
        if (checked.after_intake->usable) checked.signed_volume = signed_volume(build_mesh(prepared.soup));
      } catch (const InputError& e) {
        checked.intake_error = e.what();
      }
    }
  } catch (const Error& e) {
    checked.error = e.what();
  }
  return checked;
}

nlohmann::json vector_json(const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

nlohmann::json to_json(const CheckedFile& checked) {
  nlohmann::json out;
  out["file"] = checked.file;
  out["valid"] = checked.usable();
  nlohmann::json problems = nlohmann::json::array();
  if (!checked.error.empty()) {
    out["error"] = checked.error;
    problems.push_back(checked.error);
  }
  if (!checked.report) {
    out["problems"] = problems;
    return out;
  }
  const MeshReport& r = *checked.report;
  nlohmann::json warnings = nlohmann::json::array();
  nlohmann::json repaired = nlohmann::json::array();
  for (const Problem* p : r.errors()) problems.push_back(p->message);
  for (const Problem* p : r.warnings()) warnings.push_back(p->message);
  for (const Problem* p : r.repaired()) repaired.push_back(p->message);
  nlohmann::json splits = nlohmann::json::array();
  size_t copies = 0;
  for (const VertexSplit& split : r.split_vertices) {
    splits.push_back({{"vertex", split.vertex}, {"copies", split.copies}});
    copies += split.copies.size();
  }
  out["vertices"] = r.vertices;
  out["faces"] = r.faces;
  out["edges"] = r.edges;
  out["polygons_triangulated"] = r.polygons_triangulated;
  out["components"] = r.components;
  out["boundary_loops"] = r.boundary_loops;
  out["boundary_edges"] = r.boundary_edges;
  out["euler_characteristic"] = r.euler_characteristic;
  out["genus"] = r.genus ? nlohmann::json(*r.genus) : nlohmann::json(nullptr);
  out["orientable"] = r.orientable;
  out["non_manifold_edges"] = r.non_manifold_edges.size();
  out["non_manifold_vertices"] = r.non_manifold_vertices.size();
  out["inconsistent_edges"] = r.inconsistent_edges.size();
  out["degenerate_faces"] = r.degenerate_faces.size();
  out["near_zero_area_faces"] = r.near_zero_area_faces.size();
  out["duplicate_vertices"] = r.duplicate_vertices.size();
  out["unreferenced_vertices"] = r.unreferenced_vertices.size();
  out["non_finite_vertices"] = r.non_finite_vertices.size();
  out["bbox_min"] = vector_json(r.bbox_min);
  out["bbox_max"] = vector_json(r.bbox_max);
  out["mean_edge_length"] = r.mean_edge_length;
  out["min_face_area"] = r.min_face_area;
  out["signed_volume"] = checked.signed_volume ? nlohmann::json(*checked.signed_volume) : nlohmann::json(nullptr);
  out["problems"] = problems;
  out["warnings"] = warnings;
  out["repaired"] = repaired;
  out["reoriented_faces"] = r.reoriented_faces.size();
  out["split_vertices"] = splits;
  out["vertex_copies"] = copies;
  out["usable_as_is"] = checked.usable_as_is();
  if (checked.intake) {
    out["intake"] = intake_json(*checked.intake);
    nlohmann::json remaining = nlohmann::json::array();
    for (const Problem* p : checked.after_intake->errors()) remaining.push_back(p->message);
    out["intake"]["problems_after"] = remaining;
    out["intake"]["genus_after"] =
        checked.after_intake->genus ? nlohmann::json(*checked.after_intake->genus) : nlohmann::json(nullptr);
  }
  if (!checked.intake_error.empty()) out["intake_refusal"] = checked.intake_error;
  return out;
}

std::string count(size_t n, const std::string& singular, const std::string& plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

std::string point_text(const Eigen::Vector3d& p) {
  std::ostringstream out;
  out << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return out.str();
}

void print_human(const CheckedFile& checked, std::ostream& out) {
  out << checked.file << ": "
      << (checked.usable_as_is() ? "usable" : checked.usable() ? "usable after the intake" : "NOT usable") << "\n";
  if (checked.report) {
    const MeshReport& r = *checked.report;
    out << "  " << count(r.vertices, "vertex", "vertices") << ", " << count(r.faces, "face", "faces") << ", "
        << count(r.edges, "edge", "edges") << "; " << count(r.components, "component", "components") << ", "
        << count(r.boundary_loops, "boundary loop", "boundary loops") << ", genus "
        << (r.genus ? std::to_string(*r.genus) : std::string("undefined")) << " (Euler characteristic "
        << r.euler_characteristic << ")\n";
    out << "  bounding box " << point_text(r.bbox_min) << " to " << point_text(r.bbox_max)
        << ", mean edge length " << r.mean_edge_length;
    if (checked.signed_volume)
      out << ", signed volume " << *checked.signed_volume
          << (*checked.signed_volume < 0 ? " (faces point inward: flipped at load)" : "");
    out << "\n";
    if (const std::string repairs = describe_repairs(r); !repairs.empty())
      out << "  repairs (the loader applies them; --no-repair to refuse instead): " << repairs << "\n";
    for (const Problem* p : r.errors()) out << "  error: " << p->message << "\n";
    for (const Problem* p : r.repaired()) out << "  repaired: " << p->message << "\n";
    for (const Problem* p : r.warnings()) out << "  warning: " << p->message << "\n";
  }
  if (checked.intake) {
    out << "  intake (on by default for targets; --intake strict refuses instead):\n";
    for (const std::string& step : checked.intake->describe()) out << "    " << step << "\n";
    const MeshReport& after = *checked.after_intake;
    out << "    after the intake: " << (after.usable ? "usable" : "NOT usable") << ", genus "
        << (after.genus ? std::to_string(*after.genus) : std::string("undefined")) << "\n";
    for (const Problem* p : after.errors()) out << "    error: " << p->message << "\n";
  }
  if (!checked.intake_error.empty()) out << "  intake refuses: " << checked.intake_error << "\n";
  const MeshReport* final_report = checked.after_intake ? &*checked.after_intake : checked.report ? &*checked.report : nullptr;
  if (checked.usable() && final_report && final_report->genus && *final_report->genus != 0)
    out << "  note: genus " << *final_report->genus << ": pair and batch map genus-0 templates and refuse it "
        << "(close the handle in a mesh editor"
        << (checked.intake_error.empty() ? "; without --intake strict the intake cuts handles up to --max-handle" : "")
        << ")\n";
  if (!checked.error.empty()) out << "  error: " << checked.error << "\n";
}

void run_check(const CheckOptions& options) {
  std::vector<CheckedFile> results;
  results.reserve(options.meshes.size());
  ValidationSettings settings;
  settings.repair = !options.no_repair;
  for (const std::string& file : options.meshes) results.push_back(check_file(file, settings, options.intake));

  size_t usable = 0;
  for (const CheckedFile& checked : results) usable += checked.usable();
  if (options.json) {
    nlohmann::json array = nlohmann::json::array();
    for (const CheckedFile& checked : results) array.push_back(to_json(checked));
    std::cout << array.dump(2) << "\n";
  } else {
    for (const CheckedFile& checked : results) print_human(checked, std::cout);
    if (results.size() > 1) std::cout << usable << " of " << results.size() << " meshes usable\n";
  }
  // Exit status 1 (without a CLI11 message) when any mesh is unusable.
  if (usable != results.size()) throw CLI::RuntimeError(kExitSomeFailed);
}

}  // namespace

void add_check_command(CLI::App& app) {
  auto options = std::make_shared<CheckOptions>();
  CLI::App* check = app.add_subcommand(
      "check", "Validate mesh files (OBJ, PLY, OFF, STL): counts, topology, genus, defects. Faces wound "
               "against their neighbours are re-oriented and pinched vertices split, as the loader does "
               "(listed as repairs). A mesh that is still not usable (holes, loose parts, duplicated faces, "
               "non-manifold bits) is shown with what the scan intake would do to it as a target, and whether "
               "the result is usable (--intake strict: not tried). Exit status 0 when every mesh is usable "
               "(closed, one component, 2-manifold edges, orientable, no degenerate faces; as it is or after "
               "the intake), 2 otherwise.");
  check->add_option("meshes", options->meshes, "Mesh files to check")->required()->check(CLI::ExistingFile);
  check->add_flag("--json", options->json, "Print a JSON array with one object per file");
  check->add_flag("--no-repair", options->no_repair,
                  "Judge the files as they are: inconsistent orientation and pinched vertices block use");
  check->footer("Example: xparam check scans/*.ply --json > report.json");
  add_intake_options(*check, options->intake);
  check->callback([options] { run_check(*options); });
}

}  // namespace xparam::cli
