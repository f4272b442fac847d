#include "param/domain_map.h"

#include "core/errors.h"
#include "param/convex_polygon.h"

#include <Eigen/LU>

#include <sstream>
#include <utility>

namespace xparam {

Eigen::VectorXd wachspress_coordinates(const std::vector<Eigen::Vector2d>& polygon,
                                       const Eigen::Vector2d& p) {
  const int k = static_cast<int>(polygon.size());
  XP_ASSERT_MSG(k >= 3, "polygon with " << k << " corners");
  // Areas relative to the polygon's size keep the (k-2)-fold products away from under/overflow.
  double scale = 0.0;
  for (int i = 0; i < k; ++i) scale += signed_area2(polygon[0], polygon[i], polygon[(i + 1) % k]);
  Eigen::VectorXd edge_area(k);  // A_j(p): p with side j (corner j to corner j+1)
  for (int j = 0; j < k; ++j) edge_area[j] = signed_area2(p, polygon[j], polygon[(j + 1) % k]) / scale;
  Eigen::VectorXd weights(k);
  for (int i = 0; i < k; ++i) {
    const int previous = (i + k - 1) % k;
    double w = signed_area2(polygon[previous], polygon[i], polygon[(i + 1) % k]) / scale;
    for (int j = 0; j < k; ++j) {
      if (j != previous && j != i) w *= edge_area[j];
    }
    weights[i] = w;
  }
  const double sum = weights.sum();
  XP_ASSERT_MSG(sum != 0.0, "Wachspress weights vanish at (" << p.x() << ", " << p.y() << ")");
  return weights / sum;
}

DomainMap::DomainMap(std::vector<Eigen::Vector2d> from, std::vector<Eigen::Vector2d> to)
    : from_(std::move(from)), to_(std::move(to)) {
  if (from_.size() != to_.size() || from_.size() < 3) {
    std::ostringstream message;
    message << "domain map: source domain has " << from_.size() << " corners and target " << to_.size()
            << " (need the same number, at least 3)";
    throw ParamError(message.str());
  }
  if (!is_strictly_convex(from_))
    throw ParamError("domain map: source domain is not strictly convex and CCW");
  if (!is_strictly_convex(to_)) throw ParamError("domain map: target domain is not strictly convex and CCW");
  if (is_affine()) {
    Eigen::Matrix2d source, target;
    source << from_[1] - from_[0], from_[2] - from_[0];
    target << to_[1] - to_[0], to_[2] - to_[0];
    linear_ = target * source.inverse();
    offset_ = to_[0] - linear_ * from_[0];
  }
}

Eigen::Vector2d DomainMap::operator()(const Eigen::Vector2d& p) const {
  if (is_affine()) return linear_ * p + offset_;
  const Eigen::VectorXd weights = wachspress_coordinates(from_, p);
  Eigen::Vector2d image = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < to_.size(); ++i) image += weights[static_cast<Eigen::Index>(i)] * to_[i];
  return image;
}

}  // namespace xparam
