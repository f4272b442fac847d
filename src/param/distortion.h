#pragma once
/// \file
/// Distortion of a map between two triangle meshes with the same faces (paper section 4.1):
/// per-face L2-stretch (eq. 5) and angle distortion (eq. 3 summand), their global values
/// E_L2 (eq. 6) and E_ang (eq. 3), and the mean largest singular-value stretch.
///
/// The map takes source triangle f (3-D positions p_k) to its image Gamma(f) (3-D positions of
/// the mapped vertices). Eq. 5 measures it as the paper writes it: the planar frame (s_k, t_k)
/// lies on the image triangle and tau_s, tau_t are derivatives of the source positions, i.e.
/// Sander's stretch of the inverse map Gamma(f) -> f. A map that stretches by sigma1 >= sigma2
/// therefore has L2 = sqrt((1/sigma1^2 + 1/sigma2^2) / 2).

#include <Eigen/Core>

#include <array>
#include <vector>

namespace xparam {

/// Options of the distortion measure.
struct DistortionSettings {
  /// An image triangle is degenerate when its area is at most this times the square of its
  /// longest edge (scale free; a needle or a point). Its stretch is +inf.
  double degenerate_area_ratio = 1e-12;
};

/// Global values over a set of faces.
struct DistortionSummary {
  double e_l2 =
      1.0;  ///< eq. 6: sqrt(sum A(Gamma f) * sum L2(f)^2 A(f)) / sum A(f); >= 1, 1 for isometry or similarity
  double e_ang = 0.0;  ///< eq. 3 over all faces: mean of ((a - a') / a)^2 over every angle of every face
  double stretch_max_sv = 1.0;  ///< mean over faces of max(sigma1, 1 / sigma2) of the map f -> Gamma(f)
};

/// The sums eq. 3 and eq. 6 are made of, over a set of faces. Sums over disjoint face sets add
/// up (operator+=), so the global values of a union follow from its parts (the dense swap
/// metrics measure two patches at a time this way).
struct DistortionSums {
  int faces = 0;              ///< faces summed
  double source_area = 0.0;   ///< sum A(f), 3-D units squared
  double image_area = 0.0;    ///< sum A(Gamma f)
  double l2_area = 0.0;       ///< sum L2(f)^2 A(f) (eq. 5 and 6); +inf with a degenerate image
  double angle = 0.0;         ///< sum over faces of (1/3) sum_j ((a_j - a'_j) / a_j)^2 (eq. 3)
  double max_stretch = 0.0;   ///< sum over faces of max(sigma1, 1 / sigma2)
  DistortionSums& operator+=(const DistortionSums& other);
};

/// The global values of `sums`: E_L2 = sqrt(image_area * l2_area) / source_area (eq. 6, +inf
/// when l2_area is), E_ang = angle / faces (eq. 3), the mean max stretch; NaN for no faces.
DistortionSummary summarize(const DistortionSums& sums);

/// Per-face and global distortion of a map.
struct DistortionResult {
  std::vector<double> face_l2_stretch;  ///< #F eq. 5 L2(f); +inf for a degenerate image
  std::vector<double>
      face_angle_distortion;  ///< #F (1/3) sum_j ((a_j - a'_j) / a_j)^2; +inf for a degenerate image
  std::vector<double>
      face_max_stretch;   ///< #F max(sigma1, 1 / sigma2) of f -> Gamma(f); +inf for a degenerate image
  DistortionSummary all;  ///< over every face: +inf as soon as one image is degenerate
  DistortionSums all_sums;  ///< the sums `all` comes from (summed in face order)
  DistortionSummary nondegenerate;  ///< over the faces whose image is not degenerate
  int degenerate_faces = 0;         ///< faces whose image is degenerate (infinite stretch)
  DistortionSettings settings;      ///< the settings used
};

/// Measure the distortion of the map source_positions -> image_positions on `faces`.
/// Runs over faces in parallel (TBB) with per-face slots and sums in face order, so the
/// result is bit-identical at any thread count.
/// \param source_positions #V 3-D positions of the source mesh
/// \param image_positions  #V 3-D positions of the mapped vertices (same vertex order)
/// \param faces            #F vertex ids, the same for both
/// \throw ParamError when sizes differ, an index is out of range, a position is not finite, or
/// a source triangle is degenerate (a zero angle makes eq. 3 undefined).
DistortionResult measure_distortion(const std::vector<Eigen::Vector3d>& source_positions,
                                    const std::vector<Eigen::Vector3d>& image_positions,
                                    const std::vector<std::array<int, 3>>& faces,
                                    const DistortionSettings& settings = {});

}  // namespace xparam
