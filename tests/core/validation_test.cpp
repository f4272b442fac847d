#include "core/validation.h"

#include "core/errors.h"
#include "support/small_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace xparam {
namespace {

// A torus as an n x m grid of quads, each split into two consistently oriented triangles.
TriangleSoup torus(int n, int m) {
  TriangleSoup soup;
  soup.source = "torus.off";
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n;
      const double v = 2 * M_PI * j / m;
      soup.vertices.push_back(
          {(2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v)});
    }
  }
  const auto id = [&](int i, int j) { return (i % n) * m + (j % m); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return soup;
}

// A Moebius band: a strip of k quads whose ends are glued with a half twist.
TriangleSoup moebius(int k) {
  TriangleSoup soup;
  soup.source = "moebius.obj";
  for (int i = 0; i < k; ++i) {
    const double u = 2 * M_PI * i / k;
    const double half = u / 2;
    for (double s : {-0.3, 0.3})
      soup.vertices.push_back({(1 + s * std::cos(half)) * std::cos(u), (1 + s * std::cos(half)) * std::sin(u),
                               s * std::sin(half)});
  }
  for (int i = 0; i < k; ++i) {
    const int a = 2 * i;
    const int b = 2 * i + 1;
    // The last quad meets the first one upside down: that is the twist.
    const int c = i + 1 < k ? 2 * (i + 1) : 1;
    const int d = i + 1 < k ? 2 * (i + 1) + 1 : 0;
    soup.triangles.push_back({a, c, d});
    soup.triangles.push_back({a, d, b});
  }
  return soup;
}

bool has_problem(const MeshReport& report, ProblemKind kind, const std::string& message) {
  for (const Problem& p : report.problems)
    if (p.kind == kind && p.message == message) return true;
  return false;
}

int count_kind(const MeshReport& report, ProblemKind kind) {
  int n = 0;
  for (const Problem& p : report.problems) n += p.kind == kind;
  return n;
}

TEST(Validation, TetrahedronIsUsableGenusZero) {
  const MeshReport r = validate_soup(test::tetrahedron_soup());
  EXPECT_EQ(r.source, "tet.obj");
  EXPECT_EQ(r.vertices, 4);
  EXPECT_EQ(r.faces, 4);
  EXPECT_EQ(r.edges, 6);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.boundary_loops, 0);
  EXPECT_EQ(r.euler_characteristic, 2);
  ASSERT_TRUE(r.genus.has_value());
  EXPECT_EQ(*r.genus, 0);
  EXPECT_TRUE(r.orientable);
  EXPECT_TRUE(r.usable);
  EXPECT_TRUE(r.problems.empty());
  // Three edges of length 1 and three of length sqrt(2).
  EXPECT_NEAR(r.mean_edge_length, (3 + 3 * std::sqrt(2.0)) / 6, 1e-15);
  EXPECT_EQ(r.bbox_min, Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(r.bbox_max, Eigen::Vector3d(1, 1, 1));
  EXPECT_DOUBLE_EQ(r.min_face_area, 0.5);
}

TEST(Validation, TorusHasGenusOne) {
  for (const auto& [n, m] : {std::pair{3, 3}, std::pair{8, 5}, std::pair{20, 12}}) {
    const MeshReport r = validate_soup(torus(n, m));
    EXPECT_EQ(r.vertices, n * m);
    EXPECT_EQ(r.faces, 2 * n * m);
    EXPECT_EQ(r.edges, 3 * n * m);
    EXPECT_EQ(r.euler_characteristic, 0);
    ASSERT_TRUE(r.genus.has_value());
    EXPECT_EQ(*r.genus, 1);
    // Genus is reported, not judged: a torus is a usable mesh for validation.
    EXPECT_TRUE(r.usable) << n << "x" << m;
  }
}

TEST(Validation, OpenMeshHasOneBoundaryLoop) {
  TriangleSoup soup = test::tetrahedron_soup();
  soup.triangles.erase(soup.triangles.begin());  // remove face (0, 2, 1)
  const MeshReport r = validate_soup(soup);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(r.boundary_edges, 3);
  EXPECT_EQ(r.euler_characteristic, 1);
  ASSERT_TRUE(r.genus.has_value());
  EXPECT_EQ(*r.genus, 0);  // a disk
  EXPECT_FALSE(r.usable);
  EXPECT_TRUE(has_problem(r, ProblemKind::Boundary,
                          "tet.obj: not closed: boundary loop of 3 edges through edge (0, 1)"));
}

