#pragma once
/// \file
/// Nearest point on a triangle mesh surface: the exact point-triangle distance, and an
/// axis-aligned bounding-box tree over the faces for many queries on one mesh.

#include "core/mesh.h"
#include "core/surface_point.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// The point of triangle (a, b, c) nearest to `p`, and its barycentric coordinates
/// (entries in [0, 1], summing to 1; exactly 0 outside the feature it lies on, so a point
/// nearest to a corner gets (1, 0, 0) and one nearest to an edge a zero entry).
struct TrianglePoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
};

/// The point of segment [a, b] nearest to `p` (a when the segment is a point).
Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

/// Exact nearest point of triangle (a, b, c) to `p` by Voronoi-region tests (Ericson,
/// Real-Time Collision Detection, 5.1.5). A degenerate triangle gives its nearest edge point.
TrianglePoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// Result of a nearest-surface-point query.
struct ClosestPoint {
  SurfacePoint location;                            ///< face + barycentrics (fv_range order)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< the nearest surface point
  double distance = 0.0;                            ///< |query - point|, mesh units
};

/// A bounding-box tree over the faces of a mesh, for nearest-surface-point queries.
/// Keeps a copy of the triangles, so the mesh may change (or go away) after construction;
/// queries then answer for the mesh as it was. Among faces at exactly the same distance the
/// lowest face index wins, so the answer equals a brute-force scan over all faces.
class ClosestPointIndex {
 public:
  /// Build the tree over every face of `mesh` (O(F log F)). \pre a triangle mesh, >= 1 face
  explicit ClosestPointIndex(const Mesh& mesh);

  /// The same over the triangles `faces` (corner indices into `points`), e.g. a remesh's
  /// chords; face i of the answers is faces[i]. \pre >= 1 face, every index valid
  ClosestPointIndex(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& faces);

  /// The surface point nearest to `p`. \pre p finite
  ClosestPoint closest(const Eigen::Vector3d& p) const;

  /// Number of faces indexed.
  int n_faces() const { return static_cast<int>(triangles_.size()); }

 private:
  struct Node {
    Eigen::Vector3d lo;
    Eigen::Vector3d hi;
    int begin = 0;  ///< first slot of this node's faces in faces_
    int end = 0;    ///< one past the last slot
    int left = -1;  ///< children in nodes_; -1 for a leaf
    int right = -1;
  };

  // The node over slots [begin, end) of faces_ at `depth` (the root's is 1); its children after it.
  int build(int begin, int end, int depth, const std::vector<Eigen::Vector3d>& centroids);
  void build_tree();  // over triangles_ in face order; leaves them in slot order
  void put_triangles_in_slot_order();

  /// Corners in fv_range order: of face f while the tree is built, then of face faces_[slot] at
  /// triangles_[slot], so a leaf reads its faces' corners from consecutive memory.
  std::vector<std::array<Eigen::Vector3d, 3>> triangles_;
  std::vector<int> faces_;                                 ///< face indices, grouped by leaf
  std::vector<Node> nodes_;                                ///< nodes_[0] is the root
};

}  // namespace xparam
