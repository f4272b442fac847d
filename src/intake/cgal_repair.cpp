// The only translation unit of xparam that includes CGAL (see cgal_repair.h for why).
#include "intake/cgal_repair.h"

#include "core/errors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <set>
#include <utility>

namespace xparam::intake {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using FaceIndex = SurfaceMesh::Face_index;
using HalfedgeIndex = SurfaceMesh::Halfedge_index;
namespace PMP = CGAL::Polygon_mesh_processing;

Point3 to_cgal(const Point& p) { return {p[0], p[1], p[2]}; }
Point to_array(const Point3& p) { return {p.x(), p.y(), p.z()}; }

// Per input point: the lowest-numbered input point with the same coordinates (CGAL welds such
// points, so this is the one a welded point stands for).
std::vector<int> canonical_points(const std::vector<Point>& points, std::map<Point, int>& first_at) {
  std::vector<int> canonical(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    canonical[i] = first_at.emplace(points[i], static_cast<int>(i)).first->second;
  return canonical;
}

// The triangles of non-zero area as CGAL's soup functions take them; `degenerate[j]` says whether
// triangle j has zero area (exactly: collinear corners, two at one position included). CGAL's soup
// repair drops triangles with two equal corners but keeps collinear ones, which STL exports hold.
std::vector<std::vector<std::size_t>> nondegenerate_polygons(const std::vector<Point3>& points,
                                                             const std::vector<Triangle>& triangles,
                                                             std::vector<bool>& degenerate) {
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(triangles.size());
  degenerate.assign(triangles.size(), false);
  for (std::size_t j = 0; j < triangles.size(); ++j) {
    const Triangle& t = triangles[j];
    degenerate[j] = CGAL::collinear(points[t[0]], points[t[1]], points[t[2]]);
    if (!degenerate[j])
      polygons.push_back(
          {static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});
  }
  return polygons;
}

// A Surface_mesh whose vertex i is points[i] and face j is triangles[j] (nothing is ever removed
// from it, so Surface_mesh numbers its elements in insertion order).
SurfaceMesh build_surface_mesh(const std::vector<Point>& points, const std::vector<Triangle>& triangles) {
  SurfaceMesh mesh;
  mesh.reserve(static_cast<SurfaceMesh::size_type>(points.size()), static_cast<SurfaceMesh::size_type>(3 * triangles.size()),
               static_cast<SurfaceMesh::size_type>(triangles.size()));
  for (const Point& p : points) mesh.add_vertex(to_cgal(p));
  for (const Triangle& t : triangles) {
    const FaceIndex f = mesh.add_face(VertexIndex(t[0]), VertexIndex(t[1]), VertexIndex(t[2]));
    XP_ASSERT_MSG(f != SurfaceMesh::null_face(), "triangle (" << t[0] << ", " << t[1] << ", " << t[2]
                                                              << ") is not manifold after repair_and_orient");
  }
  return mesh;
}

double triangle_area(const Point3& a, const Point3& b, const Point3& c) {
  return std::sqrt(CGAL::to_double(CGAL::squared_area(a, b, c)));
}

}  // namespace

RepairedSoup repair_and_orient(const std::vector<Point>& points, const std::vector<Triangle>& triangles) {
  std::map<Point, int> first_at;
  const std::vector<int> canonical = canonical_points(points, first_at);
  // Each input triangle by its corners' canonical points, sorted: CGAL drops all but one of the
  // triangles sharing a key (duplicates); zero-area ones (degenerate) never reach it.
  std::map<std::array<int, 3>, int> first_triangle_with;
  for (std::size_t j = 0; j < triangles.size(); ++j) {
    std::array<int, 3> key{canonical[triangles[j][0]], canonical[triangles[j][1]], canonical[triangles[j][2]]};
    std::sort(key.begin(), key.end());
    first_triangle_with.emplace(key, static_cast<int>(j));
  }

  std::vector<Point3> cgal_points;
  cgal_points.reserve(points.size());
  for (const Point& p : points) cgal_points.push_back(to_cgal(p));
  std::vector<bool> degenerate;
  std::vector<std::vector<std::size_t>> polygons = nondegenerate_polygons(cgal_points, triangles, degenerate);
  PMP::repair_polygon_soup(cgal_points, polygons);
  const std::size_t welded_points = cgal_points.size();
  PMP::orient_polygon_soup(cgal_points, polygons);

  RepairedSoup out;
  out.split_points = static_cast<int>(cgal_points.size() - welded_points);
  out.points.reserve(cgal_points.size());
  out.point_source.reserve(cgal_points.size());
  for (const Point3& p : cgal_points) {
    out.points.push_back(to_array(p));
    const auto at = first_at.find(out.points.back());
    XP_ASSERT_MSG(at != first_at.end(), "CGAL returned a point that is not in the input");
    out.point_source.push_back(at->second);
  }
  out.triangles.reserve(polygons.size());
  for (const auto& polygon : polygons) {
    Triangle t{static_cast<int>(polygon[0]), static_cast<int>(polygon[1]), static_cast<int>(polygon[2])};
    std::array<int, 3> key{out.point_source[t[0]], out.point_source[t[1]], out.point_source[t[2]]};
    std::sort(key.begin(), key.end());
    const auto at = first_triangle_with.find(key);
    XP_ASSERT_MSG(at != first_triangle_with.end(), "CGAL returned a triangle that is not in the input");
    const int source = at->second;
    // Rotate so corner 0 is the input's corner 0, then the order of the other two says the winding.
    const int first = canonical[triangles[source][0]];
    while (out.point_source[t[0]] != first) std::rotate(t.begin(), t.begin() + 1, t.end());
    const bool reversed = out.point_source[t[1]] != canonical[triangles[source][1]];
    out.triangles.push_back(t);
    out.triangle_source.push_back(source);
    out.reversed.push_back(reversed);
    out.reversed_triangles += reversed;
  }

  std::set<int> kept_sources(out.triangle_source.begin(), out.triangle_source.end());
  for (std::size_t j = 0; j < triangles.size(); ++j) {
    if (kept_sources.count(static_cast<int>(j)) != 0) continue;
    (degenerate[j] ? out.degenerate_triangles : out.duplicate_triangles) += 1;
  }
  std::set<int> used;
  for (const Triangle& t : out.triangles)
    for (int v : t) used.insert(out.point_source[v]);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (canonical[i] != static_cast<int>(i))
      ++out.merged_points;
    else if (used.count(static_cast<int>(i)) == 0)
      ++out.unused_points;
  }
  return out;
}

