#include "cli/command_line.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <vector>

namespace xparam::cli {
namespace {

class PlainFormatter : public CLI::Formatter {
 public:
  // CLI11 writes a negated flag's default into its name: "--merge,--no-merge{false}".
  std::string make_option_name(const CLI::Option* opt, bool positional) const override {
    std::string name = CLI::Formatter::make_option_name(opt, positional);
    for (std::size_t open = name.find('{'); open != std::string::npos; open = name.find('{', open)) {
      const std::size_t close = name.find('}', open);
      if (close == std::string::npos) break;
      name.erase(open, close - open + 1);
    }
    std::string spaced;
    for (char c : name) spaced += c == ',' ? std::string(", ") : std::string(1, c);
    return spaced;
  }

  // The type and REQUIRED, without CLI11's "=default" glued to the type.
  std::string make_option_opts(const CLI::Option* opt) const override {
    std::string opts;
    if (opt->get_type_size() != 0) {
      if (!opt->get_type_name().empty()) opts += " " + opt->get_type_name();
      if (opt->get_required()) opts += " REQUIRED";
    }
    return opts;
  }

  std::string make_option_desc(const CLI::Option* opt) const override {
    std::string desc = opt->get_description();
    if (opt->get_type_size() != 0 && !opt->get_default_str().empty() && desc.find("(default") == std::string::npos)
      desc += " (default: " + opt->get_default_str() + ")";
    return desc;
  }
};

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

}  // namespace

std::shared_ptr<CLI::Formatter> plain_formatter() { return std::make_shared<PlainFormatter>(); }

CLI::Validator at_least(double low, bool inclusive) {
  const std::string bound = format_number(low);
  return CLI::Validator(
      [=](std::string& input) -> std::string {
        double value = 0.0;
        std::istringstream in(input);
        if (!(in >> value) || !in.eof()) return "must be a number, got \"" + input + "\"";
        if (inclusive ? value >= low : value > low) return {};
        return std::string("must be ") + (inclusive ? "at least " : "above ") + bound + ", got " + input;
      },
      std::string(inclusive ? ">=" : ">") + bound);
}

std::string did_you_mean(const CLI::App& app, int argc, const char* const* argv) {
  const CLI::App* command = &app;
  for (const CLI::App* sub : app.get_subcommands()) command = sub;
  for (int i = 1; i < argc; ++i) {
    std::string word = argv[i];
    if (word.rfind("--", 0) != 0 || word.size() < 3) continue;
    word = word.substr(0, word.find('='));
    if (command->get_option_no_throw(word) != nullptr || app.get_option_no_throw(word) != nullptr) continue;
    std::string best;
    std::size_t best_distance = 3;  // a typo: at most two edits
    for (const CLI::Option* option : command->get_options()) {
      for (const std::string& name : option->get_lnames()) {
        const std::size_t distance = edit_distance(word.substr(2), name);
        if (distance < best_distance) best_distance = distance, best = "--" + name;
      }
    }
    if (!best.empty()) return word + ": did you mean " + best + "?";
  }
  return {};
}

}  // namespace xparam::cli
