#pragma once
// How far a pair's remesh lands from the truth: template vertex i belongs at a known target vertex
// (vertex i for meshes that share a vertex order: the SMPL sample targets, FAUST registrations).
#include "core/mesh.h"
#include "map/pair_mapping.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace xparam::test {

// Distances from the image of template vertex i to target vertex i, as fractions of the
// target's bounding-box diagonal.
struct TruthDistance {
  double mean = 0.0;
  double max = 0.0;
};

// Distance (target units) from the image of template vertex v to target vertex truth[v].
inline double truth_miss(const PairMapping& map, const Mesh& target, const std::vector<int>& truth, int v) {
  return (map.remesh_vertices.row(v).transpose() - position(target, target.vertex_handle(truth.at(v)))).norm();
}

// Distances from the image of template vertex i to target vertex truth[i] (#template vertices).
inline TruthDistance distance_to_truth(const PairMapping& map, const Mesh& target,
                                       const std::vector<int>& truth) {
  TruthDistance distance;
  const double diagonal = bounding_box_diagonal(target);
  for (int v = 0; v < map.remesh_vertices.rows(); ++v) {
    const double error = truth_miss(map, target, truth, v) / diagonal;
    distance.mean += error;
    distance.max = std::max(distance.max, error);
  }
  distance.mean /= static_cast<double>(map.remesh_vertices.rows());
  return distance;
}

inline TruthDistance distance_to_identity_truth(const PairMapping& map, const Mesh& target) {
  std::vector<int> identity(map.remesh_vertices.rows());
  std::iota(identity.begin(), identity.end(), 0);
  return distance_to_truth(map, target, identity);
}

}  // namespace xparam::test
