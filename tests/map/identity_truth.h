#pragma once
// How far a pair's remesh lands from the truth when template vertex i belongs at target vertex i
// (meshes that share a vertex order: the SMPL sample targets, FAUST registrations).
#include "core/mesh.h"
#include "map/pair_mapping.h"

#include <algorithm>

namespace xparam::test {

// Distances from the image of template vertex i to target vertex i, as fractions of the
// target's bounding-box diagonal.
struct TruthDistance {
  double mean = 0.0;
  double max = 0.0;
};

inline TruthDistance distance_to_identity_truth(const PairMapping& map, const Mesh& target) {
  TruthDistance distance;
  const double diagonal = bounding_box_diagonal(target);
  for (int v = 0; v < map.remesh_vertices.rows(); ++v) {
    const double error =
        (map.remesh_vertices.row(v).transpose() - position(target, target.vertex_handle(v))).norm() /
        diagonal;
    distance.mean += error;
    distance.max = std::max(distance.max, error);
  }
  distance.mean /= static_cast<double>(map.remesh_vertices.rows());
  return distance;
}

}  // namespace xparam::test
