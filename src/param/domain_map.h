#pragma once
/// \file
/// The map Gamma_st between two base domains with the same number of corners (paper eq. 1).
///
/// Triangles map by the unique affine map. Convex polygons with more corners map through
/// Wachspress coordinates: a point's Wachspress coordinates in the source polygon weight the
/// target polygon's corners. Floater & Kosinka (2010, "On the injectivity of Wachspress and
/// mean value mappings between convex polygons") prove this Wachspress mapping is a bijection
/// between any two strictly convex polygons with the same number of corners, while the mean
/// value mapping the paper mentions (eq. 1 discussion) can fold for some pairs of convex
/// polygons; a fold would break the bijection of the cross-parameterization, hence Wachspress.

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// Wachspress coordinates of point p in a strictly convex counter-clockwise polygon, in the
/// product form w_i = C_i * prod_{j != i-1, i} A_j(p) (C_i = area of corners i-1, i, i+1;
/// A_j(p) = area of p, corner j, corner j+1), normalized to sum 1. The product form stays
/// finite on the boundary, where the coordinates become linear along the side (and a corner
/// gets weight 1 at itself). They are the barycentric coordinates for a triangle.
/// \pre polygon strictly convex and counter-clockwise (not checked here; DomainMap checks)
Eigen::VectorXd wachspress_coordinates(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);

/// Gamma_st: the bijection from one convex base domain onto another with as many corners,
/// taking corner i to corner i. Build once per patch pair, apply to many points.
class DomainMap {
 public:
  /// \pre both polygons strictly convex and counter-clockwise with the same number (>= 3) of
  /// corners; ParamError otherwise.
  DomainMap(std::vector<Eigen::Vector2d> from, std::vector<Eigen::Vector2d> to);

  /// The image of p (a point of the source polygon). Points slightly outside by rounding map
  /// continuously to points slightly outside the target.
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const;

  /// True for triangles, where the map is the affine map through the three corners.
  bool is_affine() const { return from_.size() == 3; }

 private:
  std::vector<Eigen::Vector2d> from_;
  std::vector<Eigen::Vector2d> to_;
  Eigen::Matrix2d linear_ = Eigen::Matrix2d::Identity();  ///< affine part (triangles only)
  Eigen::Vector2d offset_ = Eigen::Vector2d::Zero();      ///< translation (triangles only)
};

}  // namespace xparam
