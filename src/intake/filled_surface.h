#pragma once
/// \file
/// Which images of a map lie on surface the intake filled in rather than on the scan, and how far
/// each such image is from the real scan: reported per template vertex with every output.

#include "core/surface_point.h"
#include "io/mesh_loader.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// Per template vertex, whether its image is on a fill patch, and its distance to the scan.
struct FilledSurfaceImages {
  std::vector<int> on_filled;            ///< 1 when the image lies on a fill face, else 0
  /// Distance (target units) from the image to the nearest face that came from the file; 0 for
  /// images on the file's own faces.
  std::vector<double> distance_to_scan;
  int count = 0;                         ///< images on fill faces
  double max_distance = 0.0;             ///< largest distance_to_scan
};

/// For the first `n` template vertices: `images[v]` on `target`'s mesh and its position
/// `positions.row(v)`. A target the intake did not fill gives all zeros.
/// \pre n <= images.size() and n <= positions.rows()
FilledSurfaceImages filled_surface_images(const LoadedMesh& target, const std::vector<SurfacePoint>& images,
                                          const Eigen::MatrixX3d& positions, int n);

}  // namespace xparam
