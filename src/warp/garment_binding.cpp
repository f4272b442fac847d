#include "warp/garment_binding.h"

#include "core/closest_point.h"
#include "core/errors.h"

#include <Eigen/LU>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <string>

namespace xparam {

GarmentBinding bind_garment(const TriangleSoup& body_template, const std::vector<Eigen::Vector3d>& garment_vertices,
                            const BindSettings& settings) {
  const ClosestPointIndex index(body_template.vertices, body_template.triangles);
  const VertexFrames frames = vertex_frames(body_template);
  const std::size_t n = garment_vertices.size();
  GarmentBinding binding{std::vector<int>(n), std::vector<Eigen::Vector3d>(n), std::vector<Eigen::Vector3d>(n), 0.0,
                         settings};
  std::vector<double> distance(n, 0.0);
  std::vector<char> singular(n, 0);
  tbb::parallel_for(std::size_t{0}, n, [&](std::size_t g) {
    const ClosestPoint nearest = index.closest(garment_vertices[g]);
    const Eigen::Vector3d& bary = nearest.location.bary;
    const Eigen::Matrix3d frame =
        surface_frame(body_template, frames, nearest.location.face, bary, settings.frame);
    Eigen::FullPivLU<Eigen::Matrix3d> lu(frame);
    singular[g] = lu.isInvertible() ? 0 : 1;
    binding.face[g] = nearest.location.face;
    binding.bary[g] = bary;
    // Offset from the barycentric point (not the index's point) so that placing on the template
    // itself gives the garment back up to rounding.
    const Eigen::Vector3d base = surface_position(body_template, nearest.location.face, bary);
    binding.offset[g] = singular[g] ? Eigen::Vector3d::Zero() : Eigen::Vector3d(lu.solve(garment_vertices[g] - base));
    distance[g] = nearest.distance;
  });
  const auto bad = std::find(singular.begin(), singular.end(), 1);
  if (bad != singular.end()) {
    const auto g = static_cast<std::size_t>(bad - singular.begin());
    throw InputError(body_template.source + ": garment vertex " + std::to_string(g) + " is nearest to face " +
                     std::to_string(binding.face[g]) +
                     ", which has no local frame (degenerate face); repair the template with xparam check");
  }
  if (n > 0) binding.max_distance = *std::max_element(distance.begin(), distance.end());
  return binding;
}

std::vector<Eigen::Vector3d> place_garment(const GarmentBinding& binding, const TriangleSoup& image) {
  const VertexFrames frames = vertex_frames(image);
  std::vector<Eigen::Vector3d> placed(binding.face.size());
  tbb::parallel_for(std::size_t{0}, placed.size(), [&](std::size_t g) {
    const int face = binding.face[g];
    const Eigen::Vector3d& bary = binding.bary[g];
    placed[g] = surface_position(image, face, bary) +
                surface_frame(image, frames, face, bary, binding.settings.frame) * binding.offset[g];
  });
  return placed;
}

}  // namespace xparam
