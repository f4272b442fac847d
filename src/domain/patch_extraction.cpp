#include "domain/patch_extraction.h"

#include "core/errors.h"
#include "domain/patch_merging.h"
#include "param/convex_polygon.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace xparam {
namespace {

double polyline_length(const Mesh& mesh, const std::vector<VertexHandle>& chain) {
  double length = 0.0;
  for (size_t i = 1; i < chain.size(); ++i) length += (position(mesh, chain[i]) - position(mesh, chain[i - 1])).norm();
  return length;
}

// The LPBD of these sides: by the law of cosines for a triangle, by eq. 2 beyond.
Lpbd lpbd_of(const std::vector<double>& lengths, const std::vector<double>& surface_angles) {
  if (lengths.size() == 3) return triangle_lpbd(lengths[0], lengths[1], lengths[2]);
  return polygon_lpbd(lengths, surface_angles);
}

bool usable(const Lpbd& lpbd) { return lpbd.valid && is_strictly_convex(lpbd.corners); }

// Corners on a circle of circumference `sum(lengths)`, each at the arc-length fraction of the
// sides before it.
std::vector<Eigen::Vector2d> inscribed_polygon(const std::vector<double>& lengths) {
  double perimeter = 0.0;
  for (double l : lengths) perimeter += l;
  const double radius = perimeter / (2.0 * std::numbers::pi);
  std::vector<Eigen::Vector2d> corners;
  double before = 0.0;
  for (double l : lengths) {
    const double angle = 2.0 * std::numbers::pi * before / perimeter;
    corners.emplace_back(radius * std::cos(angle), radius * std::sin(angle));
    before += l;
  }
  return corners;
}

}  // namespace

PatchPolygon patch_polygon(const std::vector<double>& curve_lengths, const std::vector<double>& surface_angles,
                           const std::vector<double>& chord_lengths) {
  XP_ASSERT_MSG(curve_lengths.size() >= 3 && surface_angles.size() == curve_lengths.size() &&
                    chord_lengths.size() == curve_lengths.size(),
                curve_lengths.size() << " curves, " << surface_angles.size() << " angles, " << chord_lengths.size()
                                     << " chords");
  PatchPolygon polygon;
  polygon.lpbd = lpbd_of(curve_lengths, surface_angles);
  if (usable(polygon.lpbd)) {
    polygon.corners = polygon.lpbd.corners;
    return polygon;
  }
  polygon.fallback = true;
  // Coincident anchors give a zero chord, which no LPBD accepts: straight to the circle then.
  const bool chords_positive =
      std::all_of(chord_lengths.begin(), chord_lengths.end(), [](double l) { return std::isfinite(l) && l > 0.0; });
  if (chords_positive) {
    const Lpbd chords = lpbd_of(chord_lengths, surface_angles);
    if (usable(chords)) {
      polygon.corners = chords.corners;
      return polygon;
    }
  }
  polygon.corners = inscribed_polygon(curve_lengths);
  XP_ASSERT_MSG(is_strictly_convex(polygon.corners), "the inscribed fallback polygon is not strictly convex");
  return polygon;
}

double chain_length(const Layout& layout, int side, int e) {
  return polyline_length(layout.sides[side].mesh, layout.sides[side].chains[e]);
}

