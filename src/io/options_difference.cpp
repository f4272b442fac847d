#include "io/options_difference.h"

#include <nlohmann/json.hpp>

#include <map>
#include <set>

namespace xparam {
namespace {

using Json = nlohmann::json;

// Every leaf of `value` by its dotted key path.
void flatten(const Json& value, const std::string& prefix, std::map<std::string, std::string>& out) {
  if (value.is_object() && !value.empty()) {
    for (const auto& [key, member] : value.items()) flatten(member, prefix.empty() ? key : prefix + "." + key, out);
    return;
  }
  out[prefix] = value.dump();
}

}  // namespace

std::string options_difference(const std::string& recorded_json, const std::string& current_json) {
  if (recorded_json == current_json) return {};
  const Json recorded = Json::parse(recorded_json, nullptr, false);
  const Json current = Json::parse(current_json, nullptr, false);
  if (recorded.is_discarded() || current.is_discarded() || !recorded.is_object() || !current.is_object())
    return "options were " + recorded_json + ", now " + current_json;
  std::map<std::string, std::string> before;
  std::map<std::string, std::string> after;
  flatten(recorded, "", before);
  flatten(current, "", after);
  std::set<std::string> keys;
  for (const auto& [key, value] : before) keys.insert(key);
  for (const auto& [key, value] : after) keys.insert(key);
  std::string text;
  for (const std::string& key : keys) {
    const auto was = before.find(key);
    const auto now = after.find(key);
    const std::string was_text = was == before.end() ? "absent" : was->second;
    const std::string now_text = now == after.end() ? "absent" : now->second;
    if (was_text == now_text) continue;
    if (!text.empty()) text += "; ";
    text += "option \"" + key + "\" was " + was_text + ", now " + now_text;
  }
  return text.empty() ? "options differ only in their order" : text;
}

}  // namespace xparam
