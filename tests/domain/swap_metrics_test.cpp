#include "domain/swap_metrics.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace xparam {
namespace {

const double kSqrt2 = std::sqrt(2.0);

// A quad a-r-b-l whose five curves have the lengths of a planar quad, the new diagonal given.
SwapSideMeasures quad(double side, double ab, double lr) {
  SwapSideMeasures m;
  m.ar = m.rb = m.bl = m.la = side;
  m.ab = ab;
  m.lr = lr;
  return m;
}

// The rhombus a(0,0), r(1,-1/2), b(2,0), l(1,1/2): sides sqrt(5/4), a-b = 2, l-r = 1.
SwapSideMeasures rhombus() { return quad(std::sqrt(1.25), 2.0, 1.0); }

// The unit square a(0,0), r(1,0), b(1,1), l(0,1): both diagonals sqrt(2).
SwapSideMeasures unit_square() { return quad(1.0, kSqrt2, kSqrt2); }

TEST(SwapMetricNames, RoundTripAndUnknownNames) {
  for (const char* name : {"none", "ad", "l2", "area", "dad", "dl2", "sdl", "gar", "balanced"}) {
    EXPECT_EQ(to_string(parse_swap_metric(name)), name);
  }
  EXPECT_EQ(all_swap_metrics().size(), 9u);
  for (SwapMetric metric : all_swap_metrics()) {
    EXPECT_EQ(parse_swap_metric(to_string(metric)), metric);
    EXPECT_EQ(is_dense_metric(metric), metric == SwapMetric::ad || metric == SwapMetric::l2) << to_string(metric);
  }
  EXPECT_THROW(parse_swap_metric("SDL"), InputError);
  EXPECT_THROW(parse_swap_metric("L2"), InputError);
  try {
    parse_swap_metric("fast");
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("balanced"), std::string::npos) << error.what();
  }
}

