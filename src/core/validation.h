#pragma once
/// \file
/// Validation of a mesh file's content (a TriangleSoup) before any topology is built:
/// counts, topology (components, boundary loops, Euler characteristic, genus), and every
/// defect that makes the mesh unusable for the pipeline, each named with file indices; and
/// the two repairs real scans need (faces wound against their neighbours, pinched vertices),
/// which the loader applies (io/mesh_loader.h) so that such a mesh stays usable.

#include "core/triangle_soup.h"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace xparam {

/// Thresholds of validate_soup.
struct ValidationSettings {
  /// A face whose area is below this times the squared bounding-box diagonal is "near zero"
  /// (blocks use): its barycentric coordinates and angles are dominated by rounding. Unitless.
  /// Measured: the smallest face of the 130 meshes in ../shared/data is 1.1e-10 x diagonal^2
  /// (tosca/centaur1.off), so real meshes pass with a margin of 100.
  double near_zero_area_relative = 1e-12;
  /// At most this many offending elements are named per problem kind; the rest are counted
  /// in one "and N more" message.
  int max_listed_per_kind = 10;
  /// Judge the mesh after repair_soup: faces wound against their neighbours are re-oriented and
  /// pinched vertices are split, so those two defects are reported as repaired instead of
  /// blocking use. On by default: TOSCA, SCAPE and SHREC'19 meshes need it. The repairs are only
  /// tried on an orientable mesh without non-manifold edges (those stay refused).
  bool repair = true;
};

/// What a problem is about; `blocks_use` tells which kinds make a mesh unusable.
enum class ProblemKind {
  Empty,                    ///< no vertices or no faces
  NonFiniteCoordinate,      ///< a vertex with a NaN or Inf coordinate
  DegenerateFace,           ///< repeated vertex index, or exactly zero area
  NearZeroAreaFace,         ///< area below ValidationSettings::near_zero_area_relative * bbox_diag^2
  NonManifoldEdge,          ///< an edge with more than two faces
  NonManifoldVertex,        ///< a vertex whose faces form more than one fan (a pinch)
  InconsistentOrientation,  ///< a two-face edge traversed in the same direction by both faces
  NonOrientable,            ///< no choice of face orientations is consistent (e.g. a Moebius band)
  Boundary,                 ///< the mesh is not closed
  MultipleComponents,       ///< more than one connected component
  UnreferencedVertex,       ///< a vertex used by no face
  DuplicateVertex,          ///< two vertices with equal coordinates (a warning only)
  PolygonsTriangulated,     ///< the file had faces with more than 3 corners (a warning only)
};

/// True for the kinds that make a mesh unusable (all except DuplicateVertex and
/// PolygonsTriangulated, which are reported as warnings).
bool blocks_use(ProblemKind kind);

/// Short stable name of a kind, e.g. "non_manifold_edge".
const char* to_string(ProblemKind kind);

/// One finding; `message` names the file and the element, e.g.
/// `scan_017.ply: edge (12, 40) has 3 faces`.
struct Problem {
  ProblemKind kind;
  std::string message;
  /// Fixed by repair_soup (ValidationSettings::repair): reported, but does not block use.
  bool repaired = false;
};

/// A pinched vertex split into one vertex per fan of faces (repair_soup).
struct VertexSplit {
  int vertex = -1;          ///< file index; keeps the fan holding its lowest-numbered face
  std::vector<int> copies;  ///< indices of the new vertices (after the file's), one per further fan
};

/// Everything validate_soup finds. Element lists hold file indices (0-based), complete and
/// sorted; `problems` names at most ValidationSettings::max_listed_per_kind of each kind.
struct MeshReport {
  std::string source;  ///< the soup's file name
  int vertices = 0;    ///< vertices in the file (referenced or not)
  int faces = 0;       ///< triangles (after fan triangulation of polygons)
  int edges = 0;       ///< distinct undirected edges of the triangles
  int polygons_triangulated = 0;  ///< file faces with more than 3 corners

  int components = 0;      ///< connected components of faces (faces sharing a vertex are connected)
  int boundary_edges = 0;  ///< edges with exactly one face
  /// Boundary loops, counted as connected components of the boundary edges (boundary edges
  /// sharing a vertex are in one loop), so a boundary pinched at a vertex counts once.
  int boundary_loops = 0;
  /// chi = V - E + F with V the referenced vertices (an unreferenced vertex is not part of the
  /// surface); E and F as above.
  int euler_characteristic = 0;
  /// (2 - chi - boundary_loops) / 2 when that is meaningful: one component, 2-manifold
  /// (edges and vertices), orientable, and chi + boundary_loops even. Empty otherwise (use
  /// euler_characteristic then). When pinched vertices were split (split_vertices), it is the
  /// genus of the split surface, whose chi is euler_characteristic + the number of copies.
  std::optional<int> genus;
  bool orientable = true;  ///< every component admits a consistent orientation

