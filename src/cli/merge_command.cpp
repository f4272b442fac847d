// `xparam merge SHARD.h5... --out ARCHIVE.h5`: combine shard archives into one.
#include "cli/commands.h"
#include "cli/text_format.h"

#include "core/errors.h"
#include "io/archive_lock.h"
#include "io/archive_merge.h"
#include "io/archive_reader.h"
#include "io/output_paths.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace xparam::cli {
namespace {

struct MergeOptions {
  std::vector<std::string> shards;
  std::string out;
  bool force = false;
};

void run_merge(const MergeOptions& options) {
  check_writable_file(options.out, "--out");
  const ArchiveLock lock(options.out);  // no batch run or other merge writes it meanwhile
  if (!options.force && std::filesystem::exists(options.out)) {
    std::cerr << "xparam merge: " << options.out
              << " already exists; nothing was changed. Add --force to replace it, or choose another --out\n";
    throw CLI::RuntimeError(kExitUsage);
  }
  merge_archives({options.shards.begin(), options.shards.end()}, options.out);
  std::cout << "merged " << plural(ArchiveReader(options.out).targets().size(), "target") << " from "
            << plural(options.shards.size(), "shard") << " into " << options.out << "\n";
}

}  // namespace

void add_merge_command(CLI::App& app) {
  auto options = std::make_shared<MergeOptions>();
  CLI::App* command = app.add_subcommand(
      "merge", "Combine shard archives (same template, options and xparam build; disjoint targets) into one "
               "archive whose datasets equal those of a single run over all targets.");
  command->add_option("shards", options->shards, "Shard archives (.h5)")->required()->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "Merged archive to write")->required();
  command->add_flag("--force", options->force, "Replace --out when it exists");
  command->footer("Example: xparam merge shard_0.h5 shard_1.h5 shard_2.h5 --out all.h5");
  command->callback([options] { run_merge(*options); });
}

}  // namespace xparam::cli
