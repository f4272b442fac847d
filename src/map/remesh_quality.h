#pragma once
/// \file
/// Quality of a remesh (the template's faces on the target's surface, ARCHITECTURE step 9):
/// faces that fold over (their normal opposes the target surface) and the area ratio.

#include "core/mesh.h"
#include "core/surface_point.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// Flip test and area comparison of a remesh against the target surface.
struct RemeshQualityResult {
  std::vector<int>
      flipped_faces;  ///< remesh faces whose normal has a negative dot with the reference normal, ascending
  int degenerate_faces = 0;  ///< remesh faces of zero area (neither flipped nor not)
  /// Remesh faces folded by the strict count: the face's normal opposes the normal of the
  /// target face under each of its three corners (when all three lie on one target face, that
  /// face is the one under each).
  int strictly_folded_faces = 0;
  double remesh_area = 0.0;  ///< total area of the remesh, target units^2
  double target_area = 0.0;  ///< total area of the target mesh
  double area_ratio = 0.0;   ///< remesh_area / target_area (1 when the remesh covers the target once)
};

/// The reference normals of measure_remesh_quality, with the target's vertex normals computed
/// once, for callers that test single faces (map/remesh_untangling.h).
class RemeshReference {
 public:
  /// \param target the surface the remesh lies on; must outlive this object
  explicit RemeshReference(const Mesh& target);

  /// Reference normal (not normalized; zero where it vanishes) of a remesh face whose corners
  /// lie at `a`, `b`, `c` on the target (see measure_remesh_quality).
  /// \pre every face index valid
  Eigen::Vector3d normal(const SurfacePoint& a, const SurfacePoint& b, const SurfacePoint& c) const;

  /// The same, with the interpolated normals at the three corners given (interpolated_normal),
  /// for callers that keep them.
  Eigen::Vector3d normal(const std::array<const SurfacePoint*, 3>& corners,
                         const std::array<const Eigen::Vector3d*, 3>& interpolated) const;

  /// The lowest-index target face all three points lie on (a point on a target vertex or edge
  /// lies on every face around it), or -1: where the reference normal is that face's.
  int shared_face(const std::array<const SurfacePoint*, 3>& corners) const;

  /// Whether a remesh face whose normal is `normal` (any length) and whose corners lie at `corners`
  /// is folded by the strict count: its normal opposes the normal of the target face under each
  /// corner (that face is shared_face's for all three when there is one).
  bool opposes_every_corner(const Eigen::Vector3d& normal, const std::array<const SurfacePoint*, 3>& corners) const;
  /// Unit normal of target face `face`.
  Eigen::Vector3d face_normal(int face) const { return face_normals_[face]; }

  /// The target's interpolated unit normal at a point (see measure_remesh_quality; zero where it
  /// vanishes). \pre point.face valid
  Eigen::Vector3d interpolated_normal(const SurfacePoint& point) const;

  /// Total area of the target, target units^2.
  double target_area() const { return target_area_; }

 private:
  const Mesh* target_;
  std::vector<Eigen::Vector3d> vertex_normals_;  ///< #target V, unit area-weighted vertex normals
  std::vector<Eigen::Vector3d> face_normals_;    ///< #target F, unit
  double target_area_ = 0.0;
};

/// Compare a remesh with the target surface it lies on.
///
/// Reference normal of remesh face (a, b, c): when its three corners lie on one common target
/// face (a corner on a target vertex or edge lies on every face around it), the normal of that
/// face — the remesh face then lies in that target face, so the comparison is exact (a remesh
/// equal to the target has no flipped face even where the target has sharp creases). Otherwise
/// the target's interpolated normal at the three corners, summed (each normalized): the
/// interpolated normal at a surface point is sum_k bary_k * n(v_k) over the vertices of its
/// target face, normalized, with n(v) the unit area-weighted vertex normal, continuous across
/// target edges and vertices. A face is flipped when dot(remesh normal, reference normal) < 0.
/// \param faces      #F remesh faces (the template's faces), vertex ids
/// \param positions  #V mapped 3-D positions of the remesh vertices
/// \param locations  #V location of every remesh vertex on `target`
/// \throw ParamError when sizes differ, an index is out of range or a location's face is not a
/// face of `target`.
RemeshQualityResult measure_remesh_quality(const std::vector<std::array<int, 3>>& faces,
                                           const std::vector<Eigen::Vector3d>& positions,
                                           const std::vector<SurfacePoint>& locations, const Mesh& target);

}  // namespace xparam
