#pragma once
/// \file
/// Synthetic damage with known truth for the intake tests: a clean bundled mesh, and copies with
/// faces punched out, a floater added, a face duplicated, a handle added; each knows which file
/// elements are which.

#include "core/triangle_soup.h"
#include "io/mesh_reader.h"
#include "support/test_data.h"

#include <Eigen/Core>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

namespace xparam::test {

/// spot_low_resolution.obj (829 vertices, 1654 faces, genus 0) read as a soup.
inline TriangleSoup clean_spot() { return read_triangle_soup(data_path("spot_low_resolution.obj")); }

/// `soup` without the faces whose centroid lies within `radius` of vertex `center`: one hole.
/// The removed faces are listed in `removed` (file indices of `soup`), the rest keep their order.
inline TriangleSoup punch_hole(const TriangleSoup& soup, int center, double radius, std::vector<int>& removed) {
  TriangleSoup out = soup;
  out.triangles.clear();
  removed.clear();
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const auto& t = soup.triangles[f];
    const Eigen::Vector3d centroid = (soup.vertices[t[0]] + soup.vertices[t[1]] + soup.vertices[t[2]]) / 3.0;
    if ((centroid - soup.vertices[center]).norm() < radius)
      removed.push_back(static_cast<int>(f));
    else
      out.triangles.push_back(t);
  }
  return out;
}

/// `soup` with a closed tetrahedron of edge `size` added at `at` (4 vertices and 4 faces after
/// the soup's own).
inline TriangleSoup add_floater(const TriangleSoup& soup, const Eigen::Vector3d& at, double size) {
  TriangleSoup out = soup;
  const int first = static_cast<int>(out.vertices.size());
  for (const Eigen::Vector3d& corner : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                        Eigen::Vector3d(0, 0, 1)})
    out.vertices.push_back(at + size * corner);
  for (const std::array<int, 3>& t : {std::array<int, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}})
    out.triangles.push_back({first + t[0], first + t[1], first + t[2]});
  return out;
}

/// `soup` with face `face` repeated at the end (reversed when `reversed`).
inline TriangleSoup duplicate_face(const TriangleSoup& soup, int face, bool reversed) {
  TriangleSoup out = soup;
  std::array<int, 3> t = soup.triangles[face];
  if (reversed) std::swap(t[1], t[2]);
  out.triangles.push_back(t);
  return out;
}

/// The vertices around `center` in the order its faces run (x -> y for each face (center, x, y)).
/// \pre `center` is an inner vertex of a closed, oriented mesh
inline std::vector<int> link_loop(const TriangleSoup& soup, int center) {
  std::map<int, int> next;
  for (const auto& t : soup.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] == center) next[t[(k + 1) % 3]] = t[(k + 2) % 3];
  std::vector<int> loop{next.begin()->first};
  while (next.at(loop.back()) != loop.front()) loop.push_back(next.at(loop.back()));
  return loop;
}

/// A soup with a handle: a thin tube arching over the surface from vertex a to vertex b.
struct HandleDamage {
  TriangleSoup soup;
  /// The tube's inner rings (all alike: the same polygon swept along a half circle), their
  /// centres, and the perimeter of one: the shortest loop around the handle.
  std::vector<std::vector<int>> rings;
  std::vector<Eigen::Vector3d> ring_centres;
  double ring_perimeter = 0.0;
  double tube_radius = 0.0;
  /// The two vertices of `soup` the tube replaced (indices before the removal).
  std::array<int, 2> replaced{-1, -1};
};

