#include "warp/body_distance.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace xparam {
namespace {

std::uint64_t edge_key(int a, int b) {
  const auto low = static_cast<std::uint64_t>(std::min(a, b));
  const auto high = static_cast<std::uint64_t>(std::max(a, b));
  return (low << 32) | high;
}

double corner_angle(const Eigen::Vector3d& at, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
  const Eigen::Vector3d u = p - at;
  const Eigen::Vector3d v = q - at;
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

}  // namespace

BodyDistance::BodyDistance(const TriangleSoup& body)
    : body_(body),
      index_(body.vertices, body.triangles),
      face_normals_(body.triangles.size()),
      vertex_normals_(body.vertices.size(), Eigen::Vector3d::Zero()) {
  for (std::size_t f = 0; f < body_.triangles.size(); ++f) {
    const std::array<int, 3>& t = body_.triangles[f];
    const Eigen::Vector3d& a = body_.vertices[t[0]];
    const Eigen::Vector3d& b = body_.vertices[t[1]];
    const Eigen::Vector3d& c = body_.vertices[t[2]];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() > 0.0) normal.normalize();
    face_normals_[f] = normal;
    vertex_normals_[t[0]] += corner_angle(a, b, c) * normal;
    vertex_normals_[t[1]] += corner_angle(b, c, a) * normal;
    vertex_normals_[t[2]] += corner_angle(c, a, b) * normal;
    for (int k = 0; k < 3; ++k) {
      auto [it, inserted] = edge_normals_.try_emplace(edge_key(t[k], t[(k + 1) % 3]), normal);
      if (!inserted) it->second += normal;
    }
  }
}

Eigen::Vector3d BodyDistance::pseudonormal(int face, const Eigen::Vector3d& bary) const {
  const std::array<int, 3>& t = body_.triangles[face];
  const int zeros = static_cast<int>((bary.array() == 0.0).count());
  if (zeros == 2) {  // at a corner
    int k = 0;
    bary.maxCoeff(&k);
    return vertex_normals_[t[k]];
  }
  if (zeros == 1) {  // on the edge opposite the zero entry
    int k = 0;
    bary.minCoeff(&k);
    return edge_normals_.at(edge_key(t[(k + 1) % 3], t[(k + 2) % 3]));
  }
  return face_normals_[face];
}

BodySample BodyDistance::sample(const Eigen::Vector3d& p) const {
  const ClosestPoint nearest = index_.closest(p);
  const Eigen::Vector3d normal = pseudonormal(nearest.location.face, nearest.location.bary);
  const Eigen::Vector3d away = p - nearest.point;
  const bool inside = away.dot(normal) < 0.0;
  BodySample sample;
  sample.nearest = nearest.point;
  sample.signed_distance = inside ? -nearest.distance : nearest.distance;
  // Off the surface, the way out is along the segment to the nearest point (the distance's
  // gradient); on it, along the pseudonormal.
  if (nearest.distance > 1e-12 * (1.0 + p.norm())) {
    sample.outward = (inside ? -away : away) / nearest.distance;
  } else {
    sample.outward = normal.norm() > 0.0 ? Eigen::Vector3d(normal.normalized()) : face_normals_[nearest.location.face];
  }
  return sample;
}

}  // namespace xparam
