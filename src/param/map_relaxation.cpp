#include "param/map_relaxation.h"

#include "core/errors.h"
#include "param/convex_polygon.h"
#include "param/fixed_pattern_system.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace xparam {
namespace {

using Matrix2 = Eigen::Matrix2d;

// A template face in its own plane: M = sum_k uv_k * gradient.row(k) maps the face's plane
// to its image, for image corners uv_0, uv_1, uv_2.
struct FaceFrame {
  Eigen::Matrix<double, 3, 2> gradient = Eigen::Matrix<double, 3, 2>::Zero();
  double area = 0.0;
  bool weighted = false;  // false for slivers, whose frame is too ill-conditioned to weigh
};

FaceFrame face_frame(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  FaceFrame frame;
  const Eigen::Vector3d e1 = b - a;
  const Eigen::Vector3d e2 = c - a;
  const double double_area = e1.cross(e2).norm();
  frame.area = 0.5 * double_area;
  const double longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (c - b).squaredNorm()});
  if (!(double_area > 1e-8 * longest2)) return frame;
  const double l1 = e1.norm();
  Matrix2 edges;  // the two edges in a frame whose x axis is e1
  edges << l1, e1.dot(e2) / l1, 0.0, double_area / l1;
  Eigen::Matrix<double, 3, 2> corner_weights;
  corner_weights << -1.0, -1.0, 1.0, 0.0, 0.0, 1.0;
  frame.gradient = corner_weights * edges.inverse();
  frame.weighted = true;
  return frame;
}

// The target's metric on each triangle of its parameterization: G = J^T J for the affine map
// J from the parameter triangle to the 3-D triangle.
struct TargetMetrics {
  std::vector<Matrix2> metric;
  std::vector<double> uv_area;  // 0 for triangles that add nothing (degenerate in uv)
  std::vector<Eigen::Vector2d> centroid;
};

TargetMetrics target_metrics(const TargetPatchView& target) {
  const std::vector<std::array<int, 3>>& triangles = target.patch->triangles;
  const std::vector<Eigen::Vector3d>& positions = target.patch->positions;
  const std::vector<Eigen::Vector2d>& uv = *target.uv;
  TargetMetrics metrics;
  metrics.metric.resize(triangles.size(), Matrix2::Zero());
  metrics.uv_area.resize(triangles.size(), 0.0);
  metrics.centroid.resize(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& [a, b, c] = triangles[t];
    metrics.centroid[t] = (uv[a] + uv[b] + uv[c]) / 3.0;
    const double area2 = signed_area2(uv[a], uv[b], uv[c]);
    if (!(area2 > 0.0)) continue;
    Matrix2 uv_edges;
    uv_edges.col(0) = uv[b] - uv[a];
    uv_edges.col(1) = uv[c] - uv[a];
    Eigen::Matrix<double, 3, 2> edges;
    edges.col(0) = positions[b] - positions[a];
    edges.col(1) = positions[c] - positions[a];
    const Eigen::Matrix<double, 3, 2> jacobian = edges * uv_edges.inverse();
    metrics.metric[t] = jacobian.transpose() * jacobian;
    metrics.uv_area[t] = 0.5 * area2;
  }
  return metrics;
}

// Edge matrix of a triangle's image.
Matrix2 image_edges(const std::vector<Eigen::Vector2d>& uv, const std::array<int, 3>& t) {
  Matrix2 edges;
  edges.col(0) = uv[t[1]] - uv[t[0]];
  edges.col(1) = uv[t[2]] - uv[t[0]];
  return edges;
}

// Smallest t > 0 with det(edges + t * step) = 0, infinity when there is none.
double first_collapse(const Matrix2& edges, const Matrix2& step) {
  const double a = step.determinant();
  const double b = edges(0, 0) * step(1, 1) - edges(1, 0) * step(0, 1) + step(0, 0) * edges(1, 1) -
                   step(1, 0) * edges(0, 1);
  const double c = edges.determinant();
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](double t) {
    if (t > 0.0) best = std::min(best, t);
  };
  if (std::abs(a) < 1e-300) {
    if (b != 0.0) consider(-c / b);
    return best;
  }
  const double discriminant = b * b - 4.0 * a * c;
  if (discriminant < 0.0) return best;
  // The cancellation-free pair of roots.
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  consider(q / a);
  if (q != 0.0) consider(c / q);
  return best;
}

