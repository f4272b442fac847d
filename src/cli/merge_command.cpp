// `xparam merge SHARD.h5... --out ARCHIVE.h5`: combine shard archives into one.
#include "cli/commands.h"

#include "io/archive_merge.h"
#include "io/archive_reader.h"

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
};

}  // namespace

void add_merge_command(CLI::App& app) {
  auto options = std::make_shared<MergeOptions>();
  CLI::App* command = app.add_subcommand(
      "merge", "Combine shard archives (same template, options and xparam build; disjoint targets) into one "
               "archive whose datasets equal those of a single run over all targets.");
  command->add_option("shards", options->shards, "Shard archives (.h5)")->required()->check(CLI::ExistingFile);
  command->add_option("--out", options->out, "Merged archive to write (replaced if it exists)")->required();
  command->callback([options] {
    merge_archives({options->shards.begin(), options->shards.end()}, options->out);
    std::cout << "merged " << ArchiveReader(options->out).targets().size() << " targets from "
              << options->shards.size() << " shards into " << options->out << "\n";
  });
}

}  // namespace xparam::cli
