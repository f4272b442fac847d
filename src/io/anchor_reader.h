#pragma once
/// \file
/// Reading anchor files: JSON (schemas/anchors.schema.json), MeshLab picked points (.pp) and
/// plain text. Every problem is an InputError that starts with "file:line:".
///
/// Plain text (any extension but .json and .pp): one anchor a line, `name index` (0-based
/// vertex index) or `name x y z` (a 3-D position). `#` starts a comment (whole line or after
/// the values); blank lines are ignored. A name with spaces (or a `#`, or a leading `"`) is
/// written in double quotes, with `\"` and `\\` inside: `"Lt. Acromion" 1862`.
///
/// MeshLab picked points: every `<point x=".." y=".." z=".." name=".."/>` is a position
/// anchor; points with `active="0"` (unticked in MeshLab's picking dialog) are skipped, a
/// point without `active` counts as active (older MeshLab files).

#include "core/anchors.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

namespace xparam {

/// Read the anchors of one mesh, choosing the format by extension (case-insensitive):
/// `.json`, `.pp`, anything else plain text. The set is checked with check_anchor_set
/// (duplicate names, two anchors on one vertex index, at least kMinAnchors, ...).
/// \throw InputError "file:line: what" (or "file: what" when no line applies)
AnchorSet read_anchors(const std::filesystem::path& path);

/// Parse anchor JSON held in `text`; `source` names it in messages. Canonical form
/// `{"anchors": [{"name": "Nose", "vertex": 412}, {"name": "Tail", "position": [x, y, z]},
/// {"name": "Hoof", "face": 10, "barycentric": [a, b, c]}]}`, or the flat forms
/// `{"Nose": 412, "Tail": [x, y, z]}` (a top-level object without an "anchors" member).
AnchorSet parse_anchors_json(const std::string& text, const std::string& source);

/// Parse MeshLab picked points (XML) held in `text`; `source` names it in messages.
AnchorSet parse_picked_points(const std::string& text, const std::string& source);

/// Parse plain-text anchors held in `text`; `source` names it in messages.
AnchorSet parse_anchors_text(const std::string& text, const std::string& source);

/// The whole content of a file. \throw InputError when it cannot be read
std::string read_text_file(const std::filesystem::path& path);

/// A parsed JSON document with the 1-based line on which each value starts, keyed by JSON
/// pointer ("/anchors/3", "/Lt. Thelion~1Bustpoint"); shared by the anchor and curve readers.
struct LocatedJson {
  nlohmann::ordered_json value;  ///< members in file order
  std::map<std::string, int> lines;

  /// Line of the value at `pointer`, 0 when unknown.
  int line(const std::string& pointer) const;
};

/// Deepest nesting of arrays and objects parse_located_json accepts. Anchor and curve files
/// need 4 levels; the bound keeps memory proportional to the input (each open level holds its
/// JSON pointer, so unbounded nesting would cost the square of the depth).
inline constexpr std::size_t kMaxJsonDepth = 64;

/// Parse JSON, refusing a member name given twice in one object (a plain parse keeps the
/// last silently, losing an anchor) and nesting deeper than kMaxJsonDepth.
/// \throw InputError "source: invalid JSON at byte N: ...", "source:line: duplicate member "x" (first at
/// line M)" or "source:line: JSON nested deeper than 64 levels ..."
LocatedJson parse_located_json(const std::string& text, const std::string& source);

/// Throw InputError "source:line: what" ("source: what" when line is 0): how every reader of a
/// located file reports a problem.
[[noreturn]] void fail_at(const std::string& source, int line, const std::string& what);

/// `name` escaped for use as one JSON pointer token ("~" -> "~0", "/" -> "~1").
std::string json_pointer_token(const std::string& name);

}  // namespace xparam