// Per triangle, per side k (the side opposite corner k): the triangle across it, -1 on the
// boundary. Through each vertex's triangles (a few), which costs less than sorting the sides.
std::vector<std::array<int, 3>> triangle_neighbours(const std::vector<std::array<int, 3>>& triangles) {
  int n_vertices = 0;
  for (const std::array<int, 3>& t : triangles) n_vertices = std::max({n_vertices, t[0], t[1], t[2]});
  ++n_vertices;
  // The triangles at vertex v are at[start[v] .. start[v + 1]).
  std::vector<int> start(n_vertices + 1, 0);
  for (const std::array<int, 3>& t : triangles) {
    for (int v : t) ++start[v + 1];
  }
  for (int v = 0; v < n_vertices; ++v) start[v + 1] += start[v];
  std::vector<int> at(start.back());
  std::vector<int> filled(start.begin(), start.end() - 1);
  for (int f = 0; f < static_cast<int>(triangles.size()); ++f) {
    for (int v : triangles[f]) at[filled[v]++] = f;
  }
  std::vector<std::array<int, 3>> neighbours(triangles.size(), {-1, -1, -1});
  for (int f = 0; f < static_cast<int>(triangles.size()); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[f][(k + 1) % 3];
      const int b = triangles[f][(k + 2) % 3];
      for (int i = start[a]; i < start[a + 1]; ++i) {
        const std::array<int, 3>& g = triangles[at[i]];
        if (at[i] != f && (g[0] == b || g[1] == b || g[2] == b)) {
          neighbours[f][k] = at[i];
          break;
        }
      }
    }
  }
  return neighbours;
}

// Steps a walk between neighbouring triangles may take before a point locator is asked.
constexpr int kMaxWalkSteps = 16;

// The triangle of (uv, triangles) that holds p strictly inside, walked to from triangle `start`
// across the side p lies farthest beyond (`neighbours` from triangle_neighbours): in an embedding
// the only triangle holding p, the one a point locator finds. -1 when the walk meets the
// boundary, a side p lies on or a degenerate triangle, or takes more than kMaxWalkSteps.
int walk_to(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& uv,
            const std::vector<std::array<int, 3>>& triangles,
            const std::vector<std::array<int, 3>>& neighbours, int start) {
  int f = start;
  for (int step = 0; step < kMaxWalkSteps && f >= 0; ++step) {
    const std::array<int, 3>& t = triangles[f];
    const double area = signed_area2(uv[t[0]], uv[t[1]], uv[t[2]]);
    if (area == 0.0) return -1;
    const double sign = area > 0.0 ? 1.0 : -1.0;  // either orientation
    const std::array<double, 3> beyond = {sign * signed_area2(p, uv[t[1]], uv[t[2]]),
                                          sign * signed_area2(uv[t[0]], p, uv[t[2]]),
                                          sign * signed_area2(uv[t[0]], uv[t[1]], p)};
    const int k = static_cast<int>(std::min_element(beyond.begin(), beyond.end()) - beyond.begin());
    if (beyond[k] > 0.0) return f;
    if (beyond[k] == 0.0) return -1;
    f = neighbours[f][k];
  }
  return -1;
}

// The triangle of (uv, triangles) holding p: the one a walk reaches from `cached` (which stays
// while it still holds p) or, without one, from `near` (a triangle close by); else `locate(p)`.
template <typename Locate>
int holding_triangle(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& uv,
                     const std::vector<std::array<int, 3>>& triangles,
                     const std::vector<std::array<int, 3>>& neighbours, int cached, int near,
                     const Locate& locate) {
  const int start = cached >= 0 ? cached : near;
  const int walked = start < 0 ? -1 : walk_to(p, uv, triangles, neighbours, start);
  return walked >= 0 ? walked : locate(p);
}