TEST(Validation, TwoHolesAreTwoLoopsAndAPinchedBoundaryIsOne) {
  // A 3 x 3 grid of vertices (a square of 8 triangles) has one boundary loop of 8 edges.
  TriangleSoup grid;
  grid.source = "grid.obj";
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) grid.vertices.push_back({double(x), double(y), 0});
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 2; ++x) {
      const int a = 3 * y + x;
      grid.triangles.push_back({a, a + 1, a + 4});
      grid.triangles.push_back({a, a + 4, a + 3});
    }
  }
  MeshReport r = validate_soup(grid);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(r.boundary_edges, 8);
  EXPECT_EQ(*r.genus, 0);

  // The torus with two faces removed far apart has two loops and genus 1.
  TriangleSoup holed = torus(8, 6);
  holed.triangles.erase(holed.triangles.begin() + 40);
  holed.triangles.erase(holed.triangles.begin());
  r = validate_soup(holed);
  EXPECT_EQ(r.boundary_loops, 2);
  EXPECT_EQ(*r.genus, 1);

  // Removing the two triangles of a quad and of the diagonal neighbour quad leaves two holes
  // that touch at one vertex: boundary edges sharing a vertex form one loop (and the vertex
  // is a pinch).
  TriangleSoup pinched = torus(8, 6);
  // Quad (i, j) holds triangles 2 * (i * 6 + j) and + 1; quads (2, 2) and (3, 3) share vertex (3, 3).
  for (int q : {3 * 6 + 3, 2 * 6 + 2})
    pinched.triangles.erase(pinched.triangles.begin() + 2 * q, pinched.triangles.begin() + 2 * q + 2);
  ValidationSettings as_is;
  as_is.repair = false;
  r = validate_soup(pinched, as_is);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(r.boundary_edges, 8);
  EXPECT_EQ(r.non_manifold_vertices, std::vector<int>{3 * 6 + 3});
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_TRUE(r.split_vertices.empty());

  // Repaired, the pinch becomes two vertices, each joining one side of each hole: one loop of
  // 8 edges, chi = 49 - 142 + 92 = -1, genus (2 + 1 - 1) / 2 = 1. The file's counts stay.
  r = validate_soup(pinched);
  ASSERT_EQ(r.split_vertices.size(), 1u);
  EXPECT_EQ(r.split_vertices[0].vertex, 3 * 6 + 3);
  EXPECT_EQ(r.split_vertices[0].copies, std::vector<int>{48});
  EXPECT_EQ(r.euler_characteristic, -2);
  EXPECT_EQ(r.boundary_loops, 1);
  ASSERT_TRUE(r.genus.has_value());
  EXPECT_EQ(*r.genus, 1);
  EXPECT_FALSE(r.usable);  // still open
}

TEST(Validation, NonManifoldEdgeIsNamedWithFileIndices) {
  TriangleSoup soup;
  soup.source = "scan_017.ply";
  soup.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  soup.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const MeshReport r = validate_soup(soup);
  ASSERT_EQ(r.non_manifold_edges.size(), 1u);
  EXPECT_EQ(r.non_manifold_edges[0], (std::array<int, 2>{0, 1}));
  EXPECT_TRUE(has_problem(r, ProblemKind::NonManifoldEdge, "scan_017.ply: edge (0, 1) has 3 faces"));
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_FALSE(r.usable);
}

