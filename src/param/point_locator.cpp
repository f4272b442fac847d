#include "param/point_locator.h"

#include "core/errors.h"
#include "param/convex_polygon.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

namespace xparam {
namespace {

// Nearest point of segment ab to p: parameter t along ab and the distance.
std::pair<double, double> nearest_on_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                             const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return {t, (p - (a + t * ab)).norm()};
}

// The barycentrics of p in triangle abc when it holds p (all >= 0); nothing when it does not or
// is collapsed.
std::optional<Eigen::Vector3d> inside_barycentrics(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                                   const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double area2 = signed_area2(a, b, c);
  if (area2 == 0.0) return std::nullopt;
  const Eigen::Vector3d bary(signed_area2(p, b, c) / area2, signed_area2(a, p, c) / area2,
                             signed_area2(a, b, p) / area2);
  if (!(bary.minCoeff() >= 0.0)) return std::nullopt;
  return bary;
}

}  // namespace

PointLocation nearest_point_in_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                        const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  PointLocation result;
  if (const std::optional<Eigen::Vector3d> bary = inside_barycentrics(p, a, b, c)) {
    result.bary = *bary;
    return result;
  }
  // Outside (or degenerate): the nearest point lies on one of the sides.
  const Eigen::Vector2d* corners[3] = {&a, &b, &c};
  result.distance = std::numeric_limits<double>::infinity();
  for (int side = 0; side < 3; ++side) {
    const auto [t, distance] = nearest_on_segment(p, *corners[side], *corners[(side + 1) % 3]);
    if (distance < result.distance) {
      result.distance = distance;
      result.bary = Eigen::Vector3d::Zero();
      result.bary[side] = 1.0 - t;
      result.bary[(side + 1) % 3] = t;
    }
  }
  return result;
}

PointLocator::PointLocator(std::vector<Eigen::Vector2d> uv, std::vector<std::array<int, 3>> triangles,
                           const PointLocatorSettings& settings)
    : uv_(std::move(uv)), triangles_(std::move(triangles)) {
  if (triangles_.empty()) throw ParamError("point locator: no triangles");
  const int n_vertices = static_cast<int>(uv_.size());
  for (std::size_t f = 0; f < triangles_.size(); ++f) {
    for (int v : triangles_[f]) {
      if (v < 0 || v >= n_vertices) {
        throw ParamError("point locator: triangle " + std::to_string(f) + " has vertex " + std::to_string(v) +
                         " of " + std::to_string(n_vertices));
      }
      if (!uv_[v].allFinite())
        throw ParamError("point locator: vertex " + std::to_string(v) + " is not finite");
    }
  }
  if (!(settings.cells_per_triangle > 0.0)) throw ParamError("point locator: cells_per_triangle must be > 0");

  Eigen::Vector2d low = uv_[triangles_[0][0]];
  Eigen::Vector2d high = low;
  for (const auto& t : triangles_) {
    for (int v : t) {
      low = low.cwiseMin(uv_[v]);
      high = high.cwiseMax(uv_[v]);
    }
  }
  const Eigen::Vector2d extent = high - low;
  const double target_cells =
      std::max(1.0, settings.cells_per_triangle * static_cast<double>(triangles_.size()));
  // Square cells, about target_cells of them over the bounding box (also when it is flat).
  cell_size_ = std::max({std::sqrt(extent.x() * extent.y() / target_cells), extent.maxCoeff() / target_cells,
                         std::numeric_limits<double>::min()});
  origin_ = low;
  nx_ =
      std::clamp(static_cast<int>(std::ceil(extent.x() / cell_size_)), 1, static_cast<int>(target_cells) + 1);
  ny_ =
      std::clamp(static_cast<int>(std::ceil(extent.y() / cell_size_)), 1, static_cast<int>(target_cells) + 1);

  // Counting pass, then a filling pass in triangle order: every cell's list is ascending.
  auto cell_range = [this](const std::array<int, 3>& t) {
    Eigen::Vector2d lo = uv_[t[0]], hi = uv_[t[0]];
    for (int v : t) {
      lo = lo.cwiseMin(uv_[v]);
      hi = hi.cwiseMax(uv_[v]);
    }
    auto cell_of = [this](double x, double o, int n) {
      return std::clamp(static_cast<int>(std::floor((x - o) / cell_size_)), 0, n - 1);
    };
    return std::array<int, 4>{cell_of(lo.x(), origin_.x(), nx_), cell_of(hi.x(), origin_.x(), nx_),
                              cell_of(lo.y(), origin_.y(), ny_), cell_of(hi.y(), origin_.y(), ny_)};
  };
  cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (const auto& t : triangles_) {
    const auto r = cell_range(t);
    for (int cy = r[2]; cy <= r[3]; ++cy) {
      for (int cx = r[0]; cx <= r[1]; ++cx) ++cell_start_[cy * nx_ + cx + 1];
    }
  }
  for (std::size_t i = 1; i < cell_start_.size(); ++i) cell_start_[i] += cell_start_[i - 1];
  cell_triangles_.resize(cell_start_.back());
  std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (int f = 0; f < static_cast<int>(triangles_.size()); ++f) {
    const auto r = cell_range(triangles_[f]);
    for (int cy = r[2]; cy <= r[3]; ++cy) {
      for (int cx = r[0]; cx <= r[1]; ++cx) cell_triangles_[fill[cy * nx_ + cx]++] = f;
    }
  }
}

