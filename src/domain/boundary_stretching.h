#pragma once
/// \file
/// Boundary stretching (paper section 2, step 1; ARCHITECTURE.md step 4): every layout curve
/// becomes a locally shortest geodesic inside the union of its two patches, inserted into both
/// meshes by splitting the edges it crosses (geodesic/straighten_path.h does one curve).
///
/// A straightened curve must stay disjoint from every other curve, so it may not touch the
/// boundary of its two-patch region except at its own two anchors. Where the geodesic of the
/// closed region would bend around another curve's vertex or an anchor w, the curve is kept a
/// small distance off w instead (see StretchSettings::contact_clearance): the curve is first
/// planned without touching the mesh (geodesic/straighten_path.h straighten_curve); for every
/// blocked vertex w it would touch, the region's interior edges at w are split close to w and
/// the thin faces around w leave the region the funnel may use (they stay in their patch);
/// then the curve is planned again from the original chain, until it touches no blocked
/// vertex, and only then inserted. The curve bends around the new split vertices ("clearance
/// vertices") instead of w: it is locally shortest in its region minus the faces at the
/// avoided vertices, and at most the clearance vertices miss pi on their w side.

#include "geodesic/straighten_path.h"
#include "layout/layout.h"

#include <array>
#include <vector>

namespace xparam {

/// Options of boundary stretching.
struct StretchSettings {
  StraightenSettings straighten;  ///< the funnel (geodesic/straighten_path.h)
  /// Where a curve would touch a blocked vertex w (an anchor or another curve's vertex) of its
  /// region's boundary, the region edges at w are split at this fraction of their length from w
  /// and the curve passes around the new vertices instead of through w.
  double contact_clearance = 0.05;
  /// Bound on the plan-and-clear rounds of one curve (each round clears every blocked vertex
  /// the planned curve touches; a vertex is never cleared twice).
  int max_clearance_rounds = 32;
  /// Keep corners (stretch_layout): a curve whose straightening collapses a patch corner on one
  /// side keeps its traced route. Off by default; map_pair turns it on, at the anchors near the
  /// folds, when it builds a second or third layout because the map on the first one folds
  /// (map/pair_mapping.h).
  bool keep_corners = false;
  /// With keep_corners: only corners at these anchors are kept (layout anchor ids); empty: all.
  std::vector<int> keep_corners_at;
  /// A corner is collapsed when its surface angle on one side is below collapsed_angle (radians,
  /// 10 degrees) and below collapsed_ratio times the same corner's angle on the other side;
  /// stretching collapsed it when it was not so before.
  double collapsed_angle = 0.17453292519943295;
  double collapsed_ratio = 0.25;  ///< see collapsed_angle
  /// Bound on the stretching passes with keep_corners (each pass starts again from the traced
  /// layout and leaves out the curves of every corner the passes so far collapsed).
  int max_keep_passes = 4;
};

/// What stretching one layout curve did, per side (0: template, 1: target).
struct CurveStretch {
  int edge = -1;                          ///< the layout edge
  std::array<int, 2> vertices_added{};    ///< mesh vertices inserted (curve crossings and clearance splits)
  std::array<int, 2> contacts_avoided{};  ///< blocked boundary vertices the curve was kept off
  /// Those vertices per side (anchors or other curves' vertices), in the order they were met.
  std::array<std::vector<VertexHandle>, 2> avoided;
  /// The clearance vertices the splits made per side (free vertices at contact_clearance from
  /// an avoided vertex); the curve may pass through some of them.
  std::array<std::vector<VertexHandle>, 2> clearance_vertices;
  std::array<double, 2> input_length{};  ///< chain length before, 3-D units
  std::array<double, 2> length{};        ///< chain length after, 3-D units
  std::array<bool, 2> converged{};       ///< the funnel converged (see StraightenResult)
  /// The straightened curve could not be inserted (it would cross a face twice after snapping,
  /// or kept touching blocked vertices) and this side keeps its chain as it was: stretching
  /// improves a layout, it is never needed for consistency.
  std::array<bool, 2> kept{};
};

/// What stretch_layout did.
struct StretchResult {
  std::vector<CurveStretch> curves;     ///< one per stretched layout edge, in edge order
  std::array<int, 2> vertices_added{};  ///< sum over curves, per side
  std::array<int, 2> kept{};            ///< curves per side left as they were (CurveStretch::kept)
  /// keep_corners: the layout edges left as traced because straightening them collapsed a
  /// corner, ascending.
  std::vector<int> unstretched;
  int passes = 1;  ///< stretching passes (more than one only with keep_corners)
};

/// Stretch layout edge `e` on both sides: straighten its chain inside the union of its two
/// patches, insert it, update `layout.sides[*].chains[e]` and the face property
/// "xparam:patch" of the faces the insertion created or moved to the other patch. Other
/// edges' chains are untouched. The layout stays consistent (check_layout passes).
/// \pre layout consistent, face property "xparam:patch" set on both sides
/// \throw InputError for settings out of range; LayoutError when the curve cannot be kept off
///        the region boundary within max_clearance_rounds or straighten_path refuses (the
///        layout may then hold clearance splits, but stays consistent)
CurveStretch stretch_edge(Layout& layout, int e, const StretchSettings& settings = {});

/// Stretch every layout edge once, in edge order (deterministic). A curve stretched early stays
/// locally shortest when its neighbours move later (their moves never touch its vertices'
/// fans), except that a vertex it was kept off may become free.
///
/// With keep_corners, the corners' surface angles (corner_surface_angles of
/// domain/patch_merging.h) are compared after stretching: geodesics from an anchor at the tip
/// of a protrusion (a fingertip) may run side by side down it on one mesh and spread on the
/// other, where the protrusion is shorter or fused, and the map between the two corners must
/// then open an angle of a few degrees to tens, which folds the remesh near the anchor. The two
/// curves of every corner that stretching collapsed (StretchSettings::collapsed_angle and
/// collapsed_ratio) are left out, and the layout is stretched again from the traced one, until
/// no new corner collapses or max_keep_passes passes ran.
/// \pre with keep_corners, layout.patches are set (the corners are those of the patches)
/// \throw InputError with keep_corners and max_keep_passes below 1
StretchResult stretch_layout(Layout& layout, const StretchSettings& settings = {});

}  // namespace xparam