/// `soup` with the faces around `a` and around `b` removed (a and b too: later vertices move
/// down) and the two holes joined by a tube of `ring_count - 1` inner rings of radius `radius` along a half circle
/// over the surface (in the plane of b - a and the surface normal there). The inner rings copy
/// the angles of a's neighbours, so the tube is one band of quads from a's loop to b's.
/// \pre a and b inner vertices of a closed, oriented mesh, with as many neighbours each, far
///   enough apart that no face holds both a neighbour of a and one of b
inline HandleDamage add_handle(const TriangleSoup& soup, int a, int b, double radius, int ring_count) {
  HandleDamage out;
  out.tube_radius = radius;
  out.replaced = {a, b};
  const std::vector<int> at_a = link_loop(soup, a);
  std::vector<int> at_b = link_loop(soup, b);
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  out.soup = soup;
  out.soup.triangles.clear();
  for (const auto& t : soup.triangles) {
    const bool around = t[0] == a || t[1] == a || t[2] == a || t[0] == b || t[1] == b || t[2] == b;
    if (around)
      normal += (soup.vertices[t[1]] - soup.vertices[t[0]]).cross(soup.vertices[t[2]] - soup.vertices[t[0]]);
    else
      out.soup.triangles.push_back(t);
  }
  const Eigen::Vector3d pa = soup.vertices[a];
  const Eigen::Vector3d pb = soup.vertices[b];
  const Eigen::Vector3d u = (pb - pa).normalized();
  const Eigen::Vector3d n = (normal - normal.dot(u) * u).normalized();
  const Eigen::Vector3d w = u.cross(n);
  const double arc = 0.5 * (pb - pa).norm();
  const Eigen::Vector3d middle = 0.5 * (pa + pb);
  std::vector<double> angles;
  for (int v : at_a) angles.push_back(std::atan2((soup.vertices[v] - pa).dot(u), (soup.vertices[v] - pa).dot(w)));

  // b's loop runs the other way round the tube: reversed, starting at the neighbour nearest to
  // where the first angle lands at b (there the sweep's frame has turned to (w, -u)).
  std::reverse(at_b.begin(), at_b.end());
  const Eigen::Vector3d first_at_b = pb + radius * (std::cos(angles[0]) * w - std::sin(angles[0]) * u);
  std::size_t start = 0;
  for (std::size_t i = 1; i < at_b.size(); ++i)
    if ((soup.vertices[at_b[i]] - first_at_b).norm() < (soup.vertices[at_b[start]] - first_at_b).norm()) start = i;
  std::rotate(at_b.begin(), at_b.begin() + static_cast<std::ptrdiff_t>(start), at_b.end());

  std::vector<std::vector<int>> all_rings{at_a};
  for (int k = 1; k < ring_count; ++k) {
    const double theta = M_PI * k / ring_count;
    const Eigen::Vector3d centre = middle - arc * std::cos(theta) * u + arc * std::sin(theta) * n;
    const Eigen::Vector3d e = std::cos(theta) * u - std::sin(theta) * n;
    std::vector<int> ring;
    for (double phi : angles) {
      ring.push_back(static_cast<int>(out.soup.vertices.size()));
      out.soup.vertices.push_back(centre + radius * (std::cos(phi) * w + std::sin(phi) * e));
    }
    out.rings.push_back(ring);
    out.ring_centres.push_back(centre);
    all_rings.push_back(ring);
  }
  all_rings.push_back(at_b);
  const std::size_t m = at_a.size();
  for (std::size_t k = 0; k + 1 < all_rings.size(); ++k) {
    const std::vector<int>& low = all_rings[k];
    const std::vector<int>& high = all_rings[k + 1];
    for (std::size_t i = 0; i < m; ++i) {
      const std::size_t j = (i + 1) % m;
      out.soup.triangles.push_back({low[i], low[j], high[i]});
      out.soup.triangles.push_back({low[j], high[j], high[i]});
    }
  }
  const std::vector<int>& ring = out.rings.front();
  for (std::size_t i = 0; i < m; ++i)
    out.ring_perimeter += (out.soup.vertices[ring[(i + 1) % m]] - out.soup.vertices[ring[i]]).norm();

  // a and b are used by no face now: leave them out, the later vertices moving down.
  std::vector<int> renumbered(out.soup.vertices.size());
  std::vector<Eigen::Vector3d> kept;
  for (std::size_t v = 0; v < out.soup.vertices.size(); ++v) {
    renumbered[v] = static_cast<int>(kept.size());
    if (static_cast<int>(v) != a && static_cast<int>(v) != b) kept.push_back(out.soup.vertices[v]);
  }
  out.soup.vertices = std::move(kept);
  for (auto& t : out.soup.triangles)
    for (int& v : t) v = renumbered[v];
  for (auto& r : out.rings)
    for (int& v : r) v = renumbered[v];
  return out;
}

/// Spot with a thin tube (radius 0.02, 5 inner rings) from the vertex nearest its right flank (no
/// landmark within 0.3) to a vertex 0.25 to 0.35 away with as many neighbours and none in common
/// (Spot's edges are about 0.07 long).
inline HandleDamage spot_with_handle() {
  const TriangleSoup clean = clean_spot();
  const Eigen::Vector3d flank(0.35, -0.1, 0.4);
  int a = 0;
  for (std::size_t i = 1; i < clean.vertices.size(); ++i)
    if ((clean.vertices[i] - flank).norm() < (clean.vertices[a] - flank).norm()) a = static_cast<int>(i);
  const std::vector<int> around_a = link_loop(clean, a);
  for (std::size_t b = 0; b < clean.vertices.size(); ++b) {
    const double d = (clean.vertices[b] - clean.vertices[a]).norm();
    if (d < 0.25 || d > 0.35) continue;
    const std::vector<int> around_b = link_loop(clean, static_cast<int>(b));
    if (around_b.size() != around_a.size() ||
        std::find_first_of(around_a.begin(), around_a.end(), around_b.begin(), around_b.end()) != around_a.end())
      continue;
    return add_handle(clean, a, static_cast<int>(b), 0.02, 6);
  }
  throw std::logic_error("no second vertex for Spot's handle");
}

}  // namespace xparam::test
