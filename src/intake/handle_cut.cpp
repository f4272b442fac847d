#include "intake/handle_cut.h"

#include "core/errors.h"

#include <map>
#include <utility>

namespace xparam::intake {

std::vector<int> cut_along_cycle(std::vector<Point>& points, std::vector<Triangle>& triangles,
                                 const std::vector<int>& cycle) {
  const std::size_t n = cycle.size();
  XP_ASSERT_MSG(n >= 3, "a cycle to cut along has " << n << " vertices");
  std::map<std::pair<int, int>, int> face_of_edge;  // directed edge -> the face holding it
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k)
      face_of_edge.emplace(std::make_pair(triangles[f][k], triangles[f][(k + 1) % 3]), static_cast<int>(f));
  const auto face_with = [&face_of_edge](int from, int to) {
    const auto at = face_of_edge.find({from, to});
    XP_ASSERT_MSG(at != face_of_edge.end(), "no face holds the edge " << from << " -> " << to);
    return at->second;
  };

  // The left fan of every cycle vertex, found before any corner changes.
  std::vector<std::vector<int>> left_fans(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int v = cycle[i];
    const int previous = cycle[(i + n - 1) % n];
    int face = face_with(v, cycle[(i + 1) % n]);
    for (;;) {
      left_fans[i].push_back(face);
      XP_ASSERT_MSG(left_fans[i].size() <= triangles.size(), "the fan around vertex " << v << " does not close");
      const Triangle& t = triangles[face];
      int k = 0;
      while (t[k] != v) ++k;
      const int before = t[(k + 2) % 3];  // this face holds before -> v; its neighbour across holds v -> before
      if (before == previous) break;
      face = face_with(v, before);
    }
  }

  std::vector<int> copied;
  copied.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int copy = static_cast<int>(points.size());
    points.push_back(points[cycle[i]]);
    copied.push_back(cycle[i]);
    for (int face : left_fans[i])
      for (int& corner : triangles[face])
        if (corner == cycle[i]) corner = copy;
  }
  return copied;
}

}  // namespace xparam::intake