namespace {

// Patch p from its faces (mesh face indices in increasing order); `local` is #V scratch, all
// -1, and is left all -1.
ExtractedPatch build_patch(const Layout& layout, int side, int p, std::vector<int> faces, std::vector<int>& local) {
  const Mesh& mesh = layout.sides[side].mesh;
  const std::vector<int>& walk = layout.patches[p];
  ExtractedPatch result;
  result.triangle_faces = std::move(faces);
  DiskPatch& patch = result.patch;
  patch.name = "side " + std::to_string(side) + " patch " + std::to_string(p);
  std::vector<int>& to_mesh = result.local_to_mesh;
  auto local_id = [&](VertexHandle v) {
    if (local[v.idx()] < 0) {
      local[v.idx()] = static_cast<int>(to_mesh.size());
      to_mesh.push_back(v.idx());
      patch.positions.push_back(position(mesh, v));
    }
    return local[v.idx()];
  };
  // Local ids in order of first appearance over the faces, so they depend on nothing but the mesh.
  for (int f : result.triangle_faces) {
    std::array<int, 3> corners{};
    int k = 0;
    for (VertexHandle v : mesh.fv_range(mesh.face_handle(f))) corners[k++] = local_id(v);
    patch.triangles.push_back(corners);
  }
  // Boundary: the chains of the patch's walk, each without its last vertex (the next one's first).
  std::vector<double> curves, chords;
  for (int h : walk) {
    patch.corner_positions.push_back(static_cast<int>(patch.boundary_loop.size()));
    const std::vector<VertexHandle> chain = halfedge_chain(layout, side, h);
    for (size_t i = 0; i + 1 < chain.size(); ++i) patch.boundary_loop.push_back(local_id(chain[i]));
    curves.push_back(polyline_length(mesh, chain));
    chords.push_back((position(mesh, chain.back()) - position(mesh, chain.front())).norm());
  }
  // A triangle's LPBD needs no surface angles (and they read the chains around its anchors).
  const std::vector<double> angles =
      walk.size() == 3 ? std::vector<double>(3, 0.0) : corner_surface_angles(layout, side, p);
  PatchPolygon polygon = patch_polygon(curves, angles, chords);
  result.fallback = polygon.fallback;
  result.lpbd = std::move(polygon.lpbd);
  patch.polygon = std::move(polygon.corners);
  for (int v : to_mesh) local[v] = -1;
  return result;
}

}  // namespace

ExtractedPatch extract_patch(const Layout& layout, int side, int p) {
  XP_ASSERT_MSG(p >= 0 && p < static_cast<int>(layout.patches.size()), "patch " << p << " does not exist");
  const Mesh& mesh = layout.sides[side].mesh;
  std::vector<int> faces;
  for (FaceHandle f : mesh.faces()) {
    if (patch_of(mesh, f) == p) faces.push_back(f.idx());
  }
  std::vector<int> local(mesh.n_vertices(), -1);
  return build_patch(layout, side, p, std::move(faces), local);
}

SidePatches extract_patches(const Layout& layout, int side) {
  const Mesh& mesh = layout.sides[side].mesh;
  const int n_patches = static_cast<int>(layout.patches.size());
  SidePatches result;
  result.patches.resize(n_patches);
  result.lpbds.resize(n_patches);
  result.local_to_mesh.resize(n_patches);
  result.triangle_faces.resize(n_patches);
  result.face_corners.assign(mesh.n_faces(), {-1, -1, -1});

  // One scan over the faces for every patch's face list.
  std::vector<std::vector<int>> faces(n_patches);
  for (FaceHandle f : mesh.faces()) {
    const int p = patch_of(mesh, f);
    XP_ASSERT_MSG(p >= 0 && p < n_patches, "side " << side << " face " << f.idx() << " has patch " << p);
    faces[p].push_back(f.idx());
  }
  std::vector<int> local(mesh.n_vertices(), -1);
  for (int p = 0; p < n_patches; ++p) {
    ExtractedPatch extracted = build_patch(layout, side, p, std::move(faces[p]), local);
    for (std::size_t t = 0; t < extracted.triangle_faces.size(); ++t) {
      result.face_corners[extracted.triangle_faces[t]] = extracted.patch.triangles[t];
    }
    if (extracted.fallback) ++result.fallback_polygons;
    result.patches[p] = std::move(extracted.patch);
    result.lpbds[p] = std::move(extracted.lpbd);
    result.local_to_mesh[p] = std::move(extracted.local_to_mesh);
    result.triangle_faces[p] = std::move(extracted.triangle_faces);
  }
  return result;
}

}  // namespace xparam
