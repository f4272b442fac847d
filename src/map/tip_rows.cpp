#include "map/tip_rows.h"

#include "map/rigid_fit.h"
#include "map/tip_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <variant>

namespace xparam {
namespace {

// Each matched tip's row on one mesh (side 0: the template, 1: the target): the short tips nearer
// it than any other matched tip, beyond kShortTipReach of the reach (not the tip itself) and within
// kRowReaches, as (distance from it, vertex), nearest first.
std::vector<std::vector<std::pair<double, int>>> rows_beside(const TipsAndAnchors& side,
                                                             const std::vector<int>& shorts,
                                                             const std::vector<ExtremityAnchor>& matched,
                                                             int mesh_side) {
  const double reach = side.reach * std::sqrt(surface_area(side.mesh));
  std::vector<std::vector<std::pair<double, int>>> beside(matched.size());
  for (int v : shorts) {
    const Eigen::Vector3d at = position(side.mesh, side.mesh.vertex_handle(v));
    int nearest = -1;
    double nearest_distance = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < matched.size(); ++k) {
      const int tip = std::get<AnchorVertex>(matched[k].specs[mesh_side].location).index;
      const double d = (position(side.mesh, side.mesh.vertex_handle(tip)) - at).norm();
      if (d < nearest_distance) {
        nearest_distance = d;
        nearest = static_cast<int>(k);
      }
    }
    if (nearest_distance <= kShortTipReach * reach || nearest_distance > kRowReaches * reach) continue;
    beside[nearest].push_back({nearest_distance, v});
  }
  for (auto& row : beside) std::sort(row.begin(), row.end());
  return beside;
}

// The template's surface within `radius` of vertex `center` laid onto the target rigidly: iterated
// closest points (map/rigid_fit.h) from the motion that fits the region to its images through
// `map`, and from that motion moved to put `center` on each of `starts` (the first map may have
// turned a forefoot by a toe, a distance the steps do not climb out of); the fit nearest the
// target kept (the first of equals).
SurfaceFit fit_region(const Mesh& source, int center, double radius, const FirstMap& map,
                      const ClosestPointIndex& target, const std::vector<Eigen::Vector3d>& starts) {
  const Eigen::Vector3d at = position(source, source.vertex_handle(center));
  std::vector<Eigen::Vector3d> region;
  std::vector<Eigen::Vector3d> images;
  for (VertexHandle v : source.vertices()) {
    if ((position(source, v) - at).norm() > radius) continue;
    region.push_back(position(source, v));
    images.push_back(map.images[v.idx()]);
  }
  const double tolerance = kFitTolerance * radius / kRowReaches;
  const RigidMotion through_map = fitted_motion(region, images);
  SurfaceFit best = fit_to_surface(region, target, through_map, tolerance, kFitSteps);
  for (const Eigen::Vector3d& start : starts) {
    RigidMotion moved = through_map;
    moved.translation += start - through_map(at);
    const SurfaceFit fit = fit_to_surface(region, target, moved, tolerance, kFitSteps);
    if (fit.mean_distance < best.mean_distance) best = fit;
  }
  return best;
}

}  // namespace

