#pragma once
/// \file
/// The directed edges of a list of triangles, grouped by the vertex they leave (compressed rows):
/// for checks and walks that ask whether an edge, or its twin, is used. A vertex leaves a few
/// edges, so each vertex's list is searched linearly; sorting every edge cost more where this runs
/// (the check of every patch parameterized, the boundary of every chart the gluing tries).

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace xparam {

class OutgoingEdges {
 public:
  /// A directed edge, from the corner `slot` names to the triangle's next corner.
  struct Edge {
    int head = -1;         ///< the vertex the edge enters
    std::size_t slot = 0;  ///< 3 * triangle + corner of the vertex it leaves
  };

  /// \pre every corner of `triangles` in [0, n_vertices)
  OutgoingEdges(const std::vector<std::array<int, 3>>& triangles, int n_vertices);

  /// The edges leaving `v`, in triangle order. \pre v in [0, n_vertices)
  std::span<const Edge> leaving(int v) const {
    return {edges_.data() + first_[v], edges_.data() + first_[v + 1]};
  }

  /// Whether some triangle has the edge from `tail` to `head`. \pre tail in [0, n_vertices)
  bool has(int tail, int head) const {
    for (const Edge& edge : leaving(tail)) {
      if (edge.head == head) return true;
    }
    return false;
  }

  int n_vertices() const { return static_cast<int>(first_.size()) - 1; }

 private:
  std::vector<int> first_;   ///< edges leaving v: edges_[first_[v] .. first_[v + 1])
  std::vector<Edge> edges_;  ///< 3 per triangle
};

}  // namespace xparam
