#include "geodesic/funnel.h"

#include "core/errors.h"
#include "core/planar.h"

namespace xparam {

std::vector<FunnelApex> funnel_path(const std::vector<Portal>& portals, const FunnelApex& start,
                                    const FunnelApex& end) {
  const int n = static_cast<int>(portals.size());
  XP_ASSERT_EQ(start.portal, -1);
  XP_ASSERT_EQ(end.portal, n);
  std::vector<FunnelApex> apexes{start};
  FunnelApex apex = start;
  // The funnel is the wedge at the apex between the rays to `left` and `right`; `empty`
  // means no portal has narrowed it since the apex was set.
  bool empty = true;
  bool turning_at_apex = true;  // the portals right after the apex still have it as an endpoint
  FunnelApex left;
  FunnelApex right;
  int i = apex.portal + 1;
  const auto restart_at = [&](const FunnelApex& corner) {
    apexes.push_back(corner);
    apex = corner;
    empty = true;
    turning_at_apex = true;
    i = corner.portal + 1;
  };
  while (true) {
    const Eigen::Vector2d& a = apex.point;
    if (i == n) {
      // The end: inside the funnel (rays included) it is seen straight from the apex;
      // otherwise the path bends at the side it lies beyond.
      if (empty) break;
      if (cross2(right.point - a, end.point - a) < 0.0) {
        restart_at(right);
      } else if (cross2(end.point - a, left.point - a) < 0.0) {
        restart_at(left);
      } else {
        break;
      }
      continue;
    }
    if (turning_at_apex && portals[i].has(apex.vertex)) {
      ++i;
      continue;
    }
    turning_at_apex = false;
    const FunnelApex next_left{i, portals[i].left, portals[i].left_point};
    const FunnelApex next_right{i, portals[i].right, portals[i].right_point};
    if (empty) {
      left = next_left;
      right = next_right;
      empty = false;
      ++i;
      continue;
    }
    // Right side: a new right point on or inside the right ray narrows the funnel, unless it
    // reaches the left ray, in which case the path bends at the left point.
    if (cross2(right.point - a, next_right.point - a) >= 0.0) {
      if (cross2(next_right.point - a, left.point - a) > 0.0) {
        right = next_right;
      } else {
        restart_at(left);
        continue;
      }
    }
    if (cross2(next_left.point - a, left.point - a) >= 0.0) {
      if (cross2(right.point - a, next_left.point - a) > 0.0) {
        left = next_left;
      } else {
        restart_at(right);
        continue;
      }
    }
    ++i;
  }
  apexes.push_back(end);
  return apexes;
}

}  // namespace xparam
