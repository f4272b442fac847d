#include "domain/swap_metrics.h"

#include "core/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace xparam {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// ((source - target) / source)^2 of eq. 9, with the 0/0 and x/0 cases made explicit.
double relative_squared(double source, double target) {
  if (source == 0.0) return target == 0.0 ? 0.0 : kInfinity;
  const double relative = (source - target) / source;
  return relative * relative;
}

// Eq. 9's sum over the six angles of two triangles.
double angle_distortion(const std::array<Lpbd, 2>& source, const std::array<Lpbd, 2>& target) {
  double sum = 0.0;
  for (int t = 0; t < 2; ++t) {
    for (int k = 0; k < 3; ++k) sum += relative_squared(source[t].angles[k], target[t].angles[k]);
  }
  return sum;
}

double max_angle(const std::array<Lpbd, 2>& triangles) {
  double greatest = -kInfinity;
  for (const Lpbd& lpbd : triangles) {
    for (double angle : lpbd.angles) greatest = std::max(greatest, angle);
  }
  return greatest;
}

// E_area of a curve: the sum over its two patches of (psi_s - psi_t)^2.
double area_energy(const std::array<double, 2>& source_surface, const std::array<Lpbd, 2>& source_lpbd,
                   const std::array<double, 2>& target_surface, const std::array<Lpbd, 2>& target_lpbd) {
  double sum = 0.0;
  for (int t = 0; t < 2; ++t) {
    const double difference =
        area_psi(source_surface[t], source_lpbd[t].area) - area_psi(target_surface[t], target_lpbd[t].area);
    sum += difference * difference;
  }
  return sum;
}

bool both_valid(const std::array<Lpbd, 2>& triangles) { return triangles[0].valid && triangles[1].valid; }

}  // namespace

const std::vector<SwapMetric>& all_swap_metrics() {
  static const std::vector<SwapMetric> metrics = {SwapMetric::none, SwapMetric::ad,  SwapMetric::l2,
                                                  SwapMetric::area, SwapMetric::dad, SwapMetric::dl2,
                                                  SwapMetric::sdl,  SwapMetric::gar, SwapMetric::balanced};
  return metrics;
}

bool is_dense_metric(SwapMetric metric) { return metric == SwapMetric::ad || metric == SwapMetric::l2; }

std::string_view to_string(SwapMetric metric) {
  switch (metric) {
    case SwapMetric::none: return "none";
    case SwapMetric::ad: return "ad";
    case SwapMetric::l2: return "l2";
    case SwapMetric::area: return "area";
    case SwapMetric::dad: return "dad";
    case SwapMetric::dl2: return "dl2";
    case SwapMetric::sdl: return "sdl";
    case SwapMetric::gar: return "gar";
    case SwapMetric::balanced: return "balanced";
  }
  XP_ASSERT_MSG(false, "unknown SwapMetric " << static_cast<int>(metric));
  return {};
}

SwapMetric parse_swap_metric(std::string_view name) {
  std::string names;
  for (SwapMetric metric : all_swap_metrics()) {
    if (to_string(metric) == name) return metric;
    names += names.empty() ? "" : ", ";
    names += to_string(metric);
  }
  throw InputError("swap metric '" + std::string(name) + "' is unknown; use one of: " + names);
}

std::array<Lpbd, 2> before_lpbds(const SwapSideMeasures& side) {
  return {triangle_lpbd(side.ab, side.bl, side.la), triangle_lpbd(side.ab, side.ar, side.rb)};
}

std::array<Lpbd, 2> after_lpbds(const SwapSideMeasures& side) {
  return {triangle_lpbd(side.lr, side.rb, side.bl), triangle_lpbd(side.lr, side.la, side.ar)};
}

SwapLpbds swap_lpbds(const SwapSideMeasures& side) { return {before_lpbds(side), after_lpbds(side)}; }

bool lpbds_valid_before(const SwapMeasures& measures) {
  return both_valid(before_lpbds(measures[0])) && both_valid(before_lpbds(measures[1]));
}

bool lpbds_valid_after(const SwapMeasures& measures) {
  return both_valid(after_lpbds(measures[0])) && both_valid(after_lpbds(measures[1]));
}

