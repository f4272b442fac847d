#pragma once
/// \file
/// The patches of one side of a layout as plain disk patches (param/patch_parameterization.h),
/// each with its LPBD polygon, ready to be parameterized.

#include "domain/lpbd.h"
#include "layout/layout.h"
#include "param/patch_parameterization.h"

#include <array>
#include <vector>

namespace xparam {

/// One side's patches in local indices, and how mesh elements find their local copies.
struct SidePatches {
  std::vector<DiskPatch> patches;                ///< #patches, polygon = the patch's LPBD (or its fallback)
  std::vector<Lpbd> lpbds;                       ///< #patches, the LPBD computed from the curve lengths
  std::vector<std::vector<int>> local_to_mesh;   ///< #patches: local vertex id -> mesh vertex index
  std::vector<std::vector<int>> triangle_faces;  ///< #patches: local triangle -> mesh face index
  std::vector<std::array<int, 3>> face_corners;  ///< #mesh faces: local ids of the face's corners (fv order) in its patch
  int fallback_polygons = 0;                     ///< patches whose LPBD was degenerate (see extract_patches)
};

/// Length of layout edge `e`'s chain on `side`, in 3-D units.
double chain_length(const Layout& layout, int side, int e);

/// Cut side `side` of a layout with triangular patches into disk patches. The boundary loop of
/// patch p is the concatenation of the chains of its layout halfedges (patch on their left, so
/// counter-clockwise), corner j at the start of halfedge j. The polygon is the patch's LPBD
/// (paper 3.2) from its three curve lengths; when that triangle is degenerate (a curve at least
/// as long as the two others together) the polygon is the triangle of the straight 3-D
/// distances between its anchors instead, which is never degenerate for distinct,
/// non-collinear anchors, and the patch is counted in `fallback_polygons`.
/// \pre every patch is a triangle and the face property "xparam:patch" is set on `side`
SidePatches extract_patches(const Layout& layout, int side);

}  // namespace xparam