double PointLocator::box_distance(const std::array<int, 3>& triangle, const Eigen::Vector2d& p) const {
  const Eigen::Vector2d& a = uv_[triangle[0]];
  const Eigen::Vector2d& b = uv_[triangle[1]];
  const Eigen::Vector2d& c = uv_[triangle[2]];
  const Eigen::Vector2d below = a.cwiseMin(b).cwiseMin(c) - p;
  const Eigen::Vector2d above = p - a.cwiseMax(b).cwiseMax(c);
  return below.cwiseMax(above).cwiseMax(0.0).norm();
}

void PointLocator::test_cell(int cx, int cy, const Eigen::Vector2d& p, PointLocation& best) const {
  const int cell = cy * nx_ + cx;
  for (int i = cell_start_[cell]; i < cell_start_[cell + 1]; ++i) {
    const int f = cell_triangles_[i];
    const auto& t = triangles_[f];
    // Skip what cannot win: a later triangle once p lies inside one, or a triangle whose
    // bounding box is already farther than the best (the answer is the same, found faster).
    if (best.distance == 0.0 && f > best.triangle) continue;
    if (box_distance(t, p) > best.distance) continue;
    PointLocation candidate = nearest_point_in_triangle(p, uv_[t[0]], uv_[t[1]], uv_[t[2]]);
    // Lowest index wins a tie, as in a scan over all triangles in order.
    if (candidate.distance < best.distance || (candidate.distance == best.distance && f < best.triangle)) {
      candidate.triangle = f;
      best = candidate;
    }
  }
}

std::optional<PointLocation> PointLocator::locate_inside(const Eigen::Vector2d& p, int cx, int cy) const {
  const int cell = cy * nx_ + cx;
  const auto box_holds = [&](const std::array<int, 3>& t) { return box_distance(t, p) == 0.0; };
  for (int i = cell_start_[cell]; i < cell_start_[cell + 1]; ++i) {
    const int f = cell_triangles_[i];
    const auto& t = triangles_[f];
    if (!box_holds(t)) continue;
    const std::optional<Eigen::Vector3d> bary = inside_barycentrics(p, uv_[t[0]], uv_[t[1]], uv_[t[2]]);
    if (!bary) continue;
    // A lower triangle at distance 0 without holding p by its barycentrics (p on a side, off by
    // rounding, or on a collapsed triangle) wins the tie, as in the full search.
    for (int k = cell_start_[cell]; k < i; ++k) {
      const int g = cell_triangles_[k];
      const auto& u = triangles_[g];
      if (!box_holds(u)) continue;
      PointLocation lower = nearest_point_in_triangle(p, uv_[u[0]], uv_[u[1]], uv_[u[2]]);
      if (lower.distance == 0.0) {
        lower.triangle = g;
        return lower;
      }
    }
    return PointLocation{f, *bary, 0.0};
  }
  return std::nullopt;
}

PointLocation PointLocator::locate(const Eigen::Vector2d& p) const {
  XP_ASSERT_MSG(p.allFinite(), "query (" << p.x() << ", " << p.y() << ")");
  const int cx = std::clamp(static_cast<int>(std::floor((p.x() - origin_.x()) / cell_size_)), 0, nx_ - 1);
  const int cy = std::clamp(static_cast<int>(std::floor((p.y() - origin_.y()) / cell_size_)), 0, ny_ - 1);
  // Most queries lie inside a triangle, which is registered in the query's cell: found with the
  // containment test alone, without a distance to every earlier triangle's sides.
  if (std::optional<PointLocation> inside = locate_inside(p, cx, cy)) return *inside;
  PointLocation best;
  best.distance = std::numeric_limits<double>::infinity();
  for (int r = 0;; ++r) {
    // Ring r: the cells at Chebyshev distance exactly r from (cx, cy).
    for (int y = std::max(cy - r, 0); y <= std::min(cy + r, ny_ - 1); ++y) {
      const bool edge_row = y == cy - r || y == cy + r;
      for (int x = std::max(cx - r, 0); x <= std::min(cx + r, nx_ - 1); ++x) {
        if (edge_row || x == cx - r || x == cx + r) test_cell(x, y, p, best);
      }
    }
    // A triangle not seen yet lies in cells beyond the searched square, so at least as far
    // as the nearest of its sides that still has cells beyond it.
    double bound = std::numeric_limits<double>::infinity();
    if (cx - r > 0) bound = std::min(bound, p.x() - (origin_.x() + (cx - r) * cell_size_));
    if (cx + r < nx_ - 1) bound = std::min(bound, origin_.x() + (cx + r + 1) * cell_size_ - p.x());
    if (cy - r > 0) bound = std::min(bound, p.y() - (origin_.y() + (cy - r) * cell_size_));
    if (cy + r < ny_ - 1) bound = std::min(bound, origin_.y() + (cy + r + 1) * cell_size_ - p.y());
    if (bound == std::numeric_limits<double>::infinity()) break;  // the whole grid is searched
    // The slack covers rounding in the cell arithmetic, so a tie just beyond is never missed.
    if (best.distance < bound - 1e-9 * cell_size_) break;
  }
  XP_ASSERT(best.triangle >= 0);
  return best;
}

}  // namespace xparam
