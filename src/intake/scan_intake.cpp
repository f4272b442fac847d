#include "intake/scan_intake.h"

#include "core/errors.h"
#include "intake/cgal_repair.h"
#include "intake/cgal_topology.h"
#include "intake/handle_cut.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <set>

namespace xparam {
namespace {

using intake::Point;
using intake::Triangle;

Eigen::Vector3d vec(const Point& p) { return {p[0], p[1], p[2]}; }

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

std::string percent(double share) { return number(100.0 * share) + "%"; }

double area(const std::vector<Point>& points, const Triangle& t) {
  return 0.5 * (vec(points[t[1]]) - vec(points[t[0]])).cross(vec(points[t[2]]) - vec(points[t[0]])).norm();
}

double bbox_diagonal(const TriangleSoup& soup) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const Eigen::Vector3d& p : soup.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return soup.vertices.empty() ? 0.0 : (hi - lo).norm();
}

// The point among `candidates` (indices into `points`) nearest to `p`: index and distance.
std::pair<int, double> nearest(const std::vector<Point>& points, const std::vector<int>& candidates,
                               const Eigen::Vector3d& p) {
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  for (int i : candidates) {
    const double d = (vec(points[i]) - p).norm();
    if (d < best.second) best = {i, d};
  }
  return best;
}

// The parts of a repaired soup and which one is kept.
struct Parts {
  std::vector<int> of_triangle;  // part per triangle
  std::vector<double> area;      // per part
  int kept = 0;
};

// Step 2: keep the part holding most landmarks (the largest by area among equals), refuse when
// that drops a landmark's part or too much area.
Parts choose_part(const intake::RepairedSoup& repaired, const std::vector<IntakeLandmark>& landmarks,
                  const IntakeSettings& settings, const std::string& source, double diagonal) {
  Parts parts;
  parts.of_triangle = intake::triangle_components(repaired.points, repaired.triangles);
  const int count = 1 + *std::max_element(parts.of_triangle.begin(), parts.of_triangle.end());
  parts.area.assign(static_cast<std::size_t>(count), 0.0);
  std::vector<int> of_point(repaired.points.size(), -1);
  for (std::size_t j = 0; j < repaired.triangles.size(); ++j) {
    parts.area[parts.of_triangle[j]] += area(repaired.points, repaired.triangles[j]);
    for (int v : repaired.triangles[j]) of_point[v] = parts.of_triangle[j];
  }
  if (count == 1) return parts;

  std::vector<int> all_points(repaired.points.size());
  std::iota(all_points.begin(), all_points.end(), 0);
  std::vector<int> landmark_part;
  std::vector<int> held(static_cast<std::size_t>(count), 0);
  for (const IntakeLandmark& landmark : landmarks) {
    landmark_part.push_back(of_point[nearest(repaired.points, all_points, landmark.position).first]);
    ++held[landmark_part.back()];
  }
  for (int c = 1; c < count; ++c) {
    if (held[c] > held[parts.kept] || (held[c] == held[parts.kept] && parts.area[c] > parts.area[parts.kept]))
      parts.kept = c;
  }
  const double total = std::accumulate(parts.area.begin(), parts.area.end(), 0.0);
  const std::string intro = source + ": " + std::to_string(count) + " parts; the one kept holds " +
                            percent(parts.area[parts.kept] / total) + " of the area";

  // A landmark nearest to a dropped part is refused only when the kept part is not close by
  // either (1% of the diagonal): landmarks given as positions are snapped onto the kept surface.
  std::vector<int> kept_points;
  for (std::size_t i = 0; i < of_point.size(); ++i)
    if (of_point[i] == parts.kept) kept_points.push_back(static_cast<int>(i));
  for (std::size_t k = 0; k < landmarks.size(); ++k) {
    if (landmark_part[k] == parts.kept) continue;
    const double gap = nearest(repaired.points, kept_points, landmarks[k].position).second;
    if (gap > 0.01 * diagonal)
      throw InputError(intro + ", but anchor \"" + landmarks[k].name + "\" lies on a part of " +
                       percent(parts.area[landmark_part[k]] / total) + " of the area that would be dropped (" +
                       number(gap) + " from the kept part): move the anchor onto the main surface or join the "
                       "parts in a mesh editor");
  }
  const double dropped = 1.0 - parts.area[parts.kept] / total;
  if (dropped > settings.max_dropped_area)
    throw InputError(intro + "; dropping the rest (" + percent(dropped) + ") is over --max-dropped-area " +
                     percent(settings.max_dropped_area) +
                     ": join or delete the parts in a mesh editor, or raise --max-dropped-area");
  return parts;
}

// The landmark nearest to any of `border` (indices into `points`); "" when none is given.
std::string nearest_landmark(const std::vector<Point>& points, const std::vector<int>& border,
                             const std::vector<IntakeLandmark>& landmarks) {
  std::string near;
  double best = std::numeric_limits<double>::infinity();
  for (const IntakeLandmark& landmark : landmarks) {
    const double d = nearest(points, border, landmark.position).second;
    if (d < best) {
      best = d;
      near = landmark.name;
    }
  }
  return near;
}

// Genus of a closed mesh of one component whose points are all used (E = 3F/2).
int closed_genus(const std::vector<Point>& points, const std::vector<Triangle>& triangles) {
  const long long euler = static_cast<long long>(points.size()) - static_cast<long long>(triangles.size()) / 2;
  return static_cast<int>((2 - euler) / 2);
}

// Step 4: while the closed mesh has genus > 0, cut it open along a short non-contractible cycle
// (intake::short_non_contractible_cycle) and cap both sides like holes; refuse a cycle longer than
// the limit. The cut's copies and the caps' points are appended to `points` (their sources to
// `vertex_source`), the caps' faces to `triangles`.
void cut_handles(std::vector<Point>& points, std::vector<Triangle>& triangles, std::vector<int>& vertex_source,
                 IntakeRecord& record, const std::vector<IntakeLandmark>& landmarks, const IntakeSettings& settings,
                 const std::string& source, double diagonal, int file_vertices) {
  const double max_handle = settings.max_handle > 0.0 ? settings.max_handle : settings.max_handle_relative * diagonal;
  for (int genus = closed_genus(points, triangles); genus > 0;) {
    const intake::EdgeCycle found = intake::short_non_contractible_cycle(points, triangles);
    const std::vector<int>& cycle = found.vertices;
    CutHandle handle;
    handle.length = found.length;
    handle.nearest_anchor = nearest_landmark(points, cycle, landmarks);
    const std::string what = "handle (genus " + std::to_string(genus) + ") with a loop of " +
                             number(handle.length) +
                             (handle.nearest_anchor.empty() ? std::string() : " at \"" + handle.nearest_anchor + "\"");
    const std::string limit = max_handle == 0.0          ? "0 (no handle is cut)"
                              : settings.max_handle > 0.0 ? number(max_handle)
                                                          : number(max_handle) + " (" +
                                                                percent(settings.max_handle_relative) +
                                                                " of the bounding-box diagonal)";
    if (handle.length > max_handle)
      throw InputError(source + ": " + what + " is over --max-handle " + limit +
                       ": close the handle (a tunnel where two surfaces touch) in a mesh editor, or raise "
                       "--max-handle if caps may cut it");
    if (std::set<int>(cycle.begin(), cycle.end()).size() != cycle.size() || cycle.size() < 3)
      throw InputError(source + ": " + what + ": the loop passes a vertex twice and cannot be cut open; close the "
                       "handle in a mesh editor");

    // A copy of a fill vertex is one more fill vertex, so fill vertices stay numbered in order.
    for (int copied : intake::cut_along_cycle(points, triangles, cycle)) {
      const bool of_fill = vertex_source[copied] >= file_vertices;
      vertex_source.push_back(of_fill ? file_vertices + record.filled_vertices : vertex_source[copied]);
      record.filled_vertices += of_fill;
      handle.vertices += of_fill;
    }
    intake::FilledSoup capped =
        intake::fill_holes(points, triangles, {std::numeric_limits<double>::infinity()});
    XP_ASSERT_EQ(capped.holes.size(), 2u);
    handle.faired = true;
    for (const intake::Hole& cap : capped.holes) {
      if (cap.self_intersecting)
        throw InputError(source + ": the caps closing the " + what +
                         " after cutting it open intersect the surface: close the handle in a mesh editor");
      handle.faces += cap.triangles;
      handle.vertices += cap.points;
      handle.area += cap.area;
      handle.faired = handle.faired && cap.faired;
      for (int m = 0; m < cap.points; ++m) vertex_source.push_back(file_vertices + record.filled_vertices++);
    }
    record.filled_faces += handle.faces;
    record.handles.push_back(handle);
    points = std::move(capped.points);
    triangles = std::move(capped.triangles);
    const std::vector<int> parts = intake::triangle_components(points, triangles);
    if (*std::max_element(parts.begin(), parts.end()) > 0)
      throw InputError(source + ": " + what + ": the loop separates the surface, so cutting it leaves two parts; "
                       "close the handle in a mesh editor");
    const int cut_genus = closed_genus(points, triangles);
    XP_ASSERT_MSG(cut_genus < genus, "cutting a handle left genus " << cut_genus << " of " << genus);
    genus = cut_genus;
  }
}

}  // namespace

