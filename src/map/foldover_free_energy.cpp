#include "map/foldover_free_energy.h"

#include <cmath>
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

double foldover_chi(double det, double eps) {
  // For det < 0 the sum cancels: the equivalent eps^2 / (2 (sqrt(eps^2 + det^2) - det)) keeps its digits.
  const double root = std::sqrt(eps * eps + det * det);
  if (det >= 0.0) return 0.5 * (det + root);
  return 0.5 * eps * eps / (root - det);
}

double foldover_free_energy(const Eigen::Matrix2d& jacobian, double lambda, double eps) {
  const double det = jacobian.determinant();
  const double chi = foldover_chi(det, eps);
  if (!(chi > 0.0)) return std::numeric_limits<double>::infinity();
  return (jacobian.squaredNorm() + lambda * (det * det + 1.0)) / chi;
}

Eigen::Matrix2d foldover_free_energy_gradient(const Eigen::Matrix2d& jacobian, double lambda, double eps) {
  const double det = jacobian.determinant();
  const double chi = foldover_chi(det, eps);
  const double energy = (jacobian.squaredNorm() + lambda * (det * det + 1.0)) / chi;
  const double root = std::sqrt(eps * eps + det * det);
  const double chi_slope = root > 0.0 ? 0.5 * (1.0 + det / root) : 0.5;
  const Eigen::Matrix2d cof = cofactor(jacobian);
  return (2.0 * jacobian + 2.0 * lambda * det * cof) / chi - (energy / chi) * chi_slope * cof;
}

}  // namespace xparam