double area_psi(double surface_area, double lpbd_area) {
  XP_ASSERT_MSG(surface_area > 0.0 && lpbd_area > 0.0, "areas " << surface_area << ", " << lpbd_area);
  return surface_area >= lpbd_area ? surface_area / lpbd_area : -lpbd_area / surface_area;
}

double area_metric(const SwapMeasures& measures) {
  const SwapLpbds s = swap_lpbds(measures[0]);
  const SwapLpbds t = swap_lpbds(measures[1]);
  const double before = area_energy(measures[0].area_before, s.before, measures[1].area_before, t.before);
  const double after = area_energy(measures[0].area_after, s.after, measures[1].area_after, t.after);
  return before - after;
}

double dad_metric(const SwapMeasures& measures) {
  const SwapLpbds s = swap_lpbds(measures[0]);
  const SwapLpbds t = swap_lpbds(measures[1]);
  const double before = angle_distortion(s.before, t.before);
  const double after = angle_distortion(s.after, t.after);
  // A repair may have an infinite term before; it can never have one after (all valid).
  if (before == kInfinity) return after == kInfinity ? 0.0 : kInfinity;
  return before - after;
}

double triangle_l2_stretch(const Lpbd& source, const Lpbd& target) {
  XP_ASSERT_EQ(source.corners.size(), std::size_t{3});
  XP_ASSERT_EQ(target.corners.size(), std::size_t{3});
  // Eq. 5 with p = source corners and (s, t) = target corners: the columns of the Jacobian
  // d p / d(s, t) are tau_s and tau_t, each over twice the target's area.
  const auto& p = source.corners;
  const auto& q = target.corners;
  const Eigen::Vector2d tau_s =
      ((q[1].y() - q[2].y()) * p[0] + (q[2].y() - q[0].y()) * p[1] + (q[0].y() - q[1].y()) * p[2]) /
      (2.0 * target.area);
  const Eigen::Vector2d tau_t =
      ((q[2].x() - q[1].x()) * p[0] + (q[0].x() - q[2].x()) * p[1] + (q[1].x() - q[0].x()) * p[2]) /
      (2.0 * target.area);
  const double l2_squared = 0.5 * (tau_s.squaredNorm() + tau_t.squaredNorm());
  // Eq. 6 over the single triangle: sqrt(A_t * L2^2 * A_s / A_s^2).
  return std::sqrt(l2_squared * target.area / source.area);
}

double dl2_energy_before(const SwapMeasures& measures) {
  const std::array<Lpbd, 2> s = before_lpbds(measures[0]);
  const std::array<Lpbd, 2> t = before_lpbds(measures[1]);
  return triangle_l2_stretch(s[0], t[0]) + triangle_l2_stretch(s[1], t[1]);
}

double dl2_energy_after(const SwapMeasures& measures) {
  const std::array<Lpbd, 2> s = after_lpbds(measures[0]);
  const std::array<Lpbd, 2> t = after_lpbds(measures[1]);
  return triangle_l2_stretch(s[0], t[0]) + triangle_l2_stretch(s[1], t[1]);
}

double dl2_metric(const SwapMeasures& measures) { return dl2_energy_before(measures) - dl2_energy_after(measures); }

double sdl_metric(const SwapMeasures& measures) {
  return 2.0 - (measures[0].lr / measures[0].ab + measures[1].lr / measures[1].ab);
}

bool sdl_refuses(const SwapMeasures& measures) {
  return std::any_of(measures.begin(), measures.end(),
                     [](const SwapSideMeasures& side) { return side.lr > kSdlMaxElongation * side.ab; });
}

double gar_metric(const SwapMeasures& measures) {
  const SwapLpbds s = swap_lpbds(measures[0]);
  const SwapLpbds t = swap_lpbds(measures[1]);
  return std::max(max_angle(s.before), max_angle(t.before)) - std::max(max_angle(s.after), max_angle(t.after));
}

double balanced_threshold(const std::vector<double>& energies) {
  double excess = 0.0;
  for (double energy : energies) excess = std::max(excess, energy - 2.0);
  return 2.0 + (1.0 - kBalancedPhi) * excess;
}

