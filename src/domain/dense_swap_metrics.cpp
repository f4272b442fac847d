#include "domain/dense_swap_metrics.h"

#include "core/errors.h"
#include "core/provenance.h"
#include "domain/patch_extraction.h"
#include "param/domain_map.h"
#include "param/patch_parameterization.h"
#include "param/point_locator.h"

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <array>
#include <optional>
#include <string>

namespace xparam {

double PatchMapDistortion::e_l2() const { return summarize(sums).e_l2; }

double PatchMapDistortion::e_ang() const { return angle / angle_weight; }

PatchMapDistortion& PatchMapDistortion::operator+=(const PatchMapDistortion& other) {
  sums += other.sums;
  angle += other.angle;
  angle_weight += other.angle_weight;
  fallback_polygons += other.fallback_polygons;
  degenerate_faces += other.degenerate_faces;
  return *this;
}

std::vector<double> input_face_areas(const Mesh& refined) {
  std::vector<double> areas;
  for (FaceHandle f : refined.faces()) {
    const int input = input_face(refined, f);
    if (input >= static_cast<int>(areas.size())) areas.resize(input + 1, 0.0);
    areas[input] += refined.calc_face_area(f);
  }
  return areas;
}

PatchMapDistortion measure_patch_map(const Layout& layout, int p, const std::vector<double>& input_areas) {
  const ExtractedPatch source = extract_patch(layout, 0, p);
  const ExtractedPatch target = extract_patch(layout, 1, p);
  const PatchParameterizationResult source_uv = parameterize_patch(source.patch);
  const PatchParameterizationResult target_uv = parameterize_patch(target.patch);
  // Corner i is the start of the patch's i-th layout halfedge on both sides (Gamma_st of eq. 1).
  const DomainMap across(source.patch.polygon, target.patch.polygon);
  const PointLocator locator(target_uv.uv, target.patch.triangles);

  std::vector<Eigen::Vector3d> images(source.patch.positions.size());
  for (std::size_t v = 0; v < images.size(); ++v) {
    const PointLocation hit = locator.locate(across(source_uv.uv[v]));
    const std::array<int, 3>& corners = target.patch.triangles[hit.triangle];
    images[v] = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) images[v] += hit.bary[k] * target.patch.positions[corners[k]];
  }

  PatchMapDistortion result;
  try {
    const DistortionResult distortion = measure_distortion(source.patch.positions, images, source.patch.triangles);
    result.sums = distortion.all_sums;
    result.degenerate_faces = distortion.degenerate_faces;
    const Mesh& mesh = layout.sides[0].mesh;
    for (std::size_t t = 0; t < source.patch.triangles.size(); ++t) {
      const std::array<int, 3>& c = source.patch.triangles[t];
      const std::vector<Eigen::Vector3d>& x = source.patch.positions;
      const double area = 0.5 * (x[c[1]] - x[c[0]]).cross(x[c[2]] - x[c[0]]).norm();
      const int input = input_face(mesh, mesh.face_handle(source.triangle_faces[t]));
      XP_ASSERT_MSG(input >= 0 && input < static_cast<int>(input_areas.size()),
                    "input face " << input << " of " << input_areas.size());
      const double share = area / input_areas[input];
      result.angle += share * distortion.face_angle_distortion[t];
      result.angle_weight += share;
    }
  } catch (const ParamError& error) {
    throw ParamError("dense swap metric, " + source.patch.name + ": " + error.what());
  }
  result.fallback_polygons = static_cast<int>(source.fallback) + static_cast<int>(target.fallback);
  return result;
}

PatchMapDistortion measure_patch_map(const Layout& layout, const std::vector<int>& patches,
                                     const std::vector<double>& input_areas) {
  std::vector<PatchMapDistortion> parts(patches.size());
  std::vector<std::optional<std::string>> errors(patches.size());
  tbb::parallel_for(std::size_t{0}, patches.size(), [&](std::size_t i) {
    try {
      parts[i] = measure_patch_map(layout, patches[i], input_areas);
    } catch (const ParamError& error) {
      errors[i] = error.what();
    }
  });
  for (const auto& error : errors) {
    if (error) throw ParamError(*error);
  }
  PatchMapDistortion total;
  for (const PatchMapDistortion& part : parts) total += part;
  return total;
}

}  // namespace xparam