  std::vector<std::array<int, 2>> non_manifold_edges;  ///< (a, b), a < b, with more than two faces
  std::vector<int> non_manifold_vertices;              ///< pinched vertices
  std::vector<std::array<int, 2>> inconsistent_edges;  ///< (a, b), a < b, used twice in one direction
  std::vector<int> degenerate_faces;                   ///< repeated index or zero area
  std::vector<int> near_zero_area_faces;               ///< tiny but nonzero area
  /// (first, later) with exactly equal coordinates (-0 equals +0; no tolerance: a tolerance
  /// would depend on the scale, and exact copies are what unwelded seams produce)
  std::vector<std::array<int, 2>> duplicate_vertices;
  std::vector<int> unreferenced_vertices;
  std::vector<int> non_finite_vertices;                ///< NaN or Inf coordinate

  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();  ///< over the finite vertices
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
  double mean_edge_length = 0.0;  ///< over the distinct edges with finite end points
  double min_face_area = 0.0;     ///< smallest face area (finite faces), for diagnostics

  std::vector<Problem> problems;  ///< capped per kind; see blocks_use
  /// Closed, one component, 2-manifold, consistently oriented, no degenerate or near-zero
  /// faces, finite coordinates, no unreferenced vertices -- after the repairs when
  /// ValidationSettings::repair (a split can leave two components: that blocks use). Genus is
  /// deliberately not part of it.
  bool usable = false;

  /// The problems that block use, in the order found.
  std::vector<const Problem*> errors() const;
  /// The problems that do not block use.
  std::vector<const Problem*> warnings() const;
  /// The problems repair_soup fixed (Problem::repaired).
  std::vector<const Problem*> repaired() const;

  /// Filled when ValidationSettings::repair applied repair_soup: the faces it re-oriented
  /// (file indices, sorted) and the pinched vertices it split.
  std::vector<int> reoriented_faces;
  std::vector<VertexSplit> split_vertices;
};

/// Validate a soup. Deterministic; O(F log F). Never throws on bad content: every defect
/// becomes a problem in the report. Counts, components, chi and the problems describe the file;
/// with ValidationSettings::repair, the file's inconsistent-orientation and pinched-vertex
/// problems are marked repaired, the repairs are listed, and `usable` and `genus` are those of
/// repair_soup(soup) (validated again; any new problem is added, prefixed "after repair:").
/// \pre every triangle index is in [0, #V) (read_triangle_soup guarantees it; InternalError otherwise)
MeshReport validate_soup(const TriangleSoup& soup, const ValidationSettings& settings = {});

/// One line naming the repairs a report lists, e.g. "36 faces re-oriented to agree with their
/// neighbours; vertex 419 split into 2 (copy 12500)"; empty when there are none.
std::string describe_repairs(const MeshReport& report);

/// A soup with the two repairs applied, and what they changed.
struct SoupRepair {
  /// The repaired soup: every face in `reversed` as (a, c, b), and in every face of a pinched
  /// vertex's further fans the vertex replaced by that fan's copy (same position). Vertex i < #V
  /// and face j keep their file numbering; the copies follow the file's vertices.
  TriangleSoup soup;
  std::vector<bool> reversed;             ///< per face: re-oriented (true for reoriented_faces)
  std::vector<int> reoriented_faces;      ///< sorted file face indices
  std::vector<VertexSplit> split_vertices;  ///< sorted by vertex
};

/// Repair a soup for the pipeline. (1) Orientation: a breadth-first walk over the faces across
/// edges with exactly two faces gives every face the winding of its neighbours; in each
/// component the smaller of the two winding classes is reversed (a tie keeps the winding of the
/// component's lowest-numbered face), so the fewest faces change. Outward orientation is not
/// decided here (the loader does it by signed volume). (2) Pinches: a vertex whose faces form
/// k > 1 fans (faces joined across edges through the vertex) becomes k vertices; the fan with
/// the lowest-numbered face keeps the index, the others get copies numbered from #V on, in
/// order of vertex and then of each fan's lowest face. Faces that repeat a vertex index are
/// left out of both and kept as they are. Deterministic; O(F log F).
/// \pre orientable, no non-manifold edges (otherwise some edge or vertex stays defective)
SoupRepair repair_soup(const TriangleSoup& soup);

}  // namespace xparam
