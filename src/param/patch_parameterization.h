#pragma once
/// \file
/// Parameterization of one disk-topology patch onto its convex LPBD polygon
/// (ARCHITECTURE step 7; the maps Gamma_s and Gamma_t of paper eq. 1).
///
/// The boundary is placed by 3-D arc length along each polygon side; interior vertices by
/// mean-value weights (Floater 2003), which are positive for any triangulation, so by
/// Tutte/Floater the map onto a convex polygon is a bijection (no flipped triangle). The
/// patch is given as plain arrays so this stage does not depend on the layout's types.

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace xparam {

/// A disk-topology patch and the convex polygon it is mapped onto, in local indices.
struct DiskPatch {
  std::vector<std::array<int, 3>> triangles;  ///< #F local vertex ids, consistently oriented
  std::vector<Eigen::Vector3d> positions;     ///< #V local 3-D positions
  /// The boundary loop as local vertex ids, counter-clockwise with respect to the triangles'
  /// orientation: every (loop[i], loop[i+1]) is a directed edge of a triangle.
  std::vector<int> boundary_loop;
  /// #k positions in `boundary_loop` of the polygon's corners, strictly increasing;
  /// corner j of `polygon` sits at boundary_loop[corner_positions[j]].
  std::vector<int> corner_positions;
  std::vector<Eigen::Vector2d> polygon;  ///< #k corners of the target polygon, convex, counter-clockwise
  std::string name = "patch";            ///< names the patch in error messages
};

/// The parameterization of one patch.
struct PatchParameterizationResult {
  std::vector<Eigen::Vector2d> uv;  ///< #V position of every local vertex in the polygon
  int interior_vertices = 0;        ///< size of the sparse system solved
};

/// Parameterize one patch. Boundary vertices are placed on the side between consecutive
/// corners at the fraction of the side's 3-D arc length; interior vertices solve
/// sum_j w_ij (u_i - u_j) = 0 with mean-value weights w_ij = (tan(a/2) + tan(b/2)) / |x_j - x_i|
/// (a, b the angles at x_i beside edge ij), one sparse solve for both coordinates with
/// Eigen::SparseLU (COLAMD ordering; the matrix is not symmetric). Deterministic.
/// \throw ParamError when the patch is not a disk whose boundary is `boundary_loop`, a
/// triangle is degenerate (zero-length edge), the polygon is not strictly convex and
/// counter-clockwise, corners are out of order, a side has zero arc length, or the solve fails.
PatchParameterizationResult parameterize_patch(const DiskPatch& patch);

/// Parameterize many independent patches in parallel (TBB). Each result goes to its own slot,
/// so the output is bit-identical at any thread count. When patches fail, the ParamError of
/// the lowest-index failing patch is rethrown (again independent of the thread count).
std::vector<PatchParameterizationResult> parameterize_patches(const std::vector<DiskPatch>& patches);

}  // namespace xparam
