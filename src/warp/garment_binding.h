#pragma once
/// \file
/// Binding a garment to the template once, and placing it on any image of the template.
///
/// Each garment vertex is bound to its nearest template surface point (face + barycentrics)
/// and its offset from that point, in the local frame there (warp/surface_frame.h). A target's
/// image of the template (the archive's remesh: the template's faces on the mapped positions)
/// takes the bound point to the same barycentrics of the same face, and the offset through the
/// image face's frame. Wrap's DeltaTransfer and Sumner–Popović deformation transfer carry extra
/// meshes the same way.

#include "core/triangle_soup.h"
#include "warp/surface_frame.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// How a garment is bound.
struct BindSettings {
  OffsetFrame frame = OffsetFrame::gradient;  ///< how offsets follow the body (surface_frame.h)
};

/// Per garment vertex: where it is bound on the template and its offset there.
struct GarmentBinding {
  std::vector<int> face;                 ///< #G template face of the nearest surface point
  std::vector<Eigen::Vector3d> bary;     ///< #G its barycentrics in that face (corner order of the face)
  std::vector<Eigen::Vector3d> offset;   ///< #G garment vertex minus that point, in the frame's coordinates
  double max_distance = 0.0;             ///< largest garment-to-template distance, template units
  BindSettings settings;                 ///< the settings used
};

/// Bind `garment_vertices` to the surface `body_template`.
/// \pre the template has >= 1 face and no degenerate face; every garment vertex finite
/// \throw InputError naming the garment vertex when its frame cannot be inverted
GarmentBinding bind_garment(const TriangleSoup& body_template, const std::vector<Eigen::Vector3d>& garment_vertices,
                            const BindSettings& settings = {});

/// The garment's vertices placed on `image`: the template's triangles on new positions (same
/// #V and faces as the template bound to). Each vertex independently, so the result is the
/// same at any thread count. \pre image.triangles equal the bound template's
std::vector<Eigen::Vector3d> place_garment(const GarmentBinding& binding, const TriangleSoup& image);

}  // namespace xparam