TEST(Validation, TwoTetrahedraTouchingAtAVertexArePinched) {
  TriangleSoup soup = test::tetrahedron_soup();
  // Second tetrahedron shares vertex 0 only, mirrored through the origin.
  for (int v = 1; v < 4; ++v) soup.vertices.push_back(-soup.vertices[v]);
  const std::array<int, 4> map{0, 4, 5, 6};
  for (int f = 0; f < 4; ++f) {
    const auto& t = soup.triangles[f];
    soup.triangles.push_back({map[t[0]], map[t[2]], map[t[1]]});  // the mirror reverses orientation
  }
  const MeshReport r = validate_soup(soup);
  EXPECT_EQ(r.components, 1);  // connected through the shared vertex
  EXPECT_EQ(r.non_manifold_vertices, std::vector<int>{0});
  EXPECT_TRUE(r.non_manifold_edges.empty());
  EXPECT_EQ(r.euler_characteristic, 7 - 12 + 8);
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_TRUE(has_problem(r, ProblemKind::NonManifoldVertex,
                          "tet.obj: vertex 0 is non-manifold: its faces form 2 separate fans"));
  // Splitting the pinch (the first tetrahedron keeps vertex 0, the second gets copy 7) leaves
  // two components: the repair cannot make it usable, and says why.
  ASSERT_EQ(r.split_vertices.size(), 1u);
  EXPECT_EQ(r.split_vertices[0].copies, std::vector<int>{7});
  EXPECT_EQ(r.repaired().size(), 1u);
  EXPECT_TRUE(has_problem(r, ProblemKind::MultipleComponents,
                          "tet.obj: after repair: component 2 of 2 has 4 faces, starting at face 4"));
  EXPECT_FALSE(r.usable);
}

TEST(Validation, FlippedFaceIsInconsistentButOrientable) {
  TriangleSoup soup = test::tetrahedron_soup();
  std::swap(soup.triangles[2][1], soup.triangles[2][2]);  // (1, 3, 2)
  const MeshReport r = validate_soup(soup);
  EXPECT_TRUE(r.orientable);
  const std::vector<std::array<int, 2>> expected{{1, 2}, {1, 3}, {2, 3}};
  EXPECT_EQ(r.inconsistent_edges, expected);
  EXPECT_TRUE(has_problem(r, ProblemKind::InconsistentOrientation,
                          "tet.obj: edge (1, 2) is traversed in the same direction by faces 0 and 2 "
                          "(inconsistent orientation)"));
  EXPECT_EQ(*r.genus, 0);
  // Repaired by default: face 2 is re-oriented and nothing blocks use.
  EXPECT_EQ(r.reoriented_faces, std::vector<int>{2});
  EXPECT_TRUE(r.usable);
  EXPECT_TRUE(r.errors().empty());
  EXPECT_EQ(r.repaired().size(), 3u);
  EXPECT_EQ(describe_repairs(r), "1 face re-oriented to agree with their neighbours");

  ValidationSettings as_is;
  as_is.repair = false;
  const MeshReport refused = validate_soup(soup, as_is);
  EXPECT_TRUE(refused.reoriented_faces.empty());
  EXPECT_TRUE(refused.repaired().empty());
  EXPECT_EQ(refused.errors().size(), 3u);
  EXPECT_FALSE(refused.usable);
}

// A torus with some faces reversed: the repair reverses exactly those back, and the result
// validates as consistent without repairs.
TEST(Validation, RepairReorientsExactlyTheFlippedFaces) {
  const TriangleSoup good = torus(8, 6);  // 96 faces, consistent
  TriangleSoup soup = good;
  const std::vector<int> flipped{0, 3, 17, 18, 40, 41, 42, 95};  // some neighbours of each other
  for (int f : flipped) std::swap(soup.triangles[f][0], soup.triangles[f][2]);  // another way to reverse
  const MeshReport r = validate_soup(soup);
  EXPECT_EQ(r.reoriented_faces, flipped);
  EXPECT_TRUE(r.usable);
  ASSERT_EQ(*r.genus, 1);

  const SoupRepair repair = repair_soup(soup);
  EXPECT_EQ(repair.reoriented_faces, flipped);
  for (int f = 0; f < 96; ++f) {
    const bool expected = std::find(flipped.begin(), flipped.end(), f) != flipped.end();
    EXPECT_EQ(repair.reversed[f], expected) << f;
    // (a, b, c) -> (a, c, b); the untouched faces are as in the file.
    const auto& t = soup.triangles[f];
    const std::array<int, 3> want = expected ? std::array<int, 3>{t[0], t[2], t[1]} : t;
    EXPECT_EQ(repair.soup.triangles[f], want) << f;
  }
  ValidationSettings as_is;
  as_is.repair = false;
  EXPECT_TRUE(validate_soup(repair.soup, as_is).usable);

  // The majority wins: reversing all but those faces re-orients the same faces.
  TriangleSoup mostly_reversed = good;
  for (int f = 0; f < 96; ++f)
    if (std::find(flipped.begin(), flipped.end(), f) == flipped.end())
      std::swap(mostly_reversed.triangles[f][1], mostly_reversed.triangles[f][2]);
  EXPECT_EQ(repair_soup(mostly_reversed).reoriented_faces, flipped);
}

