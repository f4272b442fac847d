#pragma once
/// \file
/// Point location in a 2-D triangulation (the last step of Gamma_t^-1 in paper eq. 1: which
/// triangle of the target patch's parameterization holds a mapped point).

#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace xparam {

/// Options of the point locator.
struct PointLocatorSettings {
  double cells_per_triangle = 1.0;  ///< grid cells per triangle (about); more cells, fewer tests per query
};

/// Where a query point lies.
struct PointLocation {
  int triangle = -1;  ///< nearest triangle (the containing one when distance = 0)
  Eigen::Vector3d bary =
      Eigen::Vector3d::Zero();  ///< barycentrics of the nearest point of that triangle, clamped: >= 0, sum 1
  double distance = 0.0;        ///< distance from the query to that triangle (uv units); 0 inside
};

/// A uniform-grid index over a 2-D triangulation answering "which triangle holds p".
///
/// Every triangle is registered in the grid cells its bounding box overlaps. A query tests
/// the triangles of its cell; when none contains the point (it lies outside the triangulation,
/// e.g. on the boundary off by rounding) the search grows ring by ring until no closer
/// triangle can exist, so the answer is always the nearest triangle. Ties (a point on an
/// edge or a vertex shared by several triangles) go to the lowest triangle index, so the
/// answer equals a brute-force scan's and does not depend on the grid.
class PointLocator {
 public:
  /// \param uv #V 2-D positions  \param triangles #F vertex ids into uv
  /// \pre at least one triangle, every index valid and every position finite (ParamError otherwise)
  PointLocator(std::vector<Eigen::Vector2d> uv, std::vector<std::array<int, 3>> triangles,
               const PointLocatorSettings& settings = {});

  /// The nearest triangle to p with the barycentrics of the nearest point and the distance.
  PointLocation locate(const Eigen::Vector2d& p) const;

  /// Number of triangles indexed.
  int triangle_count() const { return static_cast<int>(triangles_.size()); }

 private:
  void test_cell(int cx, int cy, const Eigen::Vector2d& p, PointLocation& best) const;
  /// The distance from p to the bounding box of `triangle` (0 inside it).
  double box_distance(const std::array<int, 3>& triangle, const Eigen::Vector2d& p) const;
  /// The answer when a triangle of cell (cx, cy) holds p by its barycentrics; nothing otherwise.
  std::optional<PointLocation> locate_inside(const Eigen::Vector2d& p, int cx, int cy) const;

  std::vector<Eigen::Vector2d> uv_;
  std::vector<std::array<int, 3>> triangles_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();  ///< lower-left corner of the grid
  double cell_size_ = 1.0;                            ///< side of a square cell, uv units
  int nx_ = 1;                                        ///< cells along x
  int ny_ = 1;                                        ///< cells along y
  std::vector<int> cell_start_;                       ///< #cells+1 offsets into cell_triangles_ (CSR)
  std::vector<int> cell_triangles_;                   ///< triangle ids of every cell, ascending
};

/// The point of triangle (a, b, c) nearest to p, as clamped barycentrics, and its distance.
/// A degenerate (zero-area) triangle is treated as its three sides.
PointLocation nearest_point_in_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                        const Eigen::Vector2d& b, const Eigen::Vector2d& c);

}  // namespace xparam
