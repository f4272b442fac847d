#pragma once
/// \file
/// The metrics that order boundary swaps and patch merges (paper sections 4 and 5), as pure
/// functions of plain numbers: the metrics on Length-Preserved Base Domains (sections 4.2, 4.3,
/// 5) of per-side measures, and the dense-mesh metrics AD and L2 (section 4.1) of the map's
/// energies, which domain/dense_swap_metrics.h measures.
///
/// Notation (paper Fig. 6): layout edge (a, b) is shared by the patch (a, b, l) on the left of
/// a -> b and the patch (b, a, r) on its right; the quad's counter-clockwise corners are
/// a, r, b, l. Swapping replaces a-b by l-r, giving the patch (l, r, b) on the left of l -> r
/// and (r, l, a) on its right. Side 0 is the template (source, s), side 1 the target (t).
///
/// Each triangle's LPBD is triangle_lpbd of its three curve lengths with the corners in the
/// order written above, so angle k of the source and angle k of the target are the same corner:
///   before left  (a, b, l) from (ab, bl, la),   before right (b, a, r) from (ab, ar, rb),
///   after left   (l, r, b) from (lr, rb, bl),   after right  (r, l, a) from (lr, la, ar).
/// These are the alpha^k (before) and beta^k (after) of eq. 9 and 14, k = 1..6.

#include "domain/lpbd.h"

#include <array>
#include <optional>
#include <string_view>
#include <vector>

