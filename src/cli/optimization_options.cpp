#include "cli/optimization_options.h"

#include <string>
#include <vector>

namespace xparam::cli {

void add_optimization_options(CLI::App& command, DomainOptimizationSettings& settings) {
  std::vector<std::string> names;
  for (SwapMetric metric : all_swap_metrics()) names.emplace_back(to_string(metric));
  command
      .add_option_function<std::string>(
          "--optimize", [&settings](const std::string& name) { settings.metric = parse_swap_metric(name); },
          "Metric of the boundary swapping (paper section 4): none; ad or l2 (the map's angle distortion or "
          "L2-stretch on the dense meshes, section 4.1; slow); area, dad, dl2, sdl, gar (on the base domains, "
          "section 4.2); or balanced (section 4.3; the default)")
      ->check(CLI::IsMember(names));
  command.add_flag("--merge,!--no-merge", settings.merge,
                   "Merge triangle pairs into quads where it lowers the domain distortion (paper section 5; default on)");
  command.add_flag("!--no-stretch", settings.stretch,
                   "Keep the initial layout curves instead of straightening them into geodesics first");
}

}  // namespace xparam::cli
