#pragma once
/// \file
/// Validation of a mesh file's content (a TriangleSoup) before any topology is built:
/// counts, topology (components, boundary loops, Euler characteristic, genus), and every
/// defect that makes the mesh unusable for the pipeline, each named with file indices.

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
  /// euler_characteristic then).
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
  /// faces, finite coordinates, no unreferenced vertices. Genus is deliberately not part of it.
  bool usable = false;

  /// The problems that block use, in the order found.
  std::vector<const Problem*> errors() const;
  /// The problems that do not block use.
  std::vector<const Problem*> warnings() const;
};

/// Validate a soup. Deterministic; O(F log F). Never throws on bad content: every defect
/// becomes a problem in the report.
/// \pre every triangle index is in [0, #V) (read_triangle_soup guarantees it; InternalError otherwise)
MeshReport validate_soup(const TriangleSoup& soup, const ValidationSettings& settings = {});

}  // namespace xparam
