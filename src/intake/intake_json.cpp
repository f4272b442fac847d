#include "intake/intake_json.h"

namespace xparam {

nlohmann::json intake_json(const IntakeRecord& record) {
  nlohmann::json dropped = nlohmann::json::array();
  for (const DroppedPart& part : record.dropped_parts)
    dropped.push_back({{"faces", part.faces}, {"area", part.area}});
  nlohmann::json holes = nlohmann::json::array();
  for (const FilledHole& hole : record.holes)
    holes.push_back({{"faces", hole.faces},
                     {"vertices", hole.vertices},
                     {"perimeter", hole.perimeter},
                     {"area", hole.area},
                     {"faired", hole.faired},
                     {"nearest_anchor", hole.nearest_anchor}});
  nlohmann::json handles = nlohmann::json::array();
  for (const CutHandle& handle : record.handles)
    handles.push_back({{"length", handle.length},
                       {"faces", handle.faces},
                       {"vertices", handle.vertices},
                       {"area", handle.area},
                       {"faired", handle.faired},
                       {"nearest_anchor", handle.nearest_anchor}});
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
          {"handles_cut", handles},
          {"filled_faces", record.filled_faces},
          {"filled_vertices", record.filled_vertices},
          {"filled_area", record.filled_area()},
          {"steps", record.describe()}};
}

}  // namespace xparam
