#pragma once
/// \file
/// The distortion energy of one triangle's map, as map/map_optimization.h uses it (Garanzha,
/// Kaporin, Kudryavtseva, Protais, Ray, Sokolov 2021, "Foldover-free maps in 50 lines of code",
/// with their regularizing eps at 0):
///     E(J) = (|J|_F^2 + lambda (det J^2 + 1)) / det J = |J|^2 / det J + lambda (det J + 1 / det J)
/// for the 2x2 Jacobian J of a triangle map (both triangles in orthonormal frames of their own):
/// +inf unless det J > 0, else >= 2 + 2 lambda, equal exactly for rotations.

#include <Eigen/Core>
#include <Eigen/LU>

namespace xparam {

/// E(J) above; +inf unless det J > 0.
double foldover_free_energy(const Eigen::Matrix2d& jacobian, double lambda);

/// dE/dJ. \pre det J > 0
Eigen::Matrix2d foldover_free_energy_gradient(const Eigen::Matrix2d& jacobian, double lambda);

}  // namespace xparam