std::vector<int> triangle_components(const std::vector<Point>& points, const std::vector<Triangle>& triangles) {
  SurfaceMesh mesh = build_surface_mesh(points, triangles);
  auto map = mesh.add_property_map<FaceIndex, std::size_t>("f:component", 0).first;
  PMP::connected_components(mesh, map);
  std::vector<int> component;
  component.reserve(triangles.size());
  for (FaceIndex f : mesh.faces()) component.push_back(static_cast<int>(map[f]));
  return component;
}

namespace {

// The mesh's points [0, n_points) and faces: the input's `triangles` (in their own corner order)
// then the patches' faces up to n_faces.
void mesh_arrays(const SurfaceMesh& mesh, const std::vector<Triangle>& triangles, std::size_t n_points,
                 std::size_t n_faces, std::vector<Point>& points, std::vector<Triangle>& faces) {
  points.clear();
  points.reserve(n_points);
  for (std::size_t v = 0; v < n_points; ++v) points.push_back(to_array(mesh.point(VertexIndex(static_cast<SurfaceMesh::size_type>(v)))));
  faces.assign(triangles.begin(), triangles.end());
  faces.reserve(n_faces);
  for (std::size_t f = triangles.size(); f < n_faces; ++f) {
    const HalfedgeIndex fh = mesh.halfedge(FaceIndex(static_cast<SurfaceMesh::size_type>(f)));
    faces.push_back({static_cast<int>(mesh.source(fh).idx()), static_cast<int>(mesh.target(fh).idx()),
                     static_cast<int>(mesh.target(mesh.next(fh)).idx())});
  }
}

// Fill the hole of border halfedge `start` (faired or not) and measure the patch into `hole`.
void fill_one(SurfaceMesh& mesh, HalfedgeIndex start, bool fair, const std::vector<FaceIndex>& around, Hole& hole) {
  std::vector<FaceIndex> patch;
  std::vector<VertexIndex> added;
  if (fair) {
    hole.faired = std::get<0>(
        PMP::triangulate_refine_and_fair_hole(mesh, start, std::back_inserter(patch), std::back_inserter(added)));
  } else {
    hole.faired = false;
    PMP::triangulate_and_refine_hole(mesh, start, std::back_inserter(patch), std::back_inserter(added));
  }
  hole.filled = true;
  hole.triangles = static_cast<int>(patch.size());
  hole.points = static_cast<int>(added.size());
  hole.area = 0.0;
  for (FaceIndex f : patch) {
    XP_ASSERT_MSG(static_cast<int>(f.idx()) >= hole.first_triangle, "a fill patch reused an existing face");
    const HalfedgeIndex fh = mesh.halfedge(f);
    hole.area += triangle_area(mesh.point(mesh.source(fh)), mesh.point(mesh.target(fh)),
                               mesh.point(mesh.target(mesh.next(fh))));
  }
  std::vector<FaceIndex> tested = patch;
  tested.insert(tested.end(), around.begin(), around.end());
  std::sort(tested.begin(), tested.end());
  tested.erase(std::unique(tested.begin(), tested.end()), tested.end());
  hole.self_intersecting = PMP::does_self_intersect(tested, mesh);
}

}  // namespace

