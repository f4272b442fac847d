#pragma once
/// \file
/// Relaxation of one patch's map (ARCHITECTURE step 8b): the template patch's vertices, placed
/// in the target patch's parameter polygon by Gamma_st . Gamma_s, slide inside it to lower the
/// symmetric Dirichlet energy of the composed map onto the target surface.
///
/// Why: the mean-value parameterization squeezes an unanchored protrusion (a tail, a finger)
/// into a tiny region of its polygon, on both sides, and Gamma_st matches the two tiny regions
/// only when the patch boundaries sit alike around them. When they do not, the template's tail
/// lands on the base of the target's, a few stretched template faces cover the target's tail,
/// and the remesh cuts it off (area ratio 0.95 on TOSCA's centaur). Only an energy that sees the
/// target surface inside each template face, not just at its corners, can notice this.
///
/// The energy of template face f (3-D area A_f, affine map M_f from its plane to its image
/// triangle in the target polygon) is A_f * SD(R_f M_f / s), SD(K) = |K|^2 + |K^-1|^2, where
/// R_f^T R_f is the target's metric averaged over the image triangle (the pullback of the
/// target's 3-D positions through its parameterization, each target parameter triangle
/// counted in the image triangle that holds its centroid, area-weighted) and s^2 the global
/// area ratio target/template. It is minimized by SLIM (Rabinovich et al. 2017): each
/// iteration fixes the metrics, solves one sparse SPD system for the reweighted proxy, and
/// takes the largest step along the result that keeps every image triangle positive and
/// lowers the energy. Boundary vertices stay where they are (on the curves, by arc length),
/// so the patch maps still glue into one bijection.

#include "param/patch_parameterization.h"
#include "param/point_locator.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// Options of the relaxation.
struct MapRelaxationSettings {
  int max_iterations = 30;           ///< SLIM iterations per patch
  double relative_tolerance = 1e-3;  ///< stop when an iteration lowers the energy by less than this fraction
  /// A patch whose mean SD (energy / area) is below this is left as it is: it is within 10% of
  /// an isometry, there is little to gain, and the estimate of the averaged metric (exact only
  /// up to rounding for slivers) would move an exact map (a mesh against itself) off the identity.
  double min_mean_energy = 4.4;
};

/// The target side of a patch, as the relaxation needs it.
struct TargetPatchView {
  const DiskPatch* patch = nullptr;                  ///< triangles and 3-D positions
  const std::vector<Eigen::Vector2d>* uv = nullptr;  ///< its parameterization in the polygon
  const PointLocator* locator = nullptr;             ///< over uv and patch->triangles
};

/// What the relaxation of one patch did.
struct MapRelaxationResult {
  std::vector<Eigen::Vector2d>
      uv;                      ///< #V of the template patch: where each vertex now lies in the target polygon
  double energy_before = 0.0;  ///< sum over faces of A_f * SD, at the initial placement
  double energy_after = 0.0;   ///< the same at the result (<= energy_before)
  double area = 0.0;           ///< sum of A_f (energy / area is the mean SD; 4 for an isometry)
  int iterations = 0;          ///< SLIM iterations that lowered the energy
};

/// Relax template patch `source` whose vertices start at `initial_uv` in the target polygon
/// (an embedding: every triangle counter-clockwise). `scale` is s above (target / template
/// length ratio). Boundary-loop vertices keep their positions; the result is again an
/// embedding. Deterministic.
/// \pre initial_uv has one entry per source vertex and no triangle of non-positive area
MapRelaxationResult relax_patch_map(const DiskPatch& source, std::vector<Eigen::Vector2d> initial_uv,
                                    const TargetPatchView& target, double scale,
                                    const MapRelaxationSettings& settings = {});

/// Relax a patch's own parameterization the same way: `uv` (an embedding in patch.polygon, the
/// mean-value one, say) slides with the boundary fixed to lower the symmetric Dirichlet energy
/// of the map from the 3-D patch to its polygon, scaled by sqrt(polygon area / patch area).
/// Mean-value weights squeeze a protrusion without an anchor into a spot of the polygon whose
/// size falls exponentially with its length; relaxed, it keeps an area near its 3-D one on
/// both sides of the cross map, which leaves the cross map's own relaxation little to do.
/// Deterministic.
/// \pre uv has one entry per patch vertex and no triangle of non-positive area
MapRelaxationResult relax_patch_parameterization(const DiskPatch& patch, std::vector<Eigen::Vector2d> uv,
                                                 const MapRelaxationSettings& settings = {});

}  // namespace xparam