class Relaxation {
 public:
  Relaxation(const DiskPatch& source, const TargetPatchView& target, double scale)
      : source_(source),
        target_(target),
        scale_(scale),
        metrics_(target_metrics(target)),
        neighbours_(triangle_neighbours(source.triangles)),
        target_neighbours_(triangle_neighbours(target.patch->triangles)) {
    const size_t n_faces = source.triangles.size();
    frames_.reserve(n_faces);
    for (const std::array<int, 3>& t : source.triangles) {
      frames_.push_back(face_frame(source.positions[t[0]], source.positions[t[1]], source.positions[t[2]]));
      area_ += frames_.back().area;
    }
    free_index_.assign(source.positions.size(), 0);
    for (int v : source.boundary_loop) free_index_[v] = -1;
    for (int& index : free_index_) {
      if (index == 0) index = free_count_++;
    }
  }

  double area() const { return area_; }
  int free_count() const { return free_count_; }

  // Energy of a placement, and the root R_f of each face's averaged metric (G = R^T R).
  // Infinity when a triangle is not counter-clockwise.
  double energy(const std::vector<Eigen::Vector2d>& uv, std::vector<Matrix2>& roots) const {
    const std::vector<std::array<int, 3>>& triangles = source_.triangles;
    for (const std::array<int, 3>& t : triangles) {
      if (!(signed_area2(uv[t[0]], uv[t[1]], uv[t[2]]) > 0.0)) return std::numeric_limits<double>::infinity();
    }
    const std::vector<Matrix2> metrics = averaged_metrics(uv);
    roots.resize(triangles.size());
    double total = 0.0;
    for (size_t f = 0; f < triangles.size(); ++f) {
      roots[f] = metric_root(metrics[f]);
      if (!frames_[f].weighted) continue;
      const Matrix2 jacobian = roots[f] * face_map(uv, f) / scale_;
      const double det = jacobian.determinant();
      total += frames_[f].area * jacobian.squaredNorm() * (1.0 + 1.0 / (det * det));
    }
    return total;
  }