TEST(Validation, RepairTieKeepsTheLowestFacesWinding) {
  TriangleSoup soup = test::tetrahedron_soup();
  for (int f : {1, 3}) std::swap(soup.triangles[f][1], soup.triangles[f][2]);
  EXPECT_EQ(repair_soup(soup).reoriented_faces, (std::vector<int>{1, 3}));
  soup = test::tetrahedron_soup();
  for (int f : {0, 3}) std::swap(soup.triangles[f][1], soup.triangles[f][2]);
  EXPECT_EQ(repair_soup(soup).reoriented_faces, (std::vector<int>{1, 2}));
}

// Two square pyramids meeting tip to tip at vertex 12 (the centre), their bases joined by a
// band: a sphere whose north and south poles are glued into one vertex (a horn torus with 4
// sectors). Outward faces; V 13, E 36, F 24, chi 1.
TriangleSoup double_pyramid() {
  TriangleSoup soup;
  soup.source = "pinched.obj";
  for (int i = 0; i < 4; ++i) {
    const double c = std::cos(M_PI / 2 * i);
    const double s = std::sin(M_PI / 2 * i);
    soup.vertices.push_back({2 * c, 2 * s, 0});  // 3 i: outer equator
    soup.vertices.push_back({c, s, 1});          // 3 i + 1: top ring
    soup.vertices.push_back({c, s, -1});         // 3 i + 2: bottom ring
  }
  soup.vertices.push_back({0, 0, 0});  // 12: the tips
  const auto outer = [](int i) { return 3 * (i % 4); };
  const auto top = [](int i) { return 3 * (i % 4) + 1; };
  const auto bottom = [](int i) { return 3 * (i % 4) + 2; };
  for (int i = 0; i < 4; ++i) {
    soup.triangles.push_back({top(i), top(i + 1), 12});  // faces 0..3: the upper pyramid
    soup.triangles.push_back({outer(i), outer(i + 1), top(i + 1)});
    soup.triangles.push_back({outer(i), top(i + 1), top(i)});
    soup.triangles.push_back({bottom(i), bottom(i + 1), outer(i + 1)});
    soup.triangles.push_back({bottom(i), outer(i + 1), outer(i)});
    soup.triangles.push_back({12, bottom(i + 1), bottom(i)});  // the lower pyramid
  }
  return soup;
}

TEST(Validation, PinchedDoublePyramidSplitsIntoASphere) {
  const TriangleSoup soup = double_pyramid();
  const MeshReport r = validate_soup(soup);
  EXPECT_EQ(r.vertices, 13);
  EXPECT_EQ(r.edges, 36);
  EXPECT_EQ(r.euler_characteristic, 1);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.non_manifold_vertices, std::vector<int>{12});
  ASSERT_EQ(r.split_vertices.size(), 1u);
  EXPECT_EQ(r.split_vertices[0].vertex, 12);
  EXPECT_EQ(r.split_vertices[0].copies, std::vector<int>{13});
  ASSERT_TRUE(r.genus.has_value());
  EXPECT_EQ(*r.genus, 0);
  EXPECT_TRUE(r.reoriented_faces.empty());
  EXPECT_TRUE(r.usable);
  EXPECT_EQ(describe_repairs(r), "vertex 12 split into 2 (copy 13)");

  // The upper pyramid holds face 0 and keeps vertex 12; the lower one takes copy 13.
  const SoupRepair repair = repair_soup(soup);
  ASSERT_EQ(repair.soup.vertices.size(), 14u);
  EXPECT_EQ(repair.soup.vertices[13], soup.vertices[12]);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(repair.soup.triangles[6 * i][2], 12);
    EXPECT_EQ(repair.soup.triangles[6 * i + 5][0], 13);
  }
  for (int f = 0; f < 24; ++f) {
    if (f % 6 == 5) continue;
    EXPECT_EQ(repair.soup.triangles[f], soup.triangles[f]) << f;
  }
  ValidationSettings as_is;
  as_is.repair = false;
  const MeshReport sphere = validate_soup(repair.soup, as_is);
  EXPECT_TRUE(sphere.usable);
  EXPECT_EQ(sphere.components, 1);
  EXPECT_EQ(sphere.euler_characteristic, 2);
  EXPECT_EQ(*sphere.genus, 0);
  EXPECT_EQ(sphere.duplicate_vertices, (std::vector<std::array<int, 2>>{{12, 13}}));

  // Without the repair it is refused.
  EXPECT_FALSE(validate_soup(soup, as_is).usable);
}

