#pragma once
/// \file
/// The CGAL jobs of the scan intake behind plain arrays: soup repair and orientation, connected
/// components, hole filling. CGAL (Polygon Mesh Processing, GPL-3.0-or-later) is included by
/// cgal_repair.cpp alone: one translation unit costs about 60 s of CPU and 1.7 GB to compile, and
/// no other file of xparam sees its headers. Every function keeps track of where each output
/// element came from, so the intake can map the prepared mesh back onto the file.

#include <array>
#include <vector>

namespace xparam::intake {

/// A vertex position (x, y, z).
using Point = std::array<double, 3>;
/// Three 0-based vertex indices.
using Triangle = std::array<int, 3>;

/// A soup after CGAL's repair_polygon_soup and orient_polygon_soup, with the origin of every
/// element in the input's numbering.
struct RepairedSoup {
  std::vector<Point> points;        ///< no two equal, every one used by a triangle
  std::vector<Triangle> triangles;  ///< consistently oriented within each component
  /// Per point: the input point it is (the lowest-numbered input point at these coordinates).
  std::vector<int> point_source;
  /// Per triangle: the input triangle it is (the lowest-numbered of equal duplicates).
  std::vector<int> triangle_source;
  /// Per triangle: corner 0 is the input triangle's corner 0, and the corners run in the
  /// input's order (false) or reversed (true).
  std::vector<bool> reversed;
  int merged_points = 0;         ///< input points welded onto an earlier point at equal coordinates
  int unused_points = 0;         ///< input points no kept triangle uses
  int degenerate_triangles = 0;  ///< input triangles removed: zero area (collinear or coincident corners)
  int duplicate_triangles = 0;   ///< input triangles removed: the same three corners as an earlier one
  /// Points added by orient_polygon_soup to cut open non-manifold edges and vertices and
  /// strips that cannot be oriented (a copy of an input point each).
  int split_points = 0;
  int reversed_triangles = 0;  ///< kept triangles stored reversed to agree with their neighbours
};

/// Repair and orient a soup (zero-area triangles dropped, then CGAL PMP repair_polygon_soup, then
/// orient_polygon_soup), then record each output element's origin by its exact coordinates (both
/// CGAL steps copy points bit for bit). Deterministic. \pre every index in [0, #points)
RepairedSoup repair_and_orient(const std::vector<Point>& points, const std::vector<Triangle>& triangles);

/// Connected components of a repaired soup (triangles sharing an edge), as CGAL PMP
/// connected_components numbers them on the Surface_mesh built in soup order: per triangle.
/// \pre the soup is a valid polygon mesh (repair_and_orient's output)
std::vector<int> triangle_components(const std::vector<Point>& points, const std::vector<Triangle>& triangles);

/// Limits of fill_holes.
struct HoleFillSettings {
  /// Holes whose border is longer than this (mesh units) are left open and reported.
  double max_perimeter = 0.0;
};

/// One boundary loop of the soup, filled or not.
struct Hole {
  std::vector<int> border;  ///< its vertices, in the order of its border halfedges
  double perimeter = 0.0;   ///< length of the border, mesh units
  bool filled = false;      ///< false when longer than HoleFillSettings::max_perimeter
  bool faired = false;      ///< CGAL's fairing succeeded (otherwise the patch is refined but not faired)
  /// Triangles of the patch intersect each other or the faces around the hole, even after the
  /// redo without fairing: the caller refuses the hole.
  bool self_intersecting = false;
  int first_triangle = 0;   ///< the patch is triangles [first_triangle, first_triangle + triangles)
  int triangles = 0;
  int first_point = 0;      ///< new points [first_point, first_point + points)
  int points = 0;
  double area = 0.0;        ///< area of the patch, mesh units squared
};

/// A soup with its holes filled: the input's points and triangles unchanged and first, each
/// filled hole's new points and triangles appended after them, in the order of `holes`.
struct FilledSoup {
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  std::vector<Hole> holes;  ///< in the order of their lowest-numbered border halfedge
};

/// Fill every hole no longer than settings.max_perimeter with CGAL PMP
/// triangulate_refine_and_fair_hole (a patch refined to the density around it and faired to
/// continue the surface smoothly), and test each patch with PMP does_self_intersect against itself
/// and the faces around the hole; a faired patch that intersects is redone once without fairing
/// (triangulate_and_refine_hole) and tested again. Deterministic.
/// \pre the soup is a valid, oriented polygon mesh (repair_and_orient's output, one component)
FilledSoup fill_holes(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                      const HoleFillSettings& settings);

}  // namespace xparam::intake