namespace xparam {

/// The metric that orders boundary swaps (paper section 4).
enum class SwapMetric {
  none,     ///< no swapping (stretching and merging still run)
  ad,       ///< angle distortion of the map on the dense meshes, eq. 3-4 (DenseSwapMeasures)
  l2,       ///< L2-stretch of the map on the dense meshes, eq. 5-7 (DenseSwapMeasures)
  area,     ///< area similarity, eq. 8
  dad,      ///< domain angle distortion, eq. 9
  dl2,      ///< domain L2-stretch, eq. 10-12
  sdl,      ///< shorter diagonal length, eq. 13
  gar,      ///< greatest angle reduction, eq. 14
  balanced  ///< SDL on the active curves by DL2 and the degenerate ones (section 4.3)
};

/// Every metric, in option order (none, ad, l2, area, dad, dl2, sdl, gar, balanced).
const std::vector<SwapMetric>& all_swap_metrics();

/// The option name of a metric ("none", "ad", "l2", "area", "dad", "dl2", "sdl", "gar", "balanced").
std::string_view to_string(SwapMetric metric);

/// True for the metrics measured on the dense meshes (ad, l2), whose keys need DenseSwapMeasures.
bool is_dense_metric(SwapMetric metric);

/// The metric named `name`; InputError listing the names for anything else.
SwapMetric parse_swap_metric(std::string_view name);

/// One side's measures of the quad a-r-b-l around layout edge (a, b). Lengths are the 3-D
/// lengths of the boundary curves, areas the surface areas of the patches (3-D units).
struct SwapSideMeasures {
  double ar = 0.0, rb = 0.0, bl = 0.0, la = 0.0;  ///< the quad's four sides
  double ab = 0.0;                                ///< the curve being swapped
  double lr = 0.0;                                ///< the curve that would replace it
  std::array<double, 2> area_before{};  ///< patches (a, b, l) [0] and (b, a, r) [1]
  std::array<double, 2> area_after{};   ///< patches (l, r, b) [0] and (r, l, a) [1]
};

/// Both sides: [0] template, [1] target.
using SwapMeasures = std::array<SwapSideMeasures, 2>;

/// The four LPBD triangles of one side: before left/right, after left/right (file comment).
struct SwapLpbds {
  std::array<Lpbd, 2> before;
  std::array<Lpbd, 2> after;
};

/// The LPBD triangles of one side's quad, with the corner orders of the file comment.
SwapLpbds swap_lpbds(const SwapSideMeasures& side);

/// The LPBDs of the two triangles before the swap (reads ar, rb, bl, la, ab only).
std::array<Lpbd, 2> before_lpbds(const SwapSideMeasures& side);

/// The LPBDs of the two triangles after the swap (reads ar, rb, bl, la, lr only).
std::array<Lpbd, 2> after_lpbds(const SwapSideMeasures& side);

/// True when the two triangles before the swap have valid LPBDs on both sides (before fields only).
bool lpbds_valid_before(const SwapMeasures& measures);

/// True when the two triangles after the swap have valid LPBDs on both sides.
bool lpbds_valid_after(const SwapMeasures& measures);

/// psi of eq. 8: A(P)/A(B) when the patch's surface area A(P) is at least its LPBD's area
/// A(B), else -A(B)/A(P). \pre both areas > 0
double area_psi(double surface_area, double lpbd_area);

/// Area similarity, eq. 8: E_area(a-b) - E_area(l-r), with E_area of a curve the sum over its
/// left and right patch of (psi_s - psi_t)^2. The paper prints the difference the other way
/// round, which would favour swaps that make the domains less similar and contradicts "the
/// greater the better" of Algorithm 1; we take before minus after like eq. 4, 7, 9 and 10.
double area_metric(const SwapMeasures& measures);

/// Domain angle distortion, eq. 9: sum_k ((alpha_s - alpha_t)/alpha_s)^2 over the six angles
/// before minus the same over the six after. A zero source angle gives +infinity for its
/// term (0 when the target angle is zero too), so the value is never NaN.
double dad_metric(const SwapMeasures& measures);

/// L2-stretch (eq. 5) between a source and a target LPBD triangle, normalized by eq. 6 taken
/// over this one triangle: L2 * sqrt(A_t / A_s) = sqrt((sigma_1^2 + sigma_2^2) / (2 sigma_1
/// sigma_2)), sigma the singular values of the affine map between the triangles. Direction as
/// eq. 5 is written: the 3-D points p are the source corners and (s, t) the target corners, so
/// the Jacobian is that of the map target -> source. After the normalization the value is the
/// same in both directions (sigma -> 1/sigma leaves it unchanged) and for any scale of either
/// triangle, which is what lets section 4.3's threshold compare to 2.0 (two identical
/// shapes) and keeps meshes of different sizes comparable; it is 1 exactly for similar
/// triangles. Degenerate triangles use their LPBD area 1e-8 and collinear corners, which makes
/// the value very large. Corners are matched by index.
double triangle_l2_stretch(const Lpbd& source, const Lpbd& target);

/// E_DL2 of the curve a-b, eq. 11: L2 of the left plus the right triangle before swapping.
/// Uses only the lengths ar, rb, bl, la, ab.
double dl2_energy_before(const SwapMeasures& measures);

/// E_DL2 of the curve l-r, eq. 12: L2 of the left plus the right triangle after swapping.
double dl2_energy_after(const SwapMeasures& measures);

/// Domain L2-stretch, eq. 10: dl2_energy_before - dl2_energy_after.
double dl2_metric(const SwapMeasures& measures);

/// How much longer than the old curve the new one may be on either side before SDL refuses
/// the swap (section 4.2: "l-r longer than 2 a-b on one side" is the paper's example).
inline constexpr double kSdlMaxElongation = 2.0;

/// Shorter diagonal length, eq. 13: 2 - (lr_s/ab_s + lr_t/ab_t).
double sdl_metric(const SwapMeasures& measures);

/// SDL's refusal: the new curve is more than kSdlMaxElongation times the old one on a side
/// ("either side has become much worse"). Both sides elongated is refused by eq. 13's sign.
bool sdl_refuses(const SwapMeasures& measures);

/// Greatest angle reduction, eq. 14: the greatest of the twelve LPBD angles before minus the
/// greatest after. Angles come from law_of_cosines_angle, so a degenerate triangle's angles
/// follow the paper's rule (possibly above pi).
double gar_metric(const SwapMeasures& measures);

/// The distortion of the cross-parameterization over the quad's two patches before and after
/// the swap (paper section 4.1; domain/dense_swap_metrics.h measures them): E_ang of eq. 3 and
/// E_L2 of eq. 6 over the (refined) template faces of the patches (a, b, l), (b, a, r) before
/// and (l, r, b), (r, l, a) after. +infinity stands for a map that cannot be measured (a
/// degenerate image triangle, a patch that cannot be parameterized).
struct DenseSwapMeasures {
  double e_ang_before = 0.0;  ///< eq. 3 of the curve a-b, >= 0
  double e_ang_after = 0.0;   ///< eq. 3 of the curve l-r, >= 0
  double e_l2_before = 1.0;   ///< eq. 6 over the two patches of a-b, >= 1
  double e_l2_after = 1.0;    ///< eq. 6 over the two patches of l-r, >= 1
};

/// Size of the rounding noise of a dense energy (sparse solves, point location), relative to
/// the larger energy and at least absolute (both energies are dimensionless): energies closer
/// than this are the same map measured twice.
inline constexpr double kDenseNoise = 1e-9;

/// The improvement `before - after` of two energies where +infinity means "not measurable":
/// -infinity when `after` is infinite (whatever `before`: a swap to a map that cannot be
/// measured, or has a collapsed triangle, is never an improvement), +infinity when only
/// `before` is (any measurable map improves on it), 0 when they differ by at most
/// kDenseNoise * max(1, before, after) (else a swap between two equally good maps would be a
/// candidate by rounding), else the difference. Never NaN.
double dense_improvement(double before, double after);

/// Angle distortion metric, eq. 4: dense_improvement(e_ang_before, e_ang_after).
double ad_metric(const DenseSwapMeasures& dense);

/// L2-stretch metric, eq. 7: dense_improvement(e_l2_before, e_l2_after).
double l2_metric(const DenseSwapMeasures& dense);

/// The golden ratio phi of section 4.3.
inline constexpr double kBalancedPhi = 0.618;

/// The activity threshold of the balanced algorithm (section 4.3, step 2):
/// 2.0 + (1 - phi) * max(E_DL2 - 2.0) over `energies`; a curve is active when its E_DL2 is
/// above it. 2.0 when `energies` is empty.
double balanced_threshold(const std::vector<double>& energies);

/// A curve winds on a side when it is longer than this many times the straight distance between
/// its two anchors there.
inline constexpr double kWindingRatio = 3.0;

/// Whether a curve winds on both sides (`lengths`: the curve's length per side, `chords`: the
/// straight distance between its anchors per side): a completion curve pushed round a limb or the
/// head by the curves already laid (SHREC'19 26 with the 73 CAESAR landmarks: Sellion to
/// Supramenton, 10 cm apart, by a 1.04 m curve down the back and up the chest on both meshes).
/// Its patches are alike on both sides, so the balanced algorithm's threshold does not see it.
bool winds(const std::array<double, 2>& lengths, const std::array<double, 2>& chords);

/// The heap key of a swap. Algorithm 1 pops the greatest: a swap that makes an invalid LPBD
/// valid (`repairs`) before any other, then by `value`.
struct SwapKey {
  bool repairs = false;  ///< some LPBD before the swap is invalid (and all after are valid)
  double value = 0.0;    ///< the metric; finite or +infinity, never NaN
  friend bool operator==(const SwapKey&, const SwapKey&) = default;
};

/// Strict order of swap keys: repairs first, then the greater value.
bool operator<(const SwapKey& lhs, const SwapKey& rhs);

/// The key of a swap under `metric` (balanced uses SDL), or nullopt when the swap is not a
/// candidate: it would leave an invalid LPBD (section 4: "the operation must be prevented"),
/// SDL refuses it (sdl_refuses, for sdl and balanced), it repairs nothing and the metric is
/// not positive (Algorithm 1 inserts only values > 0), or (ad, l2) the map after the swap is
/// not measurable (an infinite after-energy: even a repair must not lead to a collapsed map).
/// `dense` gives the energies of ad and l2 and is ignored by the others.
/// \pre metric != none; `dense` given when is_dense_metric(metric)
std::optional<SwapKey> swap_key(SwapMetric metric, const SwapMeasures& measures,
                                const std::optional<DenseSwapMeasures>& dense = std::nullopt);

/// One side's measures of merging the two patches of layout edge (a, b) into the quad
/// a-r-b-l (paper section 5, Fig. 9).
struct MergeSideMeasures {
  std::array<double, 4> sides{};  ///< curve lengths a-r, r-b, b-l, l-a (3-D units)
  double ab = 0.0;                ///< the curve that merging removes
  /// Surface angles theta at the quad corners a, r, b, l (radians): at a and b the sum of the
  /// two triangles' corner angles.
  std::array<double, 4> surface_angles{};
};

/// Both sides: [0] template, [1] target.
using MergeMeasures = std::array<MergeSideMeasures, 2>;

/// The merge metric, eq. 15: (1/6) sum |alpha_s - alpha_t| over the six angles of the two
/// triangle LPBDs minus (1/4) sum |gamma_s - gamma_t| over the four angles of the quad LPBD
/// (polygon_lpbd of the sides and surface angles, eq. 2). nullopt (the paper's -infinity) for
/// the three refusals of section 5: `quad_neighbour` (a patch of the edge is a quad already),
/// a side of the quad at least as long as the other three together on either side, or a quad
/// LPBD angle above pi on either side; also when eq. 2 has no valid solution.
std::optional<double> merge_metric(const MergeMeasures& measures, bool quad_neighbour);

}  // namespace xparam