bool winds(const std::array<double, 2>& lengths, const std::array<double, 2>& chords) {
  return lengths[0] > kWindingRatio * chords[0] && lengths[1] > kWindingRatio * chords[1];
}

bool operator<(const SwapKey& lhs, const SwapKey& rhs) {
  if (lhs.repairs != rhs.repairs) return rhs.repairs;
  return lhs.value < rhs.value;
}

double dense_improvement(double before, double after) {
  XP_ASSERT_MSG(!std::isnan(before) && !std::isnan(after), "dense energies " << before << ", " << after);
  if (std::isinf(after)) return -kInfinity;
  if (std::isinf(before)) return kInfinity;
  const double difference = before - after;
  if (std::abs(difference) <= kDenseNoise * std::max({1.0, std::abs(before), std::abs(after)})) return 0.0;
  return difference;
}

double ad_metric(const DenseSwapMeasures& dense) { return dense_improvement(dense.e_ang_before, dense.e_ang_after); }

double l2_metric(const DenseSwapMeasures& dense) { return dense_improvement(dense.e_l2_before, dense.e_l2_after); }

std::optional<SwapKey> swap_key(SwapMetric metric, const SwapMeasures& measures,
                                const std::optional<DenseSwapMeasures>& dense) {
  XP_ASSERT(metric != SwapMetric::none);
  XP_ASSERT_MSG(!is_dense_metric(metric) || dense, "swap metric " << to_string(metric) << " needs the dense measures");
  if (!lpbds_valid_after(measures)) return std::nullopt;
  SwapKey key;
  key.repairs = !lpbds_valid_before(measures);
  switch (metric) {
    case SwapMetric::ad: key.value = ad_metric(*dense); break;
    case SwapMetric::l2: key.value = l2_metric(*dense); break;
    case SwapMetric::area: key.value = area_metric(measures); break;
    case SwapMetric::dad: key.value = dad_metric(measures); break;
    case SwapMetric::dl2: key.value = dl2_metric(measures); break;
    case SwapMetric::sdl:
    case SwapMetric::balanced:
      if (sdl_refuses(measures)) return std::nullopt;
      key.value = sdl_metric(measures);
      break;
    case SwapMetric::gar: key.value = gar_metric(measures); break;
    case SwapMetric::none: break;
  }
  XP_ASSERT_MSG(!std::isnan(key.value), "swap metric " << to_string(metric) << " is NaN");
  // An unmeasurable map after the swap (dense metrics) is refused even for a repair.
  if (is_dense_metric(metric) && key.value == -kInfinity) return std::nullopt;
  if (!key.repairs && !(key.value > 0.0)) return std::nullopt;
  return key;
}

std::optional<double> merge_metric(const MergeMeasures& measures, bool quad_neighbour) {
  if (quad_neighbour) return std::nullopt;
  std::array<std::array<Lpbd, 2>, 2> triangles;
  std::array<Lpbd, 2> quads;
  for (int side = 0; side < 2; ++side) {
    const MergeSideMeasures& m = measures[side];
    const double total = m.sides[0] + m.sides[1] + m.sides[2] + m.sides[3];
    const double longest = *std::max_element(m.sides.begin(), m.sides.end());
    if (longest >= total - longest) return std::nullopt;
    const double ar = m.sides[0], rb = m.sides[1], bl = m.sides[2], la = m.sides[3];
    triangles[side] = {triangle_lpbd(m.ab, bl, la), triangle_lpbd(m.ab, ar, rb)};
    quads[side] = polygon_lpbd({ar, rb, bl, la}, {m.surface_angles.begin(), m.surface_angles.end()});
    if (!quads[side].valid) return std::nullopt;
    for (double gamma : quads[side].angles) {
      if (gamma > std::numbers::pi) return std::nullopt;
    }
  }
  double alpha = 0.0;
  for (int t = 0; t < 2; ++t) {
    for (int k = 0; k < 3; ++k) alpha += std::abs(triangles[0][t].angles[k] - triangles[1][t].angles[k]);
  }
  double gamma = 0.0;
  for (int k = 0; k < 4; ++k) gamma += std::abs(quads[0].angles[k] - quads[1].angles[k]);
  return alpha / 6.0 - gamma / 4.0;
}

}  // namespace xparam
