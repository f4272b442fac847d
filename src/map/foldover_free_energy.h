#pragma once
/// \file
/// The distortion energy of one triangle's map, as map/map_optimization.h uses it
/// (Garanzha et al. 2021, "Foldover-free maps in 50 lines of code"):
///     E(J) = (|J|_F^2 + lambda (det J^2 + 1)) / chi(det J, eps),
///     chi(D, eps) = (D + sqrt(eps^2 + D^2)) / 2,
/// for the 2x2 Jacobian J of a triangle map (both triangles in orthonormal frames of their own).
/// With eps = 0: +inf unless det J > 0, and |J|^2 / det J + lambda (det J + 1 / det J) >=
/// 2 + 2 lambda, equal exactly for rotations. With eps > 0: finite and smooth everywhere.

#include <Eigen/Core>
#include <Eigen/LU>

namespace xparam {

/// chi(D, eps) above: > 0 for eps > 0; D+ (max(D, 0)) for eps = 0.
double foldover_chi(double det, double eps);

/// E(J) above; +inf where chi is 0.
double foldover_free_energy(const Eigen::Matrix2d& jacobian, double lambda, double eps);

/// dE/dJ. \pre E(J) finite
Eigen::Matrix2d foldover_free_energy_gradient(const Eigen::Matrix2d& jacobian, double lambda, double eps);

}  // namespace xparam
