#include "core/closest_point.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace xparam {
namespace {

// Faces per leaf: small leaves prune well; the exact triangle test is cheap.
constexpr int kLeafSize = 4;

// The median split halves each node: a tree over 2^31 faces is 30 levels deep.
constexpr int kMaxDepth = 40;

// The parameter t in [0, 1] of segment [a, b]'s point a + t (b - a) nearest to p (0 for a point).
double segment_parameter(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  return length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
}

TrianglePoint on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double t = segment_parameter(p, a, b);
  return {a + t * (b - a), {1.0 - t, t, 0.0}};
}

// Nearest point of the three edges, for a triangle too flat to have a face region.
TrianglePoint on_degenerate_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  TrianglePoint best = on_segment(p, a, b);
  TrianglePoint bc = on_segment(p, b, c);
  bc.bary = {0.0, bc.bary[0], bc.bary[1]};
  TrianglePoint ca = on_segment(p, c, a);
  ca.bary = {ca.bary[1], 0.0, ca.bary[0]};
  for (const TrianglePoint& candidate : {bc, ca}) {
    if ((candidate.point - p).squaredNorm() < (best.point - p).squaredNorm()) best = candidate;
  }
  return best;
}

double box_distance2(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}

}  // namespace

Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return a + segment_parameter(p, a, b) * (b - a);
}

TrianglePoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  const Eigen::Vector3d ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, {1.0, 0.0, 0.0}};

  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, {0.0, 1.0, 0.0}};

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, {1.0 - v, v, 0.0}};
  }

  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, {0.0, 0.0, 1.0}};

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, {1.0 - w, 0.0, w}};
  }

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), {0.0, 1.0 - w, w}};
  }

  // Inside the face region; va + vb + vc is twice the squared area times |n|^2, zero only
  // for a degenerate triangle.
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return on_degenerate_triangle(p, a, b, c);
  const double v = vb / sum;
  const double w = vc / sum;
  return {a + v * ab + w * ac, {1.0 - v - w, v, w}};
}

ClosestPointIndex::ClosestPointIndex(const Mesh& mesh) {
  XP_ASSERT_MSG(mesh.n_faces() > 0, "closest-point index over a mesh without faces");
  triangles_.reserve(mesh.n_faces());
  for (FaceHandle f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> corners;
    int k = 0;
    for (VertexHandle v : mesh.fv_range(f)) {
      XP_ASSERT_MSG(k < 3, "face " << f.idx() << " is not a triangle");
      corners[k++] = position(mesh, v);
    }
    triangles_.push_back(corners);
  }
  build_tree();
}

ClosestPointIndex::ClosestPointIndex(const std::vector<Eigen::Vector3d>& points,
                                     const std::vector<std::array<int, 3>>& faces) {
  XP_ASSERT_MSG(!faces.empty(), "closest-point index over no triangles");
  triangles_.reserve(faces.size());
  for (const std::array<int, 3>& face : faces) triangles_.push_back({points[face[0]], points[face[1]], points[face[2]]});
  build_tree();
}

void ClosestPointIndex::build_tree() {
  std::vector<Eigen::Vector3d> centroids;
  centroids.reserve(triangles_.size());
  for (const auto& corners : triangles_) centroids.push_back((corners[0] + corners[1] + corners[2]) / 3.0);
  faces_.resize(triangles_.size());
  for (int f = 0; f < n_faces(); ++f) faces_[f] = f;
  nodes_.reserve(2 * triangles_.size() / kLeafSize + 1);
  build(0, n_faces(), 1, centroids);
  put_triangles_in_slot_order();
}

