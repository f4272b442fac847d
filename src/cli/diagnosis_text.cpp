#include "cli/diagnosis_text.h"

#include "cli/text_format.h"

#include <algorithm>
#include <cmath>

namespace xparam::cli {
namespace {

// The array at `key`, or an empty one (a diagnosis written before the key existed).
const nlohmann::ordered_json& list(const nlohmann::ordered_json& diagnosis, const char* key) {
  static const nlohmann::ordered_json empty = nlohmann::ordered_json::array();
  if (!diagnosis.is_object() || !diagnosis.contains(key) || !diagnosis[key].is_array()) return empty;
  return diagnosis[key];
}

// "4/11/345": whole degrees, slash-separated (as `xparam pair` prints them).
std::string degree_list(const nlohmann::ordered_json& degrees) {
  std::string text;
  for (const auto& d : degrees) text += (text.empty() ? "" : "/") + std::to_string(std::lround(d.get<double>()));
  return text;
}

}  // namespace

std::string joined_reasons(const std::string& diagnosis) {
  const nlohmann::ordered_json parsed = nlohmann::ordered_json::parse(diagnosis, nullptr, false);
  std::string text;
  for (const auto& reason : list(parsed, "reasons")) text += (text.empty() ? "" : "; ") + reason.get<std::string>();
  return text;
}

void print_diagnosis(const nlohmann::ordered_json& diagnosis, std::ostream& out) {
  for (const auto& reason : list(diagnosis, "reasons")) out << "  suspect: " << reason.get<std::string>() << "\n";
  const nlohmann::ordered_json& folds = list(diagnosis, "folds_by_anchor");
  if (!folds.empty()) {
    out << "  folded faces by nearest anchor:";
    for (const auto& f : folds)
      out << " \"" << f["anchor"].get<std::string>() << "\" " << f["folded_faces"].get<int>();
    out << "\n";
  }
  // As `xparam pair`: the disagreeing corners that explain folds, at anchors with folds near them.
  std::size_t unexplaining = 0;
  for (const auto& c : list(diagnosis, "disagreeing_corners")) {
    const auto has_folds = std::any_of(folds.begin(), folds.end(), [&](const auto& f) { return f["anchor"] == c["anchor"]; });
    if (!has_folds) {
      ++unexplaining;
      continue;
    }
    out << "  corners at \"" << c["anchor"].get<std::string>() << "\" disagree: " << degree_list(c["template_degrees"])
        << " degrees on the template, " << degree_list(c["target_degrees"])
        << " on the target (a different patch wraps round it on each mesh); moving or releasing that landmark "
           "may help\n";
  }
  if (unexplaining > 0)
    out << "  (" << plural(unexplaining, "more anchor") << " with disagreeing corners but no fold nearby: --json)\n";
  for (const auto& pair : list(diagnosis, "swapped_anchors"))
    out << "  landmarks \"" << pair[0].get<std::string>() << "\" and \"" << pair[1].get<std::string>()
        << "\" look swapped on the target: check its landmark file\n";
  for (const auto& r : list(diagnosis, "released_anchors"))
    out << "  released anchor \"" << r["anchor"].get<std::string>() << "\" (" << r["folded_faces"].get<int>()
        << " folded faces near it); the map lands " << figure(r["miss"].get<double>()) << " from its landmark\n";
  const nlohmann::ordered_json& helpers = list(diagnosis, "helper_anchors");
  if (!helpers.empty()) {
    out << "  mapped through helper anchors:";
    for (const auto& h : helpers) out << " \"" << h.get<std::string>() << "\"";
    out << "\n";
  }
  for (const auto& warning : list(diagnosis, "warnings")) out << "  warning: " << warning.get<std::string>() << "\n";
}

}  // namespace xparam::cli