PreparedScan prepare_scan(const TriangleSoup& soup, const std::vector<IntakeLandmark>& landmarks,
                          const IntakeSettings& settings) {
  const auto file_vertices = static_cast<int>(soup.vertices.size());
  const auto file_faces = static_cast<int>(soup.triangles.size());
  std::vector<Point> points;
  points.reserve(soup.vertices.size());
  for (const Eigen::Vector3d& p : soup.vertices) points.push_back({p.x(), p.y(), p.z()});

  // Step 1: repair and orient.
  const intake::RepairedSoup repaired = intake::repair_and_orient(points, soup.triangles);
  if (repaired.triangles.empty())
    throw InputError(soup.source + ": no face is left after removing degenerate and duplicated faces: the file holds no "
                     "surface; export the mesh again");
  PreparedScan out;
  IntakeRecord& record = out.record;
  record.applied = true;
  record.merged_vertices = repaired.merged_points;
  record.unused_vertices = repaired.unused_points;
  record.degenerate_faces = repaired.degenerate_triangles;
  record.duplicate_faces = repaired.duplicate_triangles;
  record.split_vertices = repaired.split_points;
  record.reversed_faces = repaired.reversed_triangles;

  // Step 2: one part.
  const double diagonal = bbox_diagonal(soup);
  const Parts parts = choose_part(repaired, landmarks, settings, soup.source, diagonal);
  record.parts = static_cast<int>(parts.area.size());
  record.total_area = std::accumulate(parts.area.begin(), parts.area.end(), 0.0);
  std::vector<int> part_faces(parts.area.size(), 0);
  for (int part : parts.of_triangle) ++part_faces[part];
  for (std::size_t c = 0; c < parts.area.size(); ++c)
    if (static_cast<int>(c) != parts.kept) record.dropped_parts.push_back({part_faces[c], parts.area[c]});
  std::stable_sort(record.dropped_parts.begin(), record.dropped_parts.end(),
                   [](const DroppedPart& a, const DroppedPart& b) { return a.area > b.area; });

  // The kept part's points and triangles, in the repaired soup's order.
  std::vector<int> new_index(repaired.points.size(), -1);
  std::vector<Point> kept_points;
  std::vector<Triangle> kept_triangles;
  std::vector<int> kept_source;
  for (std::size_t j = 0; j < repaired.triangles.size(); ++j) {
    if (parts.of_triangle[j] != parts.kept) continue;
    for (int v : repaired.triangles[j]) new_index[v] = 0;
  }
  for (std::size_t i = 0; i < repaired.points.size(); ++i) {
    if (new_index[i] < 0) continue;
    new_index[i] = static_cast<int>(kept_points.size());
    kept_points.push_back(repaired.points[i]);
    out.vertex_source.push_back(repaired.point_source[i]);
  }
  for (std::size_t j = 0; j < repaired.triangles.size(); ++j) {
    if (parts.of_triangle[j] != parts.kept) continue;
    const Triangle& t = repaired.triangles[j];
    kept_triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
    out.face_source.push_back(repaired.triangle_source[j]);
    out.reversed.push_back(repaired.reversed[j]);
  }

  // Step 3: holes.
  const double max_hole = settings.max_hole > 0.0 ? settings.max_hole : settings.max_hole_relative * diagonal;
  intake::FilledSoup filled = intake::fill_holes(kept_points, kept_triangles, {max_hole});
  for (const intake::Hole& hole : filled.holes) {
    const std::string near = nearest_landmark(filled.points, hole.border, landmarks);
    const std::string where = "hole of " + number(hole.perimeter) + " perimeter" +
                              (near.empty() ? std::string() : " at \"" + near + "\"");
    if (!hole.filled)
      throw InputError(soup.source + ": " + where + " is over --max-hole " + number(max_hole) +
                       (settings.max_hole > 0.0 ? std::string() : " (" + percent(settings.max_hole_relative) +
                                                                      " of the bounding-box diagonal)") +
                       ": close it in a mesh editor, or raise --max-hole if a patch may cover it");
    if (hole.self_intersecting)
      throw InputError(soup.source + ": the patch filling the " + where +
                       " intersects itself or the surface around the hole: close the hole in a mesh editor");
    record.holes.push_back({hole.triangles, hole.points, hole.perimeter, hole.area, hole.faired, near});
    record.filled_faces += hole.triangles;
    record.filled_vertices += hole.points;
  }
  for (int m = 0; m < record.filled_vertices; ++m) out.vertex_source.push_back(file_vertices + m);

  // Step 4: handles.
  cut_handles(filled.points, filled.triangles, out.vertex_source, record, landmarks, settings, soup.source, diagonal,
              file_vertices);
  for (int k = 0; k < record.filled_faces; ++k) {
    out.face_source.push_back(file_faces + k);
    out.reversed.push_back(false);
  }

  // The inverse maps; a welded file vertex goes where the first vertex at its coordinates went.
  out.prepared_face_of_file.assign(soup.triangles.size(), -1);
  for (std::size_t f = 0; f < out.face_source.size(); ++f)
    if (out.face_source[f] < file_faces) out.prepared_face_of_file[out.face_source[f]] = static_cast<int>(f);
  out.prepared_vertex_of_file.assign(soup.vertices.size(), -1);
  for (std::size_t v = out.vertex_source.size(); v-- > 0;)  // backwards: the first copy wins
    if (out.vertex_source[v] < file_vertices) out.prepared_vertex_of_file[out.vertex_source[v]] = static_cast<int>(v);
  std::map<Point, int> first_at;
  for (int i = 0; i < file_vertices; ++i) {
    const int first = first_at.emplace(points[i], i).first->second;
    out.prepared_vertex_of_file[i] = out.prepared_vertex_of_file[first];
  }

  out.soup.source = soup.source;
  out.soup.polygons_triangulated = soup.polygons_triangulated;
  out.soup.vertices.reserve(filled.points.size());
  for (const Point& p : filled.points) out.soup.vertices.push_back(vec(p));
  out.soup.triangles = filled.triangles;
  XP_ASSERT_EQ(out.soup.triangles.size(), out.face_source.size());
  XP_ASSERT_EQ(out.soup.vertices.size(), out.vertex_source.size());
  return out;
}

}  // namespace xparam
