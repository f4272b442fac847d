#include "cli/unknown_target.h"

#include "cli/text_format.h"

namespace xparam::cli {

void refuse_unknown_target(const std::string& command, const ArchiveReader& reader, const std::string& name,
                           bool point_to_inspect) {
  std::string names;
  for (const ArchiveTargetSummary& t : reader.targets()) names += (names.empty() ? "" : ", ") + t.name;
  usage_error(command, reader.path().string() + ": no target \"" + name + "\"; it holds " +
                           (names.empty() ? std::string("none") : names) +
                           (point_to_inspect ? " (xparam inspect lists them)" : ""));
}

}  // namespace xparam::cli
