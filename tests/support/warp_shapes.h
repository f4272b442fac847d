#pragma once
/// \file
/// Closed test bodies and garments for the warp tests, plus an inside test that shares no code
/// with warp/body_distance (a generalized winding number, brute force).

#include "core/triangle_soup.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <map>
#include <vector>

namespace xparam::test {

/// An octahedron subdivided `levels` times, projected on the sphere of `radius` about `centre`;
/// faces outward.
inline TriangleSoup sphere_soup(int levels, double radius = 1.0, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  TriangleSoup soup;
  soup.source = "sphere.obj";
  soup.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  soup.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      soup.vertices.push_back(((soup.vertices[a] + soup.vertices[b]) / 2).normalized());
      return middle[key] = static_cast<int>(soup.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& [a, b, c] : soup.triangles) {
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.insert(finer.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
    }
    soup.triangles = finer;
  }
  for (Eigen::Vector3d& p : soup.vertices) p = centre + radius * p;
  return soup;
}

/// The surface of the box [-h, h]^3, each side an n x n grid of squares cut in two; faces outward.
inline TriangleSoup box_soup(int n, double h) {
  TriangleSoup soup;
  soup.source = "box.obj";
  std::map<std::array<int, 3>, int> index;  // vertex by its integer grid coordinates in [-n, n]^3
  auto vertex = [&](const std::array<int, 3>& key) {
    const auto it = index.find(key);
    if (it != index.end()) return it->second;
    soup.vertices.emplace_back(h * key[0] / n, h * key[1] / n, h * key[2] / n);
    return index[key] = static_cast<int>(soup.vertices.size()) - 1;
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (const int sign : {-1, 1}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          std::array<int, 4> corner{};
          const int steps[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          for (int k = 0; k < 4; ++k) {
            std::array<int, 3> key{};
            key[axis] = sign * n;
            key[u] = 2 * steps[k][0] - n;
            key[v] = 2 * steps[k][1] - n;
            corner[k] = vertex(key);
          }
          // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
          if (sign > 0) {
            soup.triangles.push_back({corner[0], corner[1], corner[2]});
            soup.triangles.push_back({corner[0], corner[2], corner[3]});
          } else {
            soup.triangles.push_back({corner[0], corner[2], corner[1]});
            soup.triangles.push_back({corner[0], corner[3], corner[2]});
          }
        }
      }
    }
  }
  return soup;
}

/// The generalized winding number of `body` at `p` (1 inside, 0 outside a closed outward
/// surface), summed over solid angles (Van Oosterom & Strackee 1983).
inline double winding_number(const TriangleSoup& body, const Eigen::Vector3d& p) {
  double sum = 0.0;
  for (const auto& [i, j, k] : body.triangles) {
    const Eigen::Vector3d a = body.vertices[i] - p, b = body.vertices[j] - p, c = body.vertices[k] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return sum / (4.0 * M_PI);
}

}  // namespace xparam::test