  // One SLIM target: the minimizer of the reweighted quadratic proxy at `uv`.
  std::vector<Eigen::Vector2d> proxy_minimizer(const std::vector<Eigen::Vector2d>& uv,
                                               const std::vector<Matrix2>& roots) {
    system_.begin();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * free_count_);
    for (size_t f = 0; f < source_.triangles.size(); ++f) {
      const FaceFrame& frame = frames_[f];
      if (!frame.weighted) continue;
      const Matrix2 stretch = roots[f] / scale_;
      const Eigen::JacobiSVD<Matrix2> svd(stretch * face_map(uv, f),
                                          Eigen::ComputeFullU | Eigen::ComputeFullV);
      const Matrix2 rotation = svd.matrixU() * svd.matrixV().transpose();
      Eigen::Vector2d weights;
      for (int i = 0; i < 2; ++i) {
        const double sigma = svd.singularValues()[i];
        // SLIM's weight for the symmetric Dirichlet energy, sqrt(f'(s) / (2 (s - 1))), 2 at s = 1.
        weights[i] =
            std::abs(sigma - 1.0) < 1e-8 ? 2.0 : std::sqrt((sigma - std::pow(sigma, -3.0)) / (sigma - 1.0));
      }
      const Matrix2 weight = svd.matrixU() * weights.asDiagonal() * svd.matrixU().transpose();
      const Matrix2 c = weight * stretch;
      const Matrix2 goal = weight * rotation;
      const Matrix2 ctc = frame.area * c.transpose() * c;
      const std::array<int, 3>& t = source_.triangles[f];
      for (int k = 0; k < 3; ++k) {
        const int row = free_index_[t[k]];
        if (row < 0) continue;
        const Eigen::Vector2d gk = frame.gradient.row(k).transpose();
        rhs.segment<2>(2 * row) += frame.area * c.transpose() * (goal * gk);
        for (int l = 0; l < 3; ++l) {
          const Eigen::Vector2d gl = frame.gradient.row(l).transpose();
          const Matrix2 block = gk.dot(gl) * ctc;
          const int col = free_index_[t[l]];
          if (col < 0) {
            rhs.segment<2>(2 * row) -= block * uv[t[l]];
            continue;
          }
          for (int i = 0; i < 2; ++i) {
            for (int j = 0; j < 2; ++j) system_.add(2 * row + i, 2 * col + j, block(i, j));
          }
        }
      }
    }
    std::vector<Eigen::Vector2d> result = uv;
    if (!system_.factorize(2 * free_count_)) return result;
    const Eigen::VectorXd solution = system_.solve(rhs);
    if (!system_.solved() || !solution.allFinite()) return result;
    for (size_t v = 0; v < uv.size(); ++v) {
      if (free_index_[v] >= 0) result[v] = solution.segment<2>(2 * free_index_[v]);
    }
    return result;
  }

  // The largest step along `to - from` (at most 1) before a triangle collapses.
  double max_step(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& to) const {
    double limit = 1.0;
    for (const std::array<int, 3>& t : source_.triangles) {
      const Matrix2 edges = image_edges(from, t);
      limit = std::min(limit, first_collapse(edges, image_edges(to, t) - edges));
    }
    return limit;
  }

 private:
  Matrix2 face_map(const std::vector<Eigen::Vector2d>& uv, size_t f) const {
    const std::array<int, 3>& t = source_.triangles[f];
    Matrix2 map = Matrix2::Zero();
    for (int k = 0; k < 3; ++k) map += uv[t[k]] * frames_[f].gradient.row(k);
    return map;
  }

  // Each image triangle's target metric: the area-weighted mean over the target parameter
  // triangles whose centroid it holds, the part of its area they do not cover filled with the
  // metric at its own centroid.
  std::vector<Matrix2> averaged_metrics(const std::vector<Eigen::Vector2d>& uv) const {
    const size_t n_faces = source_.triangles.size();
    std::vector<Matrix2> sum(n_faces, Matrix2::Zero());
    std::vector<double> covered(n_faces, 0.0);
    // The images move little between calls (line-search steps), so the triangle that held a
    // centroid last time is walked from (on the first call, the previous centroid's triangle:
    // consecutive triangles lie close); the grid is built only when a walk fails.
    std::optional<PointLocator> images;
    const auto locate_image = [&](const Eigen::Vector2d& p) {
      if (!images) images.emplace(uv, source_.triangles);
      return images->locate(p).triangle;
    };
    int previous = -1;
    holder_.resize(metrics_.metric.size(), -1);
    centroid_holder_.resize(n_faces, -1);
    for (size_t t = 0; t < metrics_.metric.size(); ++t) {
      if (metrics_.uv_area[t] <= 0.0) continue;
      int& f = holder_[t];
      f = holding_triangle(metrics_.centroid[t], uv, source_.triangles, neighbours_, f, previous,
                           locate_image);
      previous = f;
      sum[f] += metrics_.uv_area[t] * metrics_.metric[t];
      covered[f] += metrics_.uv_area[t];
    }
    std::vector<Matrix2> averaged(n_faces);
    const auto locate_target = [&](const Eigen::Vector2d& p) { return target_.locator->locate(p).triangle; };
    int previous_under = -1;
    for (size_t f = 0; f < n_faces; ++f) {
      const std::array<int, 3>& t = source_.triangles[f];
      const double image_area = 0.5 * signed_area2(uv[t[0]], uv[t[1]], uv[t[2]]);
      const double uncovered = image_area - covered[f];
      if (uncovered > 0.0) {
        const Eigen::Vector2d centroid = (uv[t[0]] + uv[t[1]] + uv[t[2]]) / 3.0;
        // The same cache for the target triangle under each image triangle's centroid.
        int& under = centroid_holder_[f];
        under = holding_triangle(centroid, *target_.uv, target_.patch->triangles, target_neighbours_, under,
                                 previous_under, locate_target);
        previous_under = under;
        sum[f] += uncovered * metrics_.metric[under];
        covered[f] += uncovered;
      }
      averaged[f] = sum[f] / covered[f];
    }
    return averaged;
  }

  // Upper-triangular R with R^T R = G; G is nudged to definite when a degenerate target
  // triangle made it singular.
  static Matrix2 metric_root(const Matrix2& metric) {
    Eigen::LLT<Matrix2> llt(metric);
    if (llt.info() != Eigen::Success || !(llt.matrixL().determinant() > 0.0)) {
      const double trace = std::max(metric.trace(), 1e-300);
      llt.compute(metric + 1e-9 * trace * Matrix2::Identity());
    }
    return llt.matrixU();
  }

  const DiskPatch& source_;
  const TargetPatchView& target_;
  double scale_ = 1.0;
  TargetMetrics metrics_;
  std::vector<FaceFrame> frames_;
  std::vector<std::array<int, 3>> neighbours_;         // of the image triangles (triangle_neighbours)
  std::vector<std::array<int, 3>> target_neighbours_;  // of the target parameter triangles
  double area_ = 0.0;
  std::vector<int> free_index_;  // #V: unknown index of a free vertex, -1 on the boundary
  FixedPatternSystem system_;    // the SLIM proxy's (its pattern is the same at every iteration)
  // Per target parameter triangle: the image triangle that held its centroid at the last
  // averaged_metrics call (-1: none yet); a cache, hence mutable.
  mutable std::vector<int> holder_;
  // Per image triangle: the target parameter triangle that held its centroid at the last call.
  mutable std::vector<int> centroid_holder_;
  int free_count_ = 0;
};

}  // namespace