TEST(Validation, NonManifoldEdgesAreNotRepaired) {
  // A fin on a tetrahedron with one face flipped: the edge stays refused, nothing is repaired.
  TriangleSoup soup = test::tetrahedron_soup();
  std::swap(soup.triangles[2][1], soup.triangles[2][2]);
  soup.vertices.push_back({1, 1, 1});
  soup.triangles.push_back({0, 1, 4});
  const MeshReport r = validate_soup(soup);
  EXPECT_FALSE(r.non_manifold_edges.empty());
  EXPECT_TRUE(r.reoriented_faces.empty());
  EXPECT_TRUE(r.repaired().empty());
  EXPECT_FALSE(r.usable);
}

TEST(Validation, MoebiusBandIsNotOrientable) {
  const MeshReport r = validate_soup(moebius(9));
  EXPECT_FALSE(r.orientable);
  EXPECT_EQ(r.boundary_loops, 1);  // the band has a single boundary curve
  EXPECT_EQ(r.boundary_edges, 18);
  EXPECT_EQ(r.euler_characteristic, 0);
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_EQ(count_kind(r, ProblemKind::NonOrientable), 1);
  EXPECT_EQ(count_kind(r, ProblemKind::InconsistentOrientation), 0);
  EXPECT_FALSE(r.usable);
}

TEST(Validation, DegenerateAndNearZeroAreaFaces) {
  TriangleSoup soup = test::tetrahedron_soup();
  soup.vertices.push_back({2, 0, 0});        // 4: collinear with 0 and 1
  soup.vertices.push_back({0.5, 1e-13, 0});  // 5: almost on edge (0, 1)
  soup.triangles.push_back({0, 1, 4});       // 4: zero area
  soup.triangles.push_back({0, 1, 5});       // 5: area 5e-14 < 1e-12 * diagonal^2 = 6e-12
  soup.triangles.push_back({2, 2, 3});       // 6: repeated index
  const MeshReport r = validate_soup(soup);
  EXPECT_EQ(r.degenerate_faces, (std::vector<int>{4, 6}));
  EXPECT_EQ(r.near_zero_area_faces, std::vector<int>{5});
  EXPECT_TRUE(has_problem(r, ProblemKind::DegenerateFace, "tet.obj: face 4 (0, 1, 4) has zero area"));
  EXPECT_TRUE(has_problem(r, ProblemKind::DegenerateFace, "tet.obj: face 6 (2, 2, 3) repeats a vertex"));
  EXPECT_FALSE(r.usable);

  // The threshold is relative to the bounding box: a smaller factor accepts the sliver.
  ValidationSettings lenient;
  lenient.near_zero_area_relative = 1e-15;
  EXPECT_TRUE(validate_soup(soup, lenient).near_zero_area_faces.empty());
}

