#pragma once
/// \file
/// Small toes as rows beside a matched tip (ours, beyond the paper; ARCHITECTURE step 9): toes
/// shorter than the tip reach are no tips of their own (map/extremity_anchors.h), so each matched
/// tip's row of short tips is aligned with its partner's, through the first map and by a rigid fit
/// of the template's foot onto the target.

#include "core/closest_point.h"
#include "map/extremity_anchors.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace xparam {

/// Short tips (small toes) are the extremities (`extremities`) at this fraction of the tip reach:
/// at the full reach a small toe is no tip of its own, the foot ends in the big toe alone.
constexpr double kShortTipReach = 1.0 / 3.0;
/// A row beside a matched tip reaches this many tip reaches from it.
constexpr double kRowReaches = 3.0;
/// What leaving a short tip out of a row's alignment costs, against a pair's cost (fractions of
/// sqrt(area)): a spurious bump beside the big toe, or a toe one mesh lacks, is left out rather
/// than sliding every pair after it by one.
constexpr double kRowSkipCost = 0.02;
/// A pair's cost in a row: kRowMissWeight times its mismatch through the first map
/// (ExtremityAnchor::mismatch) plus this many times the difference of the two tips' distances from
/// the row's matched tip. Where the first map slid a foot's toes by one, the mismatch alone paired
/// them slid (FAUST 000/020 [29]: 0.031 + 0.024 and two tips left out against 0.044 + 0.035 + 0.030
/// for the right pairs); the distances from the big toe do not depend on the map (the right pairs
/// differ by 0.001-0.003, the slid ones by 0.014).
constexpr double kRowDistanceWeight = 2.0;
/// The mismatch's weight in a pair's cost. Where the first map squeezed the small toes into whorls,
/// the right pairs miss by 0.037-0.044 sqrt(area) through it, more than leaving both tips out
/// (2 kRowSkipCost), and at full weight the row was left out whole (FAUST 000/080 [73]'s right foot:
/// distances from the big toe agreeing to 0.001, the foot 0.62% sqrt(A) from the truth, 0.16% with
/// the row). At 0.5 rows formed that cost TOSCA centaur0/1 three strict folds (session 34).
constexpr double kRowMissWeight = 0.75;

/// The cheapest monotone alignment of two rows of n and m items, as in sequence alignment: pairs
/// (i, j) with i and j both increasing, each costing pair_cost(i, j) (infinite: never paired), every
/// item left unpaired costing skip_cost. On a tie a pair is preferred, then leaving out the first
/// row's item. Returns the pairs in increasing order.
std::vector<std::pair<int, int>> align_rows(int n, int m, const std::function<double(int, int)>& pair_cost,
                                            double skip_cost);

/// Small toes as rows (session 33). Toes shorter than the tip reach are no tips, and the
/// optimization squeezes them together where the first map did. Each tip in `matched` gets a row
/// on each mesh: the short tips (`source_short`, `target_short`: extremities at kShortTipReach of
/// the reach) nearer it than any other matched tip, beyond kShortTipReach and within kRowReaches
/// reaches of it, in order of distance from it. The two rows are aligned (align_rows): a pair costs
/// kRowMissWeight times its mismatch through `map` (infinite from max_mismatch on) plus
/// kRowDistanceWeight times the difference of its distances from the matched tip, a short tip left
/// out kRowSkipCost. Ranking the rows alone slid every toe by one beside a spurious bump or a missing
/// toe (3 of 6 FAUST feet). Names as in match_extremities_by_cell.
std::vector<ExtremityAnchor> match_short_tip_rows(const TipsAndAnchors& source,
                                                  const std::vector<int>& source_short,
                                                  const TipsAndAnchors& target,
                                                  const std::vector<int>& target_short, const FirstMap& map,
                                                  const std::vector<ExtremityAnchor>& matched,
                                                  const std::vector<std::string>& taken, double max_mismatch);

/// How near (mean distance, fraction of sqrt(target area)) a rigid fit must lay a row's region onto
/// the target for its pairs to count (fit_tip_rows). FAUST feet against other subjects' feet:
/// 0.00046-0.00091 (about a millimetre); hands, whose fingers bend between poses: 0.0013-0.0057.
constexpr double kFitFarthest = 0.0012;
/// A pair of the fit lies at most this far apart once the template's tip is moved by it, as a
/// fraction of sqrt(target area): the right toes of the FAUST feet 0.0003-0.0057, a toe over 0.0129
/// or more.
constexpr double kFitPairApart = 0.008;
/// ... and every other candidate on either mesh lies at least this many times as far.
constexpr double kFitClearance = 2.0;
/// The fit's steps end when no point moves by more than this fraction of the tip reach, or after
/// kFitSteps steps.
constexpr double kFitTolerance = 4e-4;
constexpr int kFitSteps = 50;

/// A row of match_short_tip_rows paired by a rigid fit: the template's tip and its row, the
/// target's tip and its row, and the pairs the fit finds among them.
struct FittedRow {
  int tip = -1;             ///< index into `matched` of the row's tip
  std::vector<int> source;  ///< the template's tip, then its row (input vertices)
  std::vector<int> target;  ///< the target's tip, then its row
  /// Pairs among them: the row's tip (its name kept, with the partner the fit gives it; absent when
  /// the fit pairs it with nothing), then small toes (TipMatching::in_row, named as in
  /// match_short_tip_rows).
  std::vector<ExtremityAnchor> pairs;
};

/// Small toes paired by the shape of the foot rather than through the first map (session 38). The
/// first map can turn a forefoot by one toe (FAUST 000/090 and 000/010 with 29 landmarks: every
/// template toe on the target's next one), and then its tip is matched with the wrong toe and its
/// row aligned beside it one toe over; the mismatches do not tell (right and wrong pairs miss alike).
/// Here the template's surface within kRowReaches reaches of the row's tip is laid onto the target
/// rigidly (fit_to_surface, map/rigid_fit.h: from the fit to its images through `map`, and from that
/// fit moved to put the tip on each of the target's tip and row, the nearest fit kept). Where it lays
/// the region within kFitFarthest of the target (a foot, not a hand whose fingers bend), a template
/// toe and a target toe are paired when the fit puts them within kFitPairApart and every other
/// candidate kFitClearance times as far. On the FAUST feet every such pair agrees with the truth.
/// One FittedRow per row of match_short_tip_rows with a short tip on either mesh whose fit holds.
/// `target_surface` is a nearest-point index over target.mesh.
std::vector<FittedRow> fit_tip_rows(const TipsAndAnchors& source, const std::vector<int>& source_short,
                                    const TipsAndAnchors& target, const std::vector<int>& target_short,
                                    const FirstMap& map, const std::vector<ExtremityAnchor>& matched,
                                    const std::vector<std::string>& taken,
                                    const ClosestPointIndex& target_surface);

}  // namespace xparam
