#include "io/archive_merge.h"

#include "core/errors.h"
#include "io/archive_commit.h"
#include "io/archive_reader.h"

#include <algorithm>
#include <memory>
#include <string>

namespace xparam {

void merge_archives(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out,
                    const ArchiveWriteSettings& settings) {
  if (shards.empty()) throw ArchiveError(out.string() + ": merge needs at least one shard archive");
  std::vector<std::unique_ptr<ArchiveReader>> readers;
  for (const std::filesystem::path& shard : shards) {
    if (std::filesystem::exists(out) && std::filesystem::equivalent(shard, out))
      throw ArchiveError(out.string() + ": the merged archive cannot also be a shard");
    readers.push_back(std::make_unique<ArchiveReader>(shard));
  }

  const ArchiveReader& first = *readers.front();
  const TemplateRecord template_record = first.read_template();
  struct Row {
    const std::string* name;
    std::size_t shard;
    std::size_t row;
  };
  std::vector<Row> rows;
  for (std::size_t s = 0; s < readers.size(); ++s) {
    const ArchiveReader& reader = *readers[s];
    const ArchiveProvenance& p = reader.provenance();
    const ArchiveProvenance& q = first.provenance();
    if (p.xparam_version != q.xparam_version || p.git_revision != q.git_revision || p.options_json != q.options_json)
      throw ArchiveError(reader.path().string() + ": provenance (version, revision or options) differs from " +
                         first.path().string());
    if (s > 0 && !same_template(reader.read_template(), template_record))
      throw ArchiveError(reader.path().string() + ": template differs from the one of " + first.path().string());
    for (std::size_t r = 0; r < reader.targets().size(); ++r) rows.push_back({&reader.targets()[r].name, s, r});
  }
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return *a.name < *b.name; });
  for (std::size_t i = 1; i < rows.size(); ++i)
    if (*rows[i].name == *rows[i - 1].name)
      throw ArchiveError("merge: target '" + *rows[i].name + "' is in both " +
                         readers[rows[i - 1].shard]->path().string() + " and " +
                         readers[rows[i].shard]->path().string());

  write_archive(
      out, template_record, first.provenance(), rows.size(),
      [&](std::size_t i) { return readers[rows[i].shard]->read_target(rows[i].row); }, settings);
}

}  // namespace xparam
