#include "map/foldover_free_energy.h"

#include <limits>

namespace xparam {
namespace {

// d det(J) / dJ.
Eigen::Matrix2d cofactor(const Eigen::Matrix2d& j) {
  Eigen::Matrix2d c;
  c << j(1, 1), -j(1, 0), -j(0, 1), j(0, 0);
  return c;
}

}  // namespace

double foldover_free_energy(const Eigen::Matrix2d& jacobian, double lambda) {
  const double det = jacobian.determinant();
  if (!(det > 0.0)) return std::numeric_limits<double>::infinity();
  return (jacobian.squaredNorm() + lambda * (det * det + 1.0)) / det;
}

Eigen::Matrix2d foldover_free_energy_gradient(const Eigen::Matrix2d& jacobian, double lambda) {
  const double det = jacobian.determinant();
  const double energy = (jacobian.squaredNorm() + lambda * (det * det + 1.0)) / det;
  const Eigen::Matrix2d cof = cofactor(jacobian);
  return (2.0 * jacobian + 2.0 * lambda * det * cof - energy * cof) / det;
}

}  // namespace xparam