FilledSoup fill_holes(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                      const HoleFillSettings& settings) {
  SurfaceMesh mesh = build_surface_mesh(points, triangles);
  FilledSoup out;

  // The border cycles first, each by the two ends of its lowest-numbered border halfedge (vertex
  // numbers survive rebuilding the mesh; halfedge numbers do not).
  std::vector<std::pair<VertexIndex, VertexIndex>> cycles;
  std::vector<bool> seen(mesh.number_of_halfedges(), false);
  for (HalfedgeIndex h : mesh.halfedges()) {
    if (!mesh.is_border(h) || seen[h.idx()]) continue;
    cycles.emplace_back(mesh.source(h), mesh.target(h));
    for (HalfedgeIndex g = h; !seen[g.idx()]; g = mesh.next(g)) seen[g.idx()] = true;
  }

  for (const auto& [u, v] : cycles) {
    const HalfedgeIndex start = mesh.halfedge(u, v);
    XP_ASSERT(start != SurfaceMesh::null_halfedge() && mesh.is_border(start));
    Hole hole;
    std::vector<FaceIndex> around;  // the faces outside the hole along its border
    HalfedgeIndex h = start;
    do {
      hole.border.push_back(static_cast<int>(mesh.source(h).idx()));
      hole.perimeter += std::sqrt(CGAL::to_double(CGAL::squared_distance(mesh.point(mesh.source(h)), mesh.point(mesh.target(h)))));
      around.push_back(mesh.face(mesh.opposite(h)));
      h = mesh.next(h);
    } while (h != start);
    hole.first_triangle = static_cast<int>(mesh.number_of_faces());
    hole.first_point = static_cast<int>(mesh.number_of_vertices());
    if (hole.perimeter <= settings.max_perimeter) {
      fill_one(mesh, start, true, around, hole);
      if (hole.self_intersecting) {
        // Redo without fairing: a faired patch over a long, bent border can fold through the
        // surface where a flat refined one does not. The mesh is rebuilt without the patch.
        std::vector<Point> kept_points;
        std::vector<Triangle> kept_faces;
        mesh_arrays(mesh, triangles, static_cast<std::size_t>(hole.first_point),
                    static_cast<std::size_t>(hole.first_triangle), kept_points, kept_faces);
        mesh = build_surface_mesh(kept_points, kept_faces);  // `around` keeps its numbers
        fill_one(mesh, mesh.halfedge(u, v), false, around, hole);
      }
    }
    out.holes.push_back(std::move(hole));
  }

  // Nothing was removed, so the mesh's elements are numbered in the order they were added.
  XP_ASSERT(mesh.number_of_removed_faces() == 0 && mesh.number_of_removed_vertices() == 0);
  mesh_arrays(mesh, triangles, mesh.number_of_vertices(), mesh.number_of_faces(), out.points, out.triangles);
  return out;
}

}  // namespace xparam::intake
