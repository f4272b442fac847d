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
  int fallback_polygons = 0;                     ///< patches whose LPBD was unusable (see patch_polygon)
};

/// The convex polygon one patch is parameterized onto.
struct PatchPolygon {
  Lpbd lpbd;                             ///< the LPBD of the curve lengths (and surface angles)
  std::vector<Eigen::Vector2d> corners;  ///< #n corners, strictly convex, counter-clockwise
  bool fallback = false;                 ///< true when `corners` are not lpbd.corners
};

/// The parameter polygon of an n-sided patch: the first strictly convex (param/convex_polygon.h)
/// of (1) its LPBD from the curve lengths (triangle_lpbd for n = 3; polygon_lpbd, paper eq. 2,
/// with the surface angles for n > 3), (2) the same from the straight 3-D distances between
/// consecutive anchors, (3) the polygon inscribed in a circle whose corners split the circle in
/// the proportions of the curve lengths (distinct points on a circle in order always form a
/// strictly convex polygon, so this never fails). A degenerate or concave LPBD would make the
/// patch's mean-value map fold; any convex polygon keeps it, and the domain map between
/// two convex polygons, bijective: (2) and (3) trade distortion for bijectivity.
/// \param curve_lengths #n boundary-curve lengths (side i: corner i -> corner i+1), > 0
/// \param surface_angles #n surface angles at the corners, radians (unused for n = 3)
/// \param chord_lengths #n straight distances between consecutive corners' anchors, >= 0
/// \pre n >= 3, same sizes; ParamError from the LPBD solvers for non-positive curve lengths
PatchPolygon patch_polygon(const std::vector<double>& curve_lengths, const std::vector<double>& surface_angles,
                           const std::vector<double>& chord_lengths);

/// Length of layout edge `e`'s chain on `side`, in 3-D units.
double chain_length(const Layout& layout, int side, int e);

/// One patch of one side as a plain disk patch, in local indices.
struct ExtractedPatch {
  DiskPatch patch;                 ///< polygon = the patch's LPBD (or its fallback)
  Lpbd lpbd;                       ///< the LPBD computed from the curve lengths
  bool fallback = false;           ///< true when patch.polygon is patch_polygon's fallback, not lpbd.corners
  std::vector<int> local_to_mesh;  ///< local vertex id -> mesh vertex index
  std::vector<int> triangle_faces; ///< local triangle -> mesh face index
};

/// Cut patch p of side `side` out of a layout, as extract_patches does for every patch: its
/// triangles are the mesh faces with patch id p (in face order, local vertex ids by first
/// appearance), its boundary the chains of its walk. Reads only those faces, those chains and
/// the patch's anchors (and, for n > 3 sides, the chains at its anchors for the surface
/// angles), so it also works on a layout where nothing else is meaningful (SwapTrial::after).
/// \pre p a patch of the layout whose faces carry patch id p on `side`
ExtractedPatch extract_patch(const Layout& layout, int side, int p);

/// Cut side `side` of a layout into disk patches. The boundary loop of patch p is the
/// concatenation of the chains of its layout halfedges (patch on their left, so
/// counter-clockwise), corner j at the start of halfedge j. The polygon comes from
/// patch_polygon with the chain lengths, the surface angles of domain/patch_merging.h and the
/// anchor-to-anchor distances; patches that need its fallback are counted in `fallback_polygons`.
/// \pre layout consistent (triangles, or merged quads and n-gons of distinct anchors) and the
///   face property "xparam:patch" set on `side`
SidePatches extract_patches(const Layout& layout, int side);

}  // namespace xparam
