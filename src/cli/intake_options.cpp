#include "cli/intake_options.h"

#include <map>
#include <string>

namespace xparam::cli {

void add_intake_options(CLI::App& command, IntakeSettings& settings) {
  const std::map<std::string, IntakeMode> modes{{"repair", IntakeMode::Repair}, {"strict", IntakeMode::Strict}};
  command
      .add_option_function<std::string>(
          "--intake", [&settings, modes](const std::string& name) { settings.mode = modes.at(name); },
          "What to do with a target the pipeline cannot take as it is (holes, loose parts, duplicated or "
          "degenerate faces, non-manifold bits, handles): repair (the default: repair the soup, drop loose parts, "
          "fill holes, cut short handles and cap them, all recorded) or strict (refuse it)")
      ->check(CLI::IsMember({"repair", "strict"}));
  command
      .add_option_function<double>(
          "--max-dropped-area", [&settings](double percent) { settings.max_dropped_area = percent / 100.0; },
          "Largest share of a target's area, in percent, that the intake may drop as loose parts (default 10)")
      ->check(CLI::Range(0.0, 100.0));
  command
      .add_option("--max-hole", settings.max_hole,
                  "Longest hole border (target units) the intake fills; longer holes are refused (default: "
                  "a quarter of the target's bounding-box diagonal)")
      ->check(CLI::PositiveNumber);
  command
      .add_option_function<double>(
          "--max-handle",
          [&settings](double length) {
            settings.max_handle = length;
            if (length == 0.0) settings.max_handle_relative = 0.0;
          },
          "Longest loop around a handle (genus, e.g. a tunnel where two surfaces touch; target units) that the "
          "intake cuts open and caps; longer ones are refused, and 0 refuses every handle (default: 5% of the "
          "target's bounding-box diagonal)")
      ->check(CLI::NonNegativeNumber);
}

}  // namespace xparam::cli