// In place, cycle by cycle: a copy of the corners would cost as many fresh pages again, which
// on the benchmark machine's VM took longer than the tree.
void ClosestPointIndex::put_triangles_in_slot_order() {
  std::vector<bool> placed(triangles_.size(), false);
  for (int start = 0; start < n_faces(); ++start) {
    if (placed[start]) continue;
    // Slot s takes face faces_[s]'s corners: follow s -> faces_[s] until the cycle closes.
    const std::array<Eigen::Vector3d, 3> first = triangles_[start];
    int slot = start;
    while (faces_[slot] != start) {
      triangles_[slot] = triangles_[faces_[slot]];
      placed[slot] = true;
      slot = faces_[slot];
    }
    triangles_[slot] = first;
    placed[slot] = true;
  }
}

int ClosestPointIndex::build(int begin, int end, int depth, const std::vector<Eigen::Vector3d>& centroids) {
  XP_ASSERT_MSG(depth < kMaxDepth, "closest-point tree deeper than " << kMaxDepth);
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  Eigen::Vector3d centroid_lo = lo;
  Eigen::Vector3d centroid_hi = hi;
  for (int slot = begin; slot < end; ++slot) {
    // triangles_ is in face order until build_tree puts it in slot order.
    for (const Eigen::Vector3d& corner : triangles_[faces_[slot]]) {
      lo = lo.cwiseMin(corner);
      hi = hi.cwiseMax(corner);
    }
    centroid_lo = centroid_lo.cwiseMin(centroids[faces_[slot]]);
    centroid_hi = centroid_hi.cwiseMax(centroids[faces_[slot]]);
  }
  Node node{lo, hi, begin, end, -1, -1};
  if (end - begin > kLeafSize) {
    // Median split of the centroids along their longest extent; ties broken by face index
    // so the tree does not depend on the sort's implementation.
    int axis = 0;
    (centroid_hi - centroid_lo).maxCoeff(&axis);
    const int middle = begin + (end - begin) / 2;
    std::nth_element(faces_.begin() + begin, faces_.begin() + middle, faces_.begin() + end,
                     [&](int f, int g) {
                       return centroids[f][axis] < centroids[g][axis] ||
                              (centroids[f][axis] == centroids[g][axis] && f < g);
                     });
    node.left = build(begin, middle, depth + 1, centroids);
    node.right = build(middle, end, depth + 1, centroids);
  }
  nodes_[index] = node;
  return index;
}

ClosestPoint ClosestPointIndex::closest(const Eigen::Vector3d& p) const {
  XP_ASSERT_MSG(p.allFinite(), "closest-point query at (" << p.transpose() << ")");
  ClosestPoint best;
  double best_distance2 = std::numeric_limits<double>::infinity();
  // Each visit pops one node and pushes at most two: the stack never holds more than the
  // tree's depth plus one (build asserts it below kMaxDepth).
  std::array<int, kMaxDepth + 1> stack;
  int stacked = 0;
  stack[stacked++] = 0;
  while (stacked > 0) {
    const Node& node = nodes_[stack[--stacked]];
    // Strict: a box exactly as far as the best may still hold a lower-indexed face at that distance.
    if (box_distance2(p, node.lo, node.hi) > best_distance2) continue;
    if (node.left < 0) {
      for (int slot = node.begin; slot < node.end; ++slot) {
        const int f = faces_[slot];
        const auto& t = triangles_[slot];
        const TrianglePoint candidate = closest_point_on_triangle(p, t[0], t[1], t[2]);
        const double distance2 = (candidate.point - p).squaredNorm();
        if (distance2 < best_distance2 || (distance2 == best_distance2 && f < best.location.face)) {
          best_distance2 = distance2;
          best.location = {f, candidate.bary};
          best.point = candidate.point;
        }
      }
      continue;
    }
    // Visit the nearer child first (pushed last) so the bound tightens early.
    const Node& left = nodes_[node.left];
    const Node& right = nodes_[node.right];
    const bool left_nearer = box_distance2(p, left.lo, left.hi) <= box_distance2(p, right.lo, right.hi);
    stack[stacked++] = left_nearer ? node.right : node.left;
    stack[stacked++] = left_nearer ? node.left : node.right;
  }
  best.distance = std::sqrt(best_distance2);
  return best;
}

}  // namespace xparam
