#pragma once
/// \file
/// Construction of the consistent base domain (paper section 2, pre-step; Kraevoy & Sheffer
/// 2004): one triangulation of the anchors embedded on both meshes with the same combinatorics.
///
/// Strategy (complete on genus 0, LAYOUT.md):
/// 1. Candidates: the Delaunay neighbour pairs of the anchors' geodesic Voronoi cells on either
///    mesh (one multi-source Dijkstra per mesh, both in parallel). A pair's key is the sum over
///    both meshes of its distance along that mesh's Delaunay graph (the border-crossing estimate
///    for touching cells).
/// 2. Spanning tree (Kruskal over the candidates by key): a forest never separates the sphere,
///    so the source path (any corners) always has a target twin through the same corners.
/// 3. Diagonals in candidate order: a pair whose anchors share a layout face is joined through
///    the pair of corners with the shortest summed traced length on both meshes.
/// 4. Completion: while a face has four or more corners, join its two corners of distinct,
///    not yet joined anchors with the smallest key (one always exists).
/// Every path is the shortest edge path inside its face between its two corners' wedges on
/// each mesh; refinement (layout/refinement.h) keeps a path always possible.

#include "layout/layout.h"

#include <array>
#include <vector>

namespace xparam {

/// Options of build_consistent_layout.
struct ConsistentLayoutSettings {
  /// Take the Voronoi-neighbour diagonals in key order (step 3). When false, step 4 alone
  /// triangulates the faces the tree leaves (worse shapes; tests use it to exercise step 4).
  bool greedy_diagonals = true;
  /// Build the spanning tree from the anchor pairs whose Voronoi cells share one stretch of
  /// border on both meshes first (tree_order in the source). When false, the tree takes the
  /// pairs in key order alone, as Kraevoy and Sheffer's greedy does: a pair that may be joined
  /// round either side of a limb can then wind differently on the two meshes.
  bool unambiguous_tree_first = true;
  /// Keep each tree edge's target path near the template's, once the target is brought onto the
  /// template by the similarity that best fits the anchors near the edge (LayoutBuilder::corridor
  /// in the source); when false, or when no path fits, the target's shortest path through the
  /// same corners. With both settings false the tree is Kraevoy and Sheffer's greedy alone, which
  /// the tests of the retries use to make the maps those retries repair.
  bool tree_corridor = true;
  /// The same for each diagonal (steps 3 and 4): its target path is traced in the corridor about
  /// its template path through the same corners first. A face of the tree is a disc, but a
  /// diagonal inside it may still pass either side of the head or a limb where no anchor lies
  /// between (a diagonal's route is fixed up to isotopy only), and a map between the two routes
  /// squeezes what lies between.
  bool diagonal_corridor = true;
};

/// Wall-clock seconds of each stage of the construction.
struct LayoutTimings {
  double candidates = 0.0;  ///< Voronoi cells, Delaunay graph distances, initial refinement
  double tree = 0.0;        ///< spanning tree paths
  double diagonals = 0.0;   ///< greedy and completion diagonals
  double patches = 0.0;     ///< face walks and per-face patch ids
};

/// The layout plus what it took to build it.
struct ConsistentLayoutResult {
  Layout layout;             ///< consistent; patches are triangles, face property "xparam:patch" set
  int tree_edges = 0;        ///< n - 1
  int greedy_edges = 0;      ///< diagonals taken from the candidate order
  int completion_edges = 0;  ///< diagonals added by the completion rule
  std::array<int, 2> refined_vertices{};      ///< vertices refinement added, per side
  std::array<double, 2> total_path_length{};  ///< sum of chain lengths per side, 3-D units
  LayoutTimings seconds;
  ConsistentLayoutSettings settings;
};

/// Build the consistent layout of `anchors[k]` (index k is the same named anchor on both
/// meshes). Meshes are copied; a mesh without provenance is taken as its own input.
/// \pre both meshes closed, connected, genus 0, consistently (outward) oriented
/// \throw LayoutError when the inputs cannot be laid out: a mesh with a boundary, more than one
///   component or a genus other than 0, anchor counts that differ or are below kMinAnchors,
///   an anchor vertex out of range or given twice.
ConsistentLayoutResult build_consistent_layout(const Mesh& source,
                                               const std::vector<VertexHandle>& source_anchors,
                                               const Mesh& target,
                                               const std::vector<VertexHandle>& target_anchors,
                                               const ConsistentLayoutSettings& settings = {});

}  // namespace xparam
