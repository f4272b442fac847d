#include "io/options_difference.h"

#include <nlohmann/json.hpp>

#include <map>
#include <set>

namespace xparam {
namespace {

// Every leaf of `value` by its dotted key path.
void flatten(const nlohmann::json& value, const std::string& prefix,
             std::map<std::string, std::string>& out) {
  if (value.is_object() && !value.empty()) {
    for (const auto& [key, member] : value.items()) flatten(member, prefix.empty() ? key : prefix + "." + key, out);
    return;
  }
  out[prefix] = value.dump();
}

std::map<std::string, std::string> leaves(const nlohmann::json& value) {
  std::map<std::string, std::string> out;
  if (!value.is_discarded() && value.is_object()) flatten(value, "", out);
  return out;
}

}  // namespace

std::string options_difference(const std::string& recorded_json, const std::string& current_json,
                               const std::string& implied_json) {
  if (recorded_json == current_json) return {};
  const nlohmann::json recorded = nlohmann::json::parse(recorded_json, nullptr, false);
  const nlohmann::json current = nlohmann::json::parse(current_json, nullptr, false);
  if (recorded.is_discarded() || current.is_discarded() || !recorded.is_object() || !current.is_object())
    return "options were " + recorded_json + ", now " + current_json;
  const std::map<std::string, std::string> before = leaves(recorded);
  const std::map<std::string, std::string> after = leaves(current);
  const std::map<std::string, std::string> implied =
      leaves(nlohmann::json::parse(implied_json, nullptr, false));
  std::set<std::string> keys;
  for (const auto& [key, value] : before) keys.insert(key);
  for (const auto& [key, value] : after) keys.insert(key);
  bool any_implied = false;
  std::string text;
  for (const std::string& key : keys) {
    const auto was = before.find(key);
    const auto now = after.find(key);
    const auto then = implied.find(key);
    const std::string now_text = now == after.end() ? "absent" : now->second;
    std::string difference;
    if (was != before.end()) {
      if (was->second != now_text) difference = "was " + was->second + ", now " + now_text;
    } else if (then != implied.end()) {
      any_implied = true;
      if (then->second != now_text)
        difference = "is not recorded (the archive predates it: " + then->second + "), now " + now_text;
    } else if (now_text != "absent") {
      difference = "was absent, now " + now_text;
    }
    if (difference.empty()) continue;
    if (!text.empty()) text += "; ";
    text += "option \"" + key + "\" " + difference;
  }
  if (text.empty() && !any_implied) return "options differ only in their order";
  return text;
}

}  // namespace xparam