MapRelaxationResult relax_patch_map(const DiskPatch& source, std::vector<Eigen::Vector2d> initial_uv,
                                    const TargetPatchView& target, double scale,
                                    const MapRelaxationSettings& settings) {
  XP_ASSERT_EQ(initial_uv.size(), source.positions.size());
  XP_ASSERT(target.patch && target.uv && target.locator && scale > 0.0);
  Relaxation relaxation(source, target, scale);
  MapRelaxationResult result;
  result.uv = std::move(initial_uv);
  result.area = relaxation.area();
  std::vector<Matrix2> roots;
  double energy = relaxation.energy(result.uv, roots);
  result.energy_before = energy;
  result.energy_after = energy;
  // An input that is not an embedding (rounding in a very squeezed region) is left alone.
  if (!std::isfinite(energy) || relaxation.free_count() == 0) return result;
  if (energy < settings.min_mean_energy * result.area) return result;

  std::vector<Eigen::Vector2d> trial(result.uv.size());
  std::vector<Matrix2> trial_roots;
  bool converged = false;
  while (!converged && result.iterations < settings.max_iterations) {
    const std::vector<Eigen::Vector2d> goal = relaxation.proxy_minimizer(result.uv, roots);
    // Stay clear of the first collapse, then halve until the energy goes down.
    double step = 0.8 * relaxation.max_step(result.uv, goal);
    double trial_energy = energy;
    for (int attempt = 0; attempt < 12 && !(trial_energy < energy); ++attempt, step *= 0.5) {
      for (size_t v = 0; v < trial.size(); ++v) trial[v] = result.uv[v] + step * (goal[v] - result.uv[v]);
      trial_energy = relaxation.energy(trial, trial_roots);
    }
    if (!(trial_energy < energy)) break;
    converged = energy - trial_energy < settings.relative_tolerance * energy;
    energy = trial_energy;
    result.uv.swap(trial);
    roots.swap(trial_roots);
    ++result.iterations;
  }
  result.energy_after = energy;
  return result;
}

MapRelaxationResult relax_patch_parameterization(const DiskPatch& patch, std::vector<Eigen::Vector2d> uv,
                                                 const MapRelaxationSettings& settings) {
  // The polygon as a flat target surface: a fan of its corners, the identity metric.
  DiskPatch polygon;
  const std::vector<Eigen::Vector2d>& corners = patch.polygon;
  for (const Eigen::Vector2d& corner : corners) polygon.positions.emplace_back(corner.x(), corner.y(), 0.0);
  double polygon_area = 0.0;
  for (int k = 1; k + 1 < static_cast<int>(corners.size()); ++k) {
    polygon.triangles.push_back({0, k, k + 1});
    polygon_area += 0.5 * signed_area2(corners[0], corners[k], corners[k + 1]);
  }
  double patch_area = 0.0;
  for (const std::array<int, 3>& t : patch.triangles) {
    patch_area += 0.5 * (patch.positions[t[1]] - patch.positions[t[0]])
                            .cross(patch.positions[t[2]] - patch.positions[t[0]])
                            .norm();
  }
  const PointLocator locator(corners, polygon.triangles);
  const TargetPatchView flat{&polygon, &corners, &locator};
  return relax_patch_map(patch, std::move(uv), flat, std::sqrt(polygon_area / patch_area), settings);
}

}  // namespace xparam
