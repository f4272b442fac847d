#include "param/convex_polygon.h"

#include <cmath>
#include <numbers>

namespace xparam {

bool is_strictly_convex(const std::vector<Eigen::Vector2d>& polygon) {
  const std::size_t k = polygon.size();
  if (k < 3) return false;
  double turning = 0.0;
  for (std::size_t i = 0; i < k; ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % k];
    const Eigen::Vector2d& c = polygon[(i + 2) % k];
    if (!(signed_area2(a, b, c) > 0.0)) return false;
    const Eigen::Vector2d in = b - a;
    const Eigen::Vector2d out = c - b;
    turning += std::atan2(cross2(in, out), in.dot(out));
  }
  // All left turns winding once add up to 2 pi; a star polygon (all left turns) winds more.
  return turning < 3.0 * std::numbers::pi;
}

}  // namespace xparam
