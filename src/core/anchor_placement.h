#pragma once
/// \file
/// Placing anchors on a mesh: every anchor becomes a vertex of the (refined) mesh.
///
/// A vertex index names an input vertex. A 3-D position is snapped to its nearest surface
/// point, and a face + barycentrics is already one; such a point becomes an existing vertex
/// when it is within `snap_tolerance` of one, the new vertex of an edge split when it is
/// within `snap_tolerance` of an edge, and the new vertex of a face split otherwise
/// (ARCHITECTURE.md step 2). Existing vertices never move; every new face keeps its input
/// face (core/provenance.h).

#include "core/anchors.h"
#include "core/mesh.h"
#include "core/surface_point.h"

#include <string>
#include <vector>

namespace xparam {

class ClosestPointIndex;

/// Options of place_anchors. Distances are relative to the input mesh's bounding-box diagonal.
struct PlacementSettings {
  /// A surface point this close to a vertex (edge) is that vertex (is put on that edge), so
  /// no sliver triangle is made for a point that only rounding moved off it. Fraction of the
  /// bounding-box diagonal.
  double snap_tolerance = 1e-6;
  /// A position farther than this from the surface gets a warning (it is still placed).
  /// Fraction of the bounding-box diagonal; 1% is ~1.7 cm on a 1.7 m human.
  double warn_snap_distance = 0.01;
};

/// How an anchor became a vertex.
enum class AnchorInsertion {
  ExistingVertex,  ///< it is (or snapped onto) a vertex that was already there
  EdgeSplit,       ///< a new vertex splitting an edge
  FaceSplit,       ///< a new vertex splitting a face
};

/// One anchor on the refined mesh.
struct PlacedAnchor {
  std::string name;
  VertexHandle vertex;       ///< vertex of the refined mesh
  SurfacePoint input_point;  ///< the same place on the input mesh (face + barycentrics)
  /// Distance from the given position to the surface, mesh units (0 unless a position).
  double snap_distance = 0.0;
  AnchorInsertion insertion = AnchorInsertion::ExistingVertex;
};

/// Result of place_anchors: the anchors in the order of the set, plus diagnostics.
struct PlacedAnchors {
  std::vector<PlacedAnchor> anchors;
  /// One per anchor snapped farther than warn_snap_distance, naming file, line and anchor.
  std::vector<std::string> warnings;
  int vertices_inserted = 0;   ///< edge splits + face splits
  double bbox_diagonal = 0.0;  ///< the input mesh's bounding-box diagonal, mesh units
  PlacementSettings settings;  ///< the settings used
};

/// The warning place_anchors gives for `anchor` when it was given `snap_distance` from the surface
/// of a mesh whose bounding-box diagonal is `diagonal`; empty when that is within
/// settings.warn_snap_distance.
std::string snap_warning(const AnchorSpec& anchor, double snap_distance, double diagonal,
                         const PlacementSettings& settings);

/// Make every anchor of `anchors` a vertex of `mesh`, refining it where needed.
/// `mesh` is `input` or a refinement of it carrying provenance (init_provenance on a copy of
/// `input`, then only splits): vertex indices and faces in `anchors` refer to `input`.
/// Strong guarantee: on an exception `mesh` is unchanged.
/// Anchors given by position are snapped to `input` through `input_surface`, a nearest-point
/// index over `input`'s faces, when given (a caller placing anchors on one mesh again and again
/// builds it once); otherwise one is built here on the first position.
/// \throw InputError "file:line: anchor "name": ..." for a vertex index or face out of range
///   (checked against `input`), invalid barycentrics, a non-finite position, or two anchors
///   on one vertex (both named).
PlacedAnchors place_anchors(Mesh& mesh, const Mesh& input, const AnchorSet& anchors,
                            const PlacementSettings& settings = {},
                            const ClosestPointIndex* input_surface = nullptr);

/// Whether any anchor of `anchors` is given by position (place_anchors then needs a nearest-point
/// index over the input).
bool has_position_anchor(const AnchorSet& anchors);

}  // namespace xparam
