#include "batch/common_anchors.h"

#include "core/errors.h"
#include "io/anchor_reader.h"

#include <algorithm>
#include <map>
#include <set>

namespace xparam {

CommonAnchors common_anchor_names(const AnchorSet& template_anchors, const std::vector<TargetSpec>& targets) {
  std::map<std::string, std::size_t> missing_on;  // template name -> target files without it
  std::map<std::string, std::string> example;     // template name -> one such file
  std::vector<std::string> extra;                 // target names the template lacks, first seen first
  std::set<std::string> template_names;
  for (const AnchorSpec& anchor : template_anchors.anchors) template_names.insert(anchor.name);
  std::set<std::string> seen_extra;
  for (const TargetSpec& target : targets) {
    if (!target.problem.empty() || target.anchors.empty()) continue;
    AnchorSet set;
    try {
      set = read_anchors(target.anchors);
    } catch (const Error&) {
      continue;  // the target fails on its own, with the reading error
    }
    std::set<std::string> names;
    for (const AnchorSpec& anchor : set.anchors) {
      names.insert(anchor.name);
      if (!template_names.count(anchor.name) && seen_extra.insert(anchor.name).second) extra.push_back(anchor.name);
    }
    for (const std::string& name : template_names) {
      if (names.count(name)) continue;
      if (missing_on[name]++ == 0) example[name] = target.anchors.string();
    }
  }
  CommonAnchors common;
  for (const AnchorSpec& anchor : template_anchors.anchors) {
    const auto missing = missing_on.find(anchor.name);
    if (missing == missing_on.end())
      common.names.push_back(anchor.name);
    else
      common.left_out.push_back({anchor.name, missing->second, example[anchor.name]});
  }
  for (const std::string& name : extra) common.left_out.push_back({name, 0, ""});
  if (common.names.size() < static_cast<std::size_t>(kMinAnchors))
    throw InputError(template_anchors.source + ": --common-anchors: the template and the targets share only " +
                     std::to_string(common.names.size()) + " anchor names; a layout needs at least " +
                     std::to_string(kMinAnchors) + " (compare the names in " + template_anchors.source +
                     " with the targets' anchor files)");
  return common;
}

AnchorSet only_anchors(const AnchorSet& anchors, const std::vector<std::string>& names) {
  const std::set<std::string> kept(names.begin(), names.end());
  AnchorSet out;
  out.source = anchors.source;
  for (const AnchorSpec& anchor : anchors.anchors)
    if (kept.count(anchor.name)) out.anchors.push_back(anchor);
  return out;
}

}  // namespace xparam