TEST(SwapLpbds, CornerOrderOfTheFourTriangles) {
  // Lengths from the kite a(0,0), r(3,0), b(3,4), l(0,4) cut differently: sides 3, 4, 3, 4.
  SwapSideMeasures m;
  m.ar = 3.0, m.rb = 4.0, m.bl = 3.0, m.la = 4.0, m.ab = 5.0, m.lr = 5.0;
  const SwapLpbds lpbds = swap_lpbds(m);
  // before left (a, b, l) = (ab, bl, la) = (5, 3, 4): the right angle is at l.
  EXPECT_NEAR(lpbds.before[0].angles[2], std::numbers::pi / 2, 1e-15);
  // before right (b, a, r) = (ab, ar, rb) = (5, 3, 4): right angle at r; angle at a faces rb = 4.
  EXPECT_NEAR(lpbds.before[1].angles[2], std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR(lpbds.before[1].angles[1], std::acos(3.0 / 5.0), 1e-15);
  // after left (l, r, b) = (lr, rb, bl) = (5, 4, 3): right angle at b; after right (r, l, a):
  // right angle at a.
  EXPECT_NEAR(lpbds.after[0].angles[2], std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR(lpbds.after[1].angles[2], std::numbers::pi / 2, 1e-15);
}

TEST(WindingCurves, LongerThanThreeChordsOnBothSides) {
  // Sellion to Supramenton on SHREC'19 26 [73 CAESAR]: 10 cm apart, a 1.04 m (1.19 m) curve.
  EXPECT_TRUE(winds({1.04, 1.19}, {0.097, 0.095}));
  // Winding on one side only: the LPBDs differ, which the balanced threshold sees already.
  EXPECT_FALSE(winds({1.04, 0.12}, {0.097, 0.095}));
  EXPECT_FALSE(winds({0.12, 1.19}, {0.097, 0.095}));
  // At exactly kWindingRatio chords it does not wind yet; just above, it does.
  EXPECT_FALSE(winds({3.0, 3.0}, {1.0, 1.0}));
  EXPECT_TRUE(winds({3.0 + 1e-9, 3.0 + 1e-9}, {1.0, 1.0}));
  // A geodesic round a curved surface is longer than its chord, by far less than that.
  EXPECT_FALSE(winds({M_PI / 2.0, M_PI / 2.0}, {std::sqrt(2.0), std::sqrt(2.0)}));
}

TEST(AreaMetric, PsiAndEquationEightByHand) {
  EXPECT_DOUBLE_EQ(area_psi(3.0, 2.0), 1.5);
  EXPECT_DOUBLE_EQ(area_psi(2.0, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(area_psi(2.0, 3.0), -1.5);
  // The degenerate LPBD area 1e-8 makes psi huge.
  EXPECT_DOUBLE_EQ(area_psi(1.0, kDegenerateLpbdArea), 1e8);

  // Source rhombus: all four LPBD triangles have area 1/2. Target square: all 1/2 too. (Areas
  // equal to the LPBD's are avoided: psi jumps from +1 to -1 there, and Heron's rounding picks
  // the side.)
  SwapMeasures m = {rhombus(), unit_square()};
  m[0].area_before = {0.6, 0.45};   // psi 1.2, -10/9
  m[1].area_before = {0.75, 0.4};   // psi 1.5, -1.25
  m[0].area_after = {0.55, 0.4};    // psi 1.1, -1.25
  m[1].area_after = {0.6, 0.625};   // psi 1.2, 1.25
  const double before = 0.3 * 0.3 + (1.25 - 10.0 / 9.0) * (1.25 - 10.0 / 9.0);
  const double after = 0.1 * 0.1 + 2.5 * 2.5;
  EXPECT_NEAR(area_metric(m), before - after, 1e-12);
  // Before minus after: the right patches become less alike, so the metric is against it.
  EXPECT_LT(area_metric(m), 0.0);
}

TEST(DadMetric, RhombusAgainstSquareByHand) {
  const SwapMeasures m = {rhombus(), unit_square()};
  // Rhombus before: (a, b, l) has atan(1/2) at a and b and pi - 2 atan(1/2) at l; the square's
  // triangles have pi/4, pi/4, pi/2. After: (l, r, b) has atan(2) at l and r, 2 atan(1/2) at b.
  const double t = std::atan(0.5);
  const auto rel2 = [](double s, double tt) { return ((s - tt) / s) * ((s - tt) / s); };
  const double before =
      2.0 * (2.0 * rel2(t, std::numbers::pi / 4) + rel2(std::numbers::pi - 2.0 * t, std::numbers::pi / 2));
  const double after =
      2.0 * (2.0 * rel2(std::atan(2.0), std::numbers::pi / 4) + rel2(2.0 * t, std::numbers::pi / 2));
  EXPECT_NEAR(dad_metric(m), before - after, 1e-12);
  EXPECT_GT(dad_metric(m), 0.0);  // the long diagonal of the rhombus is the one to swap
  // Identical sides: no distortion either way.
  EXPECT_DOUBLE_EQ(dad_metric({rhombus(), rhombus()}), 0.0);
}

TEST(TriangleL2Stretch, HandValuesScaleAndDirection) {
  const Lpbd right = triangle_lpbd(1.0, kSqrt2, 1.0);  // (0,0), (1,0), (0,1)
  const Lpbd equilateral = triangle_lpbd(1.0, 1.0, 1.0);
  // Map equilateral -> right isoceles: J = [[1, -1/sqrt3], [0, 2/sqrt3]], |J|_F^2 = 8/3,
  // det = 2/sqrt3: sqrt((8/3) / (2 * 2/sqrt3)) = sqrt(2/sqrt3).
  EXPECT_NEAR(triangle_l2_stretch(right, equilateral), std::sqrt(2.0 / std::sqrt(3.0)), 1e-14);
  EXPECT_NEAR(triangle_l2_stretch(equilateral, right), std::sqrt(2.0 / std::sqrt(3.0)), 1e-14);
  // Similar triangles: exactly 1 whatever the scale.
  EXPECT_NEAR(triangle_l2_stretch(triangle_lpbd(3.0, 4.0, 5.0), triangle_lpbd(0.3, 0.4, 0.5)), 1.0, 1e-14);
  EXPECT_NEAR(triangle_l2_stretch(right, triangle_lpbd(7.0, 7.0 * kSqrt2, 7.0)), 1.0, 1e-14);
  // A degenerate triangle (LPBD area 1e-8) is very far from any real one.
  EXPECT_GT(triangle_l2_stretch(triangle_lpbd(3.0, 1.0, 1.0), equilateral), 1e3);
}

TEST(Dl2Metric, RhombusAgainstSquareAndALongerNewCurve) {
  // Rhombus vs square: each triangle pair is related by diag(sqrt2, 1/sqrt2) (before) and
  // diag(1/sqrt2, sqrt2) (after): sqrt((2 + 1/2) / 2) per triangle, so both energies are sqrt5.
  const SwapMeasures m = {rhombus(), unit_square()};
  EXPECT_NEAR(dl2_energy_before(m), std::sqrt(5.0), 1e-14);
  EXPECT_NEAR(dl2_energy_after(m), std::sqrt(5.0), 1e-14);
  EXPECT_NEAR(dl2_metric(m), 0.0, 1e-14);
  // Same quad on both sides but the target's l-r curve is 2 long instead of 1: before identical
  // (E = 2); after (1, s, s) against (2, s, s) is diag(1/2, 2): sqrt((1/4 + 4) / 2) each.
  SwapMeasures longer = {rhombus(), rhombus()};
  longer[1].lr = 2.0;
  EXPECT_NEAR(dl2_energy_before(longer), 2.0, 1e-14);
  EXPECT_NEAR(dl2_metric(longer), 2.0 - 2.0 * std::sqrt(2.125), 1e-13);
}

TEST(SdlMetric, ValueAndRefusals) {
  // Rhombus: l-r is half of a-b; square: equal. 2 - (0.5 + 1).
  EXPECT_DOUBLE_EQ(sdl_metric({rhombus(), unit_square()}), 0.5);
  EXPECT_FALSE(sdl_refuses({rhombus(), unit_square()}));
  // The paper's example: shorter on the source, more than twice a-b on the target.
  SwapMeasures worse = {rhombus(), rhombus()};
  worse[1].lr = 4.5;  // a-b is 2
  EXPECT_TRUE(sdl_refuses(worse));
  worse[1].lr = 4.0;  // exactly twice: allowed by the rule (eq. 13 is negative anyway)
  EXPECT_FALSE(sdl_refuses(worse));
  EXPECT_DOUBLE_EQ(sdl_metric(worse), 2.0 - (0.5 + 2.0));
}

TEST(GarMetric, RhombusAgainstSquareAndDegenerateAngles) {
  // Greatest before: pi - 2 atan(1/2) (rhombus at l, r); after: the square's pi/2.
  EXPECT_NEAR(gar_metric({rhombus(), unit_square()}),
              std::numbers::pi - 2.0 * std::atan(0.5) - std::numbers::pi / 2, 1e-14);
  // A degenerate source triangle (a-b = 3 > 1 + 1): cos = (1 + 1 - 9) / 2 = -3.5 -> 3.5 pi
  // (paper's rule), so the swap that removes it reduces the greatest angle hugely.
  SwapMeasures degenerate = {quad(1.0, 3.0, 1.0), unit_square()};
  EXPECT_NEAR(gar_metric(degenerate), 3.5 * std::numbers::pi - std::numbers::pi / 2, 1e-13);
}

TEST(BalancedThreshold, GoldenRatioRule) {
  EXPECT_DOUBLE_EQ(balanced_threshold({}), 2.0);
  EXPECT_DOUBLE_EQ(balanced_threshold({2.0, 2.0}), 2.0);  // all identical: nothing is above 2
  // max excess 1.0 -> 2 + 0.382.
  EXPECT_NEAR(balanced_threshold({2.5, 3.0, 2.1}), 2.382, 1e-15);
  EXPECT_NEAR(balanced_threshold({2.0, 12.0}), 2.0 + 0.382 * 10.0, 1e-14);
}

TEST(SwapKey, OrderRepairsFirstThenValue) {
  EXPECT_LT((SwapKey{false, 5.0}), (SwapKey{true, -1.0}));
  EXPECT_LT((SwapKey{false, 0.1}), (SwapKey{false, 0.2}));
  EXPECT_LT((SwapKey{true, 0.1}), (SwapKey{true, 0.2}));
  EXPECT_FALSE((SwapKey{true, 0.2}) < (SwapKey{true, 0.2}));
}

TEST(SwapKey, CandidatesRefusalsAndRepairs) {
  const SwapMeasures good = {rhombus(), unit_square()};
  ASSERT_TRUE(swap_key(SwapMetric::sdl, good).has_value());
  EXPECT_FALSE(swap_key(SwapMetric::sdl, good)->repairs);
  EXPECT_DOUBLE_EQ(swap_key(SwapMetric::sdl, good)->value, 0.5);
  EXPECT_DOUBLE_EQ(swap_key(SwapMetric::balanced, good)->value, 0.5);
  // Non-positive values are no candidates: the square swapped to the square (SDL 0, DL2 0).
  EXPECT_FALSE(swap_key(SwapMetric::sdl, {unit_square(), unit_square()}).has_value());
  EXPECT_FALSE(swap_key(SwapMetric::dl2, good).has_value());
  // A swap that leaves a degenerate LPBD is refused whatever the metric: l-r = 2.5 > 1 + 1.
  SwapMeasures breaks = {unit_square(), unit_square()};
  breaks[1].lr = 2.5;
  for (SwapMetric metric : {SwapMetric::area, SwapMetric::dad, SwapMetric::dl2, SwapMetric::sdl, SwapMetric::gar}) {
    SwapMeasures with_areas = breaks;
    for (auto& side : with_areas) side.area_before = side.area_after = {0.5, 0.5};
    EXPECT_FALSE(swap_key(metric, with_areas).has_value()) << to_string(metric);
  }
  // A repair: source a-b = 3 is degenerate, the swap makes every LPBD valid. It is a candidate
  // with the repair flag even where its metric value is negative.
  SwapMeasures repair = {quad(1.0, 3.0, 1.9), unit_square()};
  for (auto& side : repair) side.area_before = side.area_after = {0.5, 0.5};
  for (SwapMetric metric : {SwapMetric::area, SwapMetric::dad, SwapMetric::dl2, SwapMetric::sdl, SwapMetric::gar}) {
    const auto key = swap_key(metric, repair);
    ASSERT_TRUE(key.has_value()) << to_string(metric);
    EXPECT_TRUE(key->repairs) << to_string(metric);
    EXPECT_FALSE(std::isnan(key->value)) << to_string(metric);
  }
  // SDL value 2 - (1.9/3 + 1) > 0 here; an elongation above 2 on a side refuses even a repair.
  repair[1].lr = 1.5;  // keeps the square's after-triangles valid (1.5 < 2)
  repair[0].lr = 1.9;
  EXPECT_TRUE(swap_key(SwapMetric::sdl, repair).has_value());
  SwapMeasures repair_refused = {quad(1.0, 3.0, 1.9), quad(1.0, 0.7, 1.5)};
  EXPECT_TRUE(sdl_refuses(repair_refused));  // 1.5 > 2 * 0.7
  EXPECT_FALSE(swap_key(SwapMetric::sdl, repair_refused).has_value());
  EXPECT_TRUE(swap_key(SwapMetric::gar, repair_refused).has_value());
}

TEST(DenseSwapKey, EquationsFourAndSevenAndTheUnmeasurableRule) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const DenseSwapMeasures dense = {0.30, 0.10, 1.50, 1.75};  // AD improves by 0.2, L2 worsens by 0.25
  EXPECT_DOUBLE_EQ(ad_metric(dense), 0.30 - 0.10);
  EXPECT_DOUBLE_EQ(l2_metric(dense), 1.50 - 1.75);
  EXPECT_EQ(dense_improvement(kInf, 2.0), kInf);
  EXPECT_EQ(dense_improvement(2.0, kInf), -kInf);
  EXPECT_EQ(dense_improvement(kInf, kInf), -kInf);  // never NaN
  EXPECT_EQ(dense_improvement(1.25, 1.25 * (1 + 1e-12)), 0.0);  // rounding noise is no change
  EXPECT_EQ(dense_improvement(1.25 * (1 + 1e-12), 1.25), 0.0);
  EXPECT_GT(dense_improvement(1.25 * (1 + 1e-7), 1.25), 0.0);
  EXPECT_EQ(dense_improvement(3e-12, 1e-12), 0.0);  // E_ang near zero: absolute noise

  const SwapMeasures good = {rhombus(), unit_square()};  // valid LPBDs before and after
  const auto ad = swap_key(SwapMetric::ad, good, dense);
  ASSERT_TRUE(ad.has_value());
  EXPECT_FALSE(ad->repairs);
  EXPECT_DOUBLE_EQ(ad->value, 0.2);
  EXPECT_FALSE(swap_key(SwapMetric::l2, good, dense).has_value());  // not positive
  // An unmeasurable current map: any measurable swap is an improvement.
  const auto from_broken = swap_key(SwapMetric::l2, good, DenseSwapMeasures{kInf, 0.1, kInf, 1.2});
  ASSERT_TRUE(from_broken.has_value());
  EXPECT_EQ(from_broken->value, kInf);
  // An unmeasurable map after the swap is refused, even for a repair.
  SwapMeasures repair = {quad(1.0, 3.0, 1.9), unit_square()};
  const DenseSwapMeasures to_broken = {0.3, kInf, 1.5, kInf};
  EXPECT_FALSE(swap_key(SwapMetric::ad, good, to_broken).has_value());
  EXPECT_FALSE(swap_key(SwapMetric::l2, repair, to_broken).has_value());
  // A repair that worsens the map is still a candidate, first in the heap.
  const auto repair_key = swap_key(SwapMetric::l2, repair, dense);
  ASSERT_TRUE(repair_key.has_value());
  EXPECT_TRUE(repair_key->repairs);
  EXPECT_DOUBLE_EQ(repair_key->value, -0.25);
  // A degenerate LPBD after the swap is refused whatever the map: l-r = 2.5 > 1 + 1.
  SwapMeasures breaks = {unit_square(), unit_square()};
  breaks[1].lr = 2.5;
  EXPECT_FALSE(swap_key(SwapMetric::ad, breaks, dense).has_value());
}

// A square quad on both sides with right surface angles, a-b given per side.
MergeMeasures square_merge(double ab_source, double ab_target) {
  MergeMeasures m;
  for (auto& side : m) {
    side.sides = {1.0, 1.0, 1.0, 1.0};
    side.surface_angles = {std::numbers::pi / 2, std::numbers::pi / 2, std::numbers::pi / 2,
                           std::numbers::pi / 2};
  }
  m[0].ab = ab_source;
  m[1].ab = ab_target;
  return m;
}

TEST(MergeMetric, HandValues) {
  // Identical squares: 0 - 0.
  EXPECT_NEAR(*merge_metric(square_merge(kSqrt2, kSqrt2), false), 0.0, 1e-12);
  // Same square quad, but the target's a-b curve is 1.6 long: the target triangles (1.6, 1, 1)
  // have c = acos(-0.28) at l and r and (pi - c)/2 at a and b; the quads agree. Per triangle
  // |pi/2 - c| + 2 |pi/4 - (pi - c)/2| = 2c - pi, two triangles over six.
  const double c = std::acos(-0.28);
  EXPECT_NEAR(*merge_metric(square_merge(kSqrt2, 1.6), false), (2.0 * c - std::numbers::pi) / 3.0, 1e-10);
  // Square against the rhombus a(0,0), r(1,-1/2), b(2,0), l(1,1/2) with its planar angles as the
  // surface angles: with t = atan(1/2), alpha term (2 pi - 8t)/6, gamma term (pi/2 - 2t):
  // (4t - pi)/6 < 0.
  MergeMeasures rhombus_merge = square_merge(kSqrt2, 2.0);
  const double t = std::atan(0.5);
  rhombus_merge[1].sides = {std::sqrt(1.25), std::sqrt(1.25), std::sqrt(1.25), std::sqrt(1.25)};
  rhombus_merge[1].surface_angles = {2.0 * t, std::numbers::pi - 2.0 * t, 2.0 * t,
                                     std::numbers::pi - 2.0 * t};
  EXPECT_NEAR(*merge_metric(rhombus_merge, false), (4.0 * t - std::numbers::pi) / 6.0, 1e-10);
}

TEST(MergeMetric, TheThreeRefusals) {
  const MergeMeasures good = square_merge(kSqrt2, 1.6);
  ASSERT_TRUE(merge_metric(good, false).has_value());
  // 1. A quad neighbour.
  EXPECT_FALSE(merge_metric(good, true).has_value());
  // 2. A side longer than the other three together (on the target only).
  MergeMeasures long_side = good;
  long_side[1].sides = {3.5, 1.0, 1.0, 1.0};
  long_side[1].ab = 3.0;
  EXPECT_FALSE(merge_metric(long_side, false).has_value());
  // 3. An LPBD angle above pi: the dart a(0,0), r(2,-1), b(1,0), l(2,1) is reflex at b (3 pi/2).
  MergeMeasures dart = good;
  const double at_a = 2.0 * std::atan(0.5);
  const double at_r = std::acos(3.0 / std::sqrt(10.0));
  dart[1].sides = {std::sqrt(5.0), kSqrt2, kSqrt2, std::sqrt(5.0)};
  dart[1].ab = 1.0;
  dart[1].surface_angles = {at_a, at_r, 1.5 * std::numbers::pi, at_r};
  EXPECT_FALSE(merge_metric(dart, false).has_value());
  // The same sides as the convex kite a(0,0), r(2,-1), b(3,0), l(2,1) are fine.
  const double at_r_kite = std::acos(-1.0 / std::sqrt(10.0));
  dart[1].surface_angles = {at_a, at_r_kite, std::numbers::pi / 2, at_r_kite};
  EXPECT_TRUE(merge_metric(dart, false).has_value());
}

}  // namespace
}  // namespace xparam