std::vector<std::pair<int, int>> align_rows(int n, int m, const std::function<double(int, int)>& pair_cost,
                                            double skip_cost) {
  // cost[i][j]: the cheapest alignment of the first i of one row with the first j of the other.
  std::vector<std::vector<double>> cost(n + 1, std::vector<double>(m + 1, 0.0));
  enum Step : char { kPair, kSkipFirst, kSkipSecond };
  std::vector<std::vector<Step>> step(n + 1, std::vector<Step>(m + 1, kPair));
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= m; ++j) {
      if (i == 0 && j == 0) continue;
      double best = std::numeric_limits<double>::infinity();
      if (i > 0 && j > 0) {
        const double paired = cost[i - 1][j - 1] + pair_cost(i - 1, j - 1);
        if (paired < best) {
          best = paired;
          step[i][j] = kPair;
        }
      }
      if (i > 0 && cost[i - 1][j] + skip_cost < best) {
        best = cost[i - 1][j] + skip_cost;
        step[i][j] = kSkipFirst;
      }
      if (j > 0 && cost[i][j - 1] + skip_cost < best) {
        best = cost[i][j - 1] + skip_cost;
        step[i][j] = kSkipSecond;
      }
      cost[i][j] = best;
    }
  }
  std::vector<std::pair<int, int>> pairs;
  for (int i = n, j = m; i > 0 || j > 0;) {
    if (i > 0 && j > 0 && step[i][j] == kPair) {
      pairs.push_back({--i, --j});
    } else if (i > 0 && (j == 0 || step[i][j] == kSkipFirst)) {
      --i;
    } else {
      --j;
    }
  }
  std::reverse(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<ExtremityAnchor> match_short_tip_rows(
    const TipsAndAnchors& source, const std::vector<int>& source_short, const TipsAndAnchors& target,
    const std::vector<int>& target_short, const FirstMap& map, const std::vector<ExtremityAnchor>& matched,
    const std::vector<std::string>& taken, double max_mismatch) {
  std::vector<ExtremityAnchor> rows;
  if (matched.empty()) return rows;
  const double source_root_area = std::sqrt(surface_area(source.mesh));
  const double target_root_area = std::sqrt(surface_area(target.mesh));
  const auto source_rows = rows_beside(source, source_short, matched, 0);
  const auto target_rows = rows_beside(target, target_short, matched, 1);
  const TipMismatch mismatch(source.mesh, target.mesh, map);
  std::vector<std::string> names = names_taken(taken, matched);
  for (std::size_t k = 0; k < matched.size(); ++k) {
    const auto& source_row = source_rows[k];
    const auto& target_row = target_rows[k];
    if (source_row.empty() || target_row.empty()) continue;
    std::vector<Eigen::Vector3d> preimages;
    for (const auto& [distance, t] : target_row) preimages.push_back(mismatch.preimage(t));
    const auto pair_cost = [&](int i, int j) {
      const double miss = mismatch(source_row[i].second, target_row[j].second, preimages[j]);
      if (!(miss < max_mismatch)) return std::numeric_limits<double>::infinity();
      const double from_tip =
          std::abs(source_row[i].first / source_root_area - target_row[j].first / target_root_area);
      return kRowMissWeight * miss + kRowDistanceWeight * from_tip;
    };
    for (const auto& [i, j] : align_rows(static_cast<int>(source_row.size()),
                                         static_cast<int>(target_row.size()), pair_cost, kRowSkipCost)) {
      const int s = source_row[i].second;
      const int t = target_row[j].second;
      ExtremityAnchor anchor =
          tip_anchor(s, t, mismatch.misses(s, t, preimages[j]), matched.size() + rows.size() + 1, names);
      anchor.matched_by = TipMatching::in_row;
      rows.push_back(std::move(anchor));
    }
  }
  return rows;
}

std::vector<FittedRow> fit_tip_rows(const TipsAndAnchors& source, const std::vector<int>& source_short,
                                    const TipsAndAnchors& target, const std::vector<int>& target_short,
                                    const FirstMap& map, const std::vector<ExtremityAnchor>& matched,
                                    const std::vector<std::string>& taken,
                                    const ClosestPointIndex& target_surface) {
  std::vector<FittedRow> fitted;
  if (matched.empty()) return fitted;
  const auto source_rows = rows_beside(source, source_short, matched, 0);
  const auto target_rows = rows_beside(target, target_short, matched, 1);
  const auto empty = [](const std::vector<std::pair<double, int>>& row) { return row.empty(); };
  // Without a row there is nothing to fit, and the tree over the remesh is not built.
  if (std::all_of(source_rows.begin(), source_rows.end(), empty) &&
      std::all_of(target_rows.begin(), target_rows.end(), empty))
    return fitted;
  const double source_scale = std::sqrt(surface_area(source.mesh));
  const double target_scale = std::sqrt(surface_area(target.mesh));
  const TipMismatch mismatch(source.mesh, target.mesh, map);
  std::vector<std::string> names = names_taken(taken, matched);
  std::size_t added = 0;
  const auto at = [](const Mesh& mesh, int v) { return position(mesh, mesh.vertex_handle(v)); };
  for (std::size_t k = 0; k < matched.size(); ++k) {
    if (source_rows[k].empty() && target_rows[k].empty()) continue;
    FittedRow row;
    row.tip = static_cast<int>(k);
    row.source = {std::get<AnchorVertex>(matched[k].specs[0].location).index};
    row.target = {std::get<AnchorVertex>(matched[k].specs[1].location).index};
    for (const auto& [distance, v] : source_rows[k]) row.source.push_back(v);
    for (const auto& [distance, v] : target_rows[k]) row.target.push_back(v);
    std::vector<Eigen::Vector3d> starts;
    for (int t : row.target) starts.push_back(at(target.mesh, t));
    const SurfaceFit fit = fit_region(source.mesh, row.source[0], kRowReaches * source.reach * source_scale,
                                      map, target_surface, starts);
    if (!(fit.mean_distance <= kFitFarthest * target_scale)) continue;
    const int n = static_cast<int>(row.source.size());
    const int m = static_cast<int>(row.target.size());
    std::vector<double> apart(static_cast<std::size_t>(n) * m);  // fractions of sqrt(target area)
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < m; ++j)
        apart[i * m + j] =
            (fit.motion(at(source.mesh, row.source[i])) - at(target.mesh, row.target[j])).norm() /
            target_scale;
    }
    // Pairs clear of every other candidate on both meshes. The first pair with the row's tip on
    // either mesh is that tip's, which keeps its name; the tip is left out when it has none.
    bool tip_paired = false;
    for (int i = 0; i < n; ++i) {
      const int j = static_cast<int>(std::min_element(apart.begin() + i * m, apart.begin() + (i + 1) * m) -
                                     (apart.begin() + i * m));
      const double d = apart[i * m + j];
      bool clear = d <= kFitPairApart;
      for (int other = 0; other < n && clear; ++other)
        clear = other == i || apart[other * m + j] >= kFitClearance * d;
      for (int other = 0; other < m && clear; ++other)
        clear = other == j || apart[i * m + other] >= kFitClearance * d;
      if (!clear) continue;
      const int s = row.source[i];
      const int t = row.target[j];
      const std::array<double, 2> miss = mismatch.misses(s, t, mismatch.preimage(t));
      ExtremityAnchor pair;
      if (!tip_paired && (i == 0 || j == 0)) {
        tip_paired = true;
        pair = matched[k];
        if (i != 0 || j != 0) pair.rival_target = -1;  // a rival of its old partner
        pair.specs[0].location = AnchorVertex{s};
        pair.specs[1].location = AnchorVertex{t};
        pair.miss = miss;
      } else {
        pair = tip_anchor(s, t, miss, matched.size() + ++added, names);
        pair.matched_by = TipMatching::in_row;
      }
      row.pairs.push_back(std::move(pair));
    }
    fitted.push_back(std::move(row));
  }
  return fitted;
}

}  // namespace xparam
