#include "cli/map_options.h"

#include "cli/command_line.h"

#include <limits>
#include <string>
#include <vector>

namespace xparam::cli {

void add_optimization_options(CLI::App& command, DomainOptimizationSettings& optimization) {
  std::vector<std::string> names;
  for (SwapMetric metric : all_swap_metrics()) names.emplace_back(to_string(metric));
  command
      .add_option_function<std::string>(
          "--optimize",
          [&optimization](const std::string& name) { optimization.metric = parse_swap_metric(name); },
          "Metric of the boundary swapping (paper section 4): none; ad or l2 (the map's angle distortion or "
          "L2-stretch on the dense meshes, section 4.1; slow); area, dad, dl2, sdl, gar (on the base "
          "domains, "
          "section 4.2); or balanced (section 4.3; the default)")
      ->check(CLI::IsMember(names));
  command.add_flag(
      "--merge,!--no-merge", optimization.merge,
      "Merge triangle pairs into quads where it lowers the domain distortion (paper section 5; default on)");
  command.add_flag("!--no-stretch", optimization.stretch,
                   "Keep the initial layout curves instead of straightening them into geodesics first");
  command.add_flag(
      "--swap-winding,!--no-swap-winding", optimization.swap_winding_curves,
      "With --optimize balanced, also swap a curve that winds round a limb or the head on both meshes "
      "(over 3 times as long as the straight distance between its anchors), which the balanced "
      "threshold does not see (ours, beyond the paper; default on)");
  command.add_flag("--keep-corners", optimization.stretching.keep_corners,
                   "Leave as traced the curves whose straightening collapses a patch corner on one mesh only "
                   "(curves from a fingertip running side by side down the finger)");
}

void add_map_options(CLI::App& command, PairSettings& settings) {
  add_optimization_options(command, settings.optimization);
  command.add_flag(
      "--relax,!--no-relax", settings.cross_map.relax,
      "Relax each patch's map on the target surface (symmetric Dirichlet energy, SLIM) so unanchored "
      "protrusions are not squeezed (the map stays a bijection; default on)");
  command.add_flag(
      "--second-layout,!--no-second-layout", settings.retry_keeping_corners,
      "When the remesh still folds, build the base domain again with corners kept (as --keep-corners) "
      "at the anchors near the folds and their neighbours, then, if it folds too, at the anchors near "
      "the folds alone, and keep the map with the fewest folds (default on; made only when no map "
      "through protrusion tips, --extremity-anchors, replaced the first)");
  command.add_flag(
      "--tip-anchors,!--no-tip-anchors", settings.tip_anchors,
      "When the remesh still folds next to anchors whose layout corners disagree between the meshes "
      "(a different patch wraps round a tip on each), map again through a helper anchor behind each "
      "such tip on both meshes, and keep that map when it folds less (default on)");
  command.add_flag(
      "--extremity-anchors,!--no-extremity-anchors", settings.extremity_anchors,
      "Find the tips of protrusions without a landmark (fingers, toes) on both meshes, match them "
      "through the first map, and map again through them as helper anchors; keep that map when it is "
      "less stretched and folds no more (default on; tried before the retries for folds, one more whole "
      "map, counted against --max-maps)");
  command
      .add_option("--tip-rounds", settings.tip_rounds,
                  "Rounds of those tips: each later round matches tips through the last round's map "
                  "(a thumb the first map squeezed into the palm) and maps again through them too, while "
                  "--max-maps allows (default 2; 1: the first map's tips only)")
      ->check(CLI::Range(1, 10));
  command.add_flag(
      "--tip-rows,!--no-tip-rows", settings.tip_rows,
      "With the tips, small toes: the short tips in a row beside a matched tip (a big toe), aligned "
      "between the meshes through the first map; a round whose map through them loses is made again "
      "without them (default on: on FAUST subjects with realistic landmark sets the worse foot's "
      "ground-truth error 0.49 -> 0.38% of sqrt(area) on average)");
  command.add_flag(
      "--fitted-tip-rows,!--no-fitted-tip-rows", settings.fitted_tip_rows,
      "With --tip-rows, pair those toes also by fitting the template's foot rigidly onto the target's, "
      "and where the fit pairs them otherwise, map once more with its pairs; keep that map when it folds "
      "no more and is at most 0.5% more stretched (default on: a first map that turns a forefoot by one "
      "toe left FAUST feet with every toe on its neighbour; one more whole map where it applies, counted "
      "against --max-maps)");
  command.add_flag(
      "--map-carried-tips,!--no-map-carried-tips", settings.map_carried_tips,
      "Make a round of tips even when the map before already carries every one of them to its partner "
      "within the tip reach (2.5% of sqrt(area)) on both meshes (default on). Off saves that round on "
      "such pairs (the 50k-vertex bench pair, whose round is pulled: 2.8 -> 2.5 s) but leaves fingertips "
      "crumpled or blunt where the round would round them (FAUST 000/030 with 29 landmarks: ground-truth "
      "error 0.58 -> 0.71% of sqrt(area))");
  command.add_flag(
      "--pull-carried-tips,!--no-pull-carried-tips", settings.pull_carried_tips,
      "Make such a round by optimizing the map before it again, its tips pulled onto their partners, "
      "instead of a whole map through them (default on: the 50k-vertex bench pair 4.0 -> 2.8 s, a "
      "slightly better map; off: a whole map, as before session 31)");
  command
      .add_option("--whole-map-up-to", settings.whole_map_up_to,
                  "With --pull-carried-tips: on a target of at most this many vertices, such a round also "
                  "makes the whole map through its tips and keeps it when it beats the pulled map (cheap "
                  "there, and a new layout can mend what optimizing the map cannot; default 20000; 0: never)")
      ->check(CLI::NonNegativeNumber);
  command.add_flag(
      "--retry-doubtful-tips,!--no-retry-doubtful-tips", settings.retry_doubtful_tips,
      "When a map through tips wins and the tip the first map carried farthest from its partner missed by "
      "more than 1.5 times the tip reach, map once more without it (the rest matched again) and keep the "
      "better map: where the first map squeezed a hand, a fingertip can be paired with another finger's. "
      "Likewise with a landmark cell's next tip when it lies nearly as far as the tip matched, and with "
      "the pairs one finger over when a pair's neighbouring tips are unmatched on opposite sides of it "
      "(default on; one more whole map per such trial)");
  command
      .add_option(
          "--release-anchors", settings.max_released_anchors,
          "For scans whose landmarks disagree with the template's: when the remesh still folds, map "
          "without an anchor near the folds, one at a time, up to N anchors, keeping each release that "
          "folds less with the area ratio within 2%; the released anchors and how far the map lands "
          "from them are reported (default 0: every anchor is kept; each try is a whole map, counted against "
          "--max-maps)")
      ->check(CLI::Range(0, 1000));
  command.add_flag(
      "--optimize-map,!--no-optimize-map", settings.optimize_map,
      "Optimize the composed map on the target surface: every template vertex but the anchors slides "
      "across patch boundaries to lower the distortion, and no step folds a remesh face (default on; "
      "off gives the layout's map)");
  command
      .add_option("--map-sweeps", settings.map_optimization.max_sweeps,
                  "Sweeps over the template's vertices that optimizing the map runs at most (default 100)")
      ->check(CLI::Range(0, 100000));
  command
      .add_option("--map-coverage", settings.map_optimization.coverage_weight,
                  "Weight of the pull of target vertices the remesh leaves out (a finger it cuts off) against "
                  "the distortion while optimizing the map (default 10; 0: none)")
      ->check(at_least(0));
  command
      .add_option("--anchor-slack", settings.anchor_slack,
                  "For landmarks placed by hand on scans: how far (target units) optimizing the map may move "
                  "each anchor's image from its landmark; the miss is reported per anchor (default 0: exact)")
      ->check(at_least(0));
  command
      .add_option(
          "--max-maps", settings.max_maps,
          "Whole maps a pair may make in all, the first included: the second and third layouts, the "
          "helper anchors and the releases above each make one or more, and none starts once they are "
          "made (metrics.json maps.limit_reached; default 7)")
      ->check(CLI::Range(1, 1000));
  command
      .add_option("--work-vertices", settings.work_vertices,
                  "A target with more vertices is mapped through a copy decimated to this many, and the map "
                  "carried back onto the target's own faces: every output still refers to the target file "
                  "(metrics.json working_copy; default 100000; 0: never)")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  command.add_flag("--untangle,!--no-untangle", settings.untangle,
                   "Slide template vertices of folded remesh faces inside their stars so the remesh has none "
                   "(the map stays a bijection; default on)");
}

nlohmann::json optimization_json(const DomainOptimizationResult& optimization) {
  return {{"metric", std::string(to_string(optimization.settings.metric))},
          {"stretch", optimization.settings.stretch},
          {"keep_corners", optimization.settings.stretching.keep_corners},
          {"swap_winding_curves", optimization.settings.swap_winding_curves},
          {"unstretched_curves", optimization.unstretched_curves},
          {"merge", optimization.settings.merge},
          {"swaps", optimization.swaps},
          {"refused_swaps", optimization.refused_swaps},
          {"merges", optimization.merges},
          {"vertices_added", {optimization.vertices_added[0], optimization.vertices_added[1]}},
          {"seconds",
           {{"stretch", optimization.seconds_stretch},
            {"swap", optimization.seconds_swap},
            {"merge", optimization.seconds_merge}}}};
}

}  // namespace xparam::cli