TEST(Validation, NonFiniteCoordinatesAreReportedAndLeftOutOfTheBoundingBox) {
  TriangleSoup soup = test::tetrahedron_soup();
  soup.vertices[3].z() = std::numeric_limits<double>::quiet_NaN();
  const MeshReport r = validate_soup(soup);
  EXPECT_EQ(r.non_finite_vertices, std::vector<int>{3});
  EXPECT_EQ(r.bbox_max, Eigen::Vector3d(1, 1, 0));
  EXPECT_TRUE(std::isfinite(r.mean_edge_length));
  EXPECT_EQ(r.problems.front().kind, ProblemKind::NonFiniteCoordinate);
  EXPECT_FALSE(r.usable);
}

TEST(Validation, UnreferencedVerticesBlockUseButNotTheEulerCount) {
  TriangleSoup soup = test::tetrahedron_soup();
  for (int i = 0; i < 5; ++i) soup.vertices.push_back({5.0 + i, 0, 0});
  ValidationSettings settings;
  settings.max_listed_per_kind = 2;
  const MeshReport r = validate_soup(soup, settings);
  EXPECT_EQ(r.unreferenced_vertices, (std::vector<int>{4, 5, 6, 7, 8}));
  EXPECT_EQ(r.euler_characteristic, 2);
  EXPECT_EQ(*r.genus, 0);
  EXPECT_FALSE(r.usable);
  // Capped: two named, the rest counted.
  EXPECT_EQ(count_kind(r, ProblemKind::UnreferencedVertex), 3);
  EXPECT_TRUE(has_problem(r, ProblemKind::UnreferencedVertex, "tet.obj: vertex 5 is used by no face"));
  EXPECT_TRUE(has_problem(r, ProblemKind::UnreferencedVertex, "tet.obj: and 3 more (unreferenced_vertex)"));
}

TEST(Validation, TwoComponents) {
  TriangleSoup soup = test::tetrahedron_soup();
  for (int v = 0; v < 4; ++v) soup.vertices.push_back(soup.vertices[v] + Eigen::Vector3d(3, 0, 0));
  for (int f = 0; f < 4; ++f) {
    const auto t = soup.triangles[f];
    soup.triangles.push_back({t[0] + 4, t[1] + 4, t[2] + 4});
  }
  const MeshReport r = validate_soup(soup);
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(r.euler_characteristic, 4);
  EXPECT_FALSE(r.genus.has_value());
  EXPECT_TRUE(has_problem(r, ProblemKind::MultipleComponents,
                          "tet.obj: component 2 of 2 has 4 faces, starting at face 4"));
  EXPECT_FALSE(r.usable);
}

TEST(Validation, DuplicatePositionsAndPolygonsAreWarningsOnly) {
  // An octahedron flattened so that its two poles meet at the origin: still a closed
  // 2-manifold sphere with faces of nonzero area, but vertices 4 and 5 coincide.
  TriangleSoup soup;
  soup.source = "flat.ply";
  soup.vertices = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, 0}, {0, 0, 0}};
  for (int i = 0; i < 4; ++i) {
    soup.triangles.push_back({i, (i + 1) % 4, 4});
    soup.triangles.push_back({(i + 1) % 4, i, 5});
  }
  soup.polygons_triangulated = 2;
  const MeshReport r = validate_soup(soup);
  EXPECT_EQ(r.duplicate_vertices, (std::vector<std::array<int, 2>>{{4, 5}}));
  EXPECT_TRUE(r.usable);
  EXPECT_TRUE(r.errors().empty());
  ASSERT_EQ(r.warnings().size(), 2u);
  EXPECT_EQ(r.warnings()[0]->message, "flat.ply: vertices 4 and 5 have the same position (0, 0, 0)");
  EXPECT_EQ(r.warnings()[1]->kind, ProblemKind::PolygonsTriangulated);
}

TEST(Validation, EmptySoupIsNotUsable) {
  TriangleSoup soup;
  soup.source = "empty.off";
  const MeshReport r = validate_soup(soup);
  EXPECT_FALSE(r.usable);
  EXPECT_TRUE(has_problem(r, ProblemKind::Empty, "empty.off: the file has no vertices"));
}

TEST(Validation, OutOfRangeIndexIsAnInternalError) {
  TriangleSoup soup = test::tetrahedron_soup();
  soup.triangles[1][2] = 4;
  EXPECT_THROW(validate_soup(soup), InternalError);
}

}  // namespace
}  // namespace xparam
