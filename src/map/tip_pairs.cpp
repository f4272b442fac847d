#include "map/tip_pairs.h"

#include <algorithm>
#include <variant>

namespace xparam {

std::vector<std::string> names_taken(std::vector<std::string> taken,
                                     const std::vector<ExtremityAnchor>& matched) {
  for (const ExtremityAnchor& tip : matched) taken.push_back(tip.specs[0].name);
  return taken;
}

ExtremityAnchor tip_anchor(int s, int t, const std::array<double, 2>& miss, std::size_t n,
                           std::vector<std::string>& names) {
  std::string name = "tip " + std::to_string(n);
  while (std::find(names.begin(), names.end(), name) != names.end()) name += "'";
  names.push_back(name);
  ExtremityAnchor anchor;
  anchor.specs[0] = {name, AnchorVertex{s}, "", 0};
  anchor.specs[1] = {name, AnchorVertex{t}, "", 0};
  anchor.miss = miss;
  return anchor;
}

}  // namespace xparam
