#include "cli/intake_options.h"

#include <map>
#include <string>

namespace xparam::cli {

void add_intake_options(CLI::App& command, IntakeSettings& settings) {
  const std::map<std::string, IntakeMode> modes{{"repair", IntakeMode::Repair}, {"strict", IntakeMode::Strict}};
  command
      .add_option_function<std::string>(
          "--intake", [&settings, modes](const std::string& name) { settings.mode = modes.at(name); },
          "What to do with a target the pipeline cannot take as it is (holes, loose parts, duplicated or "
          "degenerate faces, non-manifold bits): repair (the default: repair the soup, drop loose parts, fill "
          "holes, all recorded) or strict (refuse it)")
      ->check(CLI::IsMember({"repair", "strict"}));
  command
      .add_option_function<double>(
          "--max-dropped-area", [&settings](double percent) { settings.max_dropped_area = percent / 100.0; },
          "Largest share of a target's area, in percent, that the intake may drop as loose parts (default 10)")
      ->check(CLI::Range(0.0, 100.0));
  command
      .add_option("--max-hole", settings.max_hole,
                  "Longest hole border (target units) the intake fills; longer holes are refused (default: "
                  "a quarter of the target's bounding-box diagonal)")
      ->check(CLI::PositiveNumber);
}

nlohmann::json intake_json(const IntakeRecord& record) {
  nlohmann::json dropped = nlohmann::json::array();
  for (const DroppedPart& part : record.dropped_parts) dropped.push_back({{"faces", part.faces}, {"area", part.area}});
  nlohmann::json holes = nlohmann::json::array();
  for (const FilledHole& hole : record.holes)
    holes.push_back({{"faces", hole.faces},
                     {"vertices", hole.vertices},
                     {"perimeter", hole.perimeter},
                     {"area", hole.area},
                     {"faired", hole.faired},
                     {"nearest_anchor", hole.nearest_anchor}});
  return {{"applied", record.applied},
          {"merged_vertices", record.merged_vertices},
          {"unused_vertices", record.unused_vertices},
          {"degenerate_faces", record.degenerate_faces},
          {"duplicate_faces", record.duplicate_faces},
          {"split_vertices", record.split_vertices},
          {"reversed_faces", record.reversed_faces},
          {"parts", record.parts},
          {"dropped_parts", dropped},
          {"dropped_faces", record.dropped_faces()},
          {"dropped_area", record.dropped_area()},
          {"total_area", record.total_area},
          {"holes_filled", holes},
          {"filled_faces", record.filled_faces},
          {"filled_vertices", record.filled_vertices},
          {"filled_area", record.filled_area()},
          {"steps", record.describe()}};
}

}  // namespace xparam::cli
