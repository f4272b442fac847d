#pragma once
/// \file
/// Boundary stretching (paper section 2, step 1; ARCHITECTURE.md step 4): a layout curve
/// becomes a locally shortest geodesic inside the union of its two patches and is inserted
/// into the mesh by splitting the edges it crosses.
///
/// Method: a funnel over an unfolded face strip with re-routing around vertices (in the
/// manner of Xin & Wang 2007, "Efficiently determining a locally exact shortest path on
/// polyhedral surfaces"). The curve is held as a strip of region faces; the funnel gives the
/// exact shortest path inside the strip; wherever that path bends at a vertex whose other side
/// spans less than pi (and lies in the region), the strip is swapped to that side, which
/// strictly shortens the path. The mesh is only touched once, at the end, so intermediate
/// curves leave no vertices behind.

#include "core/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace xparam {

/// Options of straighten_path.
struct StraightenSettings {
  /// A crossing closer than this fraction of the crossed edge's length to one of its ends
  /// passes through that end instead (no needle triangles), when that bends the curve there
  /// by at most about 2 * snap_tolerance radians; 0 snaps only crossings within 1e-12.
  double snap_tolerance = 1e-4;
  /// Radians: the curve is re-routed around a vertex whose free side spans less than
  /// pi - angle_tolerance.
  double angle_tolerance = 1e-9;
  /// Bound on the funnel rounds (each round re-routes around every vertex that needs it).
  int max_rounds = 1000;
};

/// One point of a straightened curve before insertion: a mesh vertex the curve passes through,
/// or a point inside a mesh edge it crosses.
struct CurvePoint {
  VertexHandle vertex;                              ///< valid: the curve passes through this vertex
  EdgeHandle edge;                                  ///< otherwise: the edge crossed here
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< 3-D position
};

/// A straightened curve not inserted yet (straighten_curve); valid until the mesh changes.
struct StraightenedCurve {
  std::vector<CurvePoint> points;  ///< from the first to the last vertex of the input path
  /// Interior curve vertices not inside the region (touching its boundary or the mesh
  /// boundary), in curve order: the curve bends around them.
  std::vector<VertexHandle> contacts;
  int snapped_crossings = 0;  ///< crossings moved onto an existing vertex by snap_tolerance
  int rounds = 0;             ///< funnel rounds run
  int reroutes = 0;           ///< vertices the strip was swapped around
  bool converged = false;     ///< false when max_rounds stopped a curve that could still shorten
  double input_length = 0.0;  ///< length of the input path (mesh units)
  double length = 0.0;        ///< length of the polyline through `points` (mesh units)
  StraightenSettings settings;
};

/// What straighten_path did.
struct StraightenResult {
  /// The new curve: mesh vertices from the first to the last vertex of the input path, each
  /// joined to the next by a mesh edge.
  std::vector<VertexHandle> chain;
  int vertices_added = 0;     ///< edge splits made to insert the curve (new mesh vertices)
  int snapped_crossings = 0;  ///< crossings moved onto an existing vertex by snap_tolerance
  int rounds = 0;             ///< funnel rounds run
  int reroutes = 0;           ///< vertices the strip was swapped around
  bool converged = false;     ///< false when max_rounds stopped a curve that could still shorten
  /// Interior chain vertices touching the region's boundary (or the mesh boundary): the curve
  /// bends around them, so it shares them with whatever bounds the region.
  int boundary_contacts = 0;
  std::vector<VertexHandle> contacts;  ///< those vertices, in chain order
  double input_length = 0.0;           ///< length of the input path (mesh units)
  double length = 0.0;                 ///< length of the returned chain (mesh units)
  StraightenSettings settings;
};

/// Straightens `path` into a locally shortest geodesic of the region formed by the faces f
/// with region_mask[f.idx()] == true, without changing the mesh (see straighten_path for the
/// method, the preconditions and the guarantees). Callers that must look at the curve before
/// committing to it (boundary_stretching.h keeps curves off other curves) plan with this and
/// insert with insert_curve.
/// \pre region_mask.size() == mesh.n_faces()
/// \throw LayoutError as straighten_path
StraightenedCurve straighten_curve(const Mesh& mesh, const std::vector<bool>& region_mask,
                                   const std::vector<VertexHandle>& path,
                                   const StraightenSettings& settings = {});

/// Inserts a planned curve into the mesh it was planned on (unchanged since): splits every
/// crossed edge with split_edge_keeping_provenance; region_mask grows with the mesh and every
/// new face inherits the flag of the face it was cut from.
/// \pre has_provenance(mesh), `curve` came from straighten_curve on this very mesh state
/// \throw LayoutError when the mesh has no provenance (then it is left untouched)
StraightenResult insert_curve(Mesh& mesh, std::vector<bool>& region_mask, const StraightenedCurve& curve);

/// Straightens `path` into a locally shortest geodesic of the region formed by the faces f
/// with region_mask[f.idx()] == true, then inserts it into `mesh` (straighten_curve, then
/// insert_curve). Where nothing was snapped
/// the chain is locally shortest up to rounding; a snapped crossing bends it by at most about
/// 2 * snap_tolerance radians (is_locally_shortest with 2.5 * snap_tolerance holds).
///
/// `path` is a simple chain of mesh vertices along mesh edges from anchor a to anchor b
/// (a != b); its interior vertices must lie inside the region (every incident face in it, not
/// on the mesh boundary). The endpoints stay fixed, the curve never crosses the region's
/// boundary (it may bend around a boundary vertex, see boundary_contacts). Crossed edges are
/// split with split_edge_keeping_provenance; region_mask grows with the mesh and every new
/// face inherits the flag of the face it was cut from.
///
/// \pre has_provenance(mesh), region_mask.size() == mesh.n_faces()
/// \throw LayoutError when the path or the region breaks the preconditions, or when the
///        straightened curve would cross one face twice (then the mesh is left untouched)
StraightenResult straighten_path(Mesh& mesh, std::vector<bool>& region_mask,
                                 const std::vector<VertexHandle>& path,
                                 const StraightenSettings& settings = {});

}  // namespace xparam
