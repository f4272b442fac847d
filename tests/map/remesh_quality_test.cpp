#include "map/remesh_quality.h"

#include "core/errors.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <OpenMesh/Core/IO/MeshIO.hh>

#include <algorithm>
#include <map>

namespace xparam {
namespace {

// Unit octahedron, outward oriented.
Mesh octahedron() {
  Mesh mesh;
  const VertexHandle px = mesh.add_vertex({1, 0, 0}), nx = mesh.add_vertex({-1, 0, 0});
  const VertexHandle py = mesh.add_vertex({0, 1, 0}), ny = mesh.add_vertex({0, -1, 0});
  const VertexHandle pz = mesh.add_vertex({0, 0, 1}), nz = mesh.add_vertex({0, 0, -1});
  mesh.add_face(px, py, pz);
  mesh.add_face(py, nx, pz);
  mesh.add_face(nx, ny, pz);
  mesh.add_face(ny, px, pz);
  mesh.add_face(py, px, nz);
  mesh.add_face(nx, py, nz);
  mesh.add_face(ny, nx, nz);
  mesh.add_face(px, ny, nz);
  return mesh;
}

// Vertex v of `mesh` as a surface point: an incident face with barycentric 1 at v's corner.
SurfacePoint at_vertex(const Mesh& mesh, int v) {
  const VertexHandle vh = mesh.vertex_handle(v);
  const FaceHandle f = *mesh.vf_range(vh).begin();
  SurfacePoint point;
  point.face = f.idx();
  int corner = 0;
  for (VertexHandle w : mesh.fv_range(f)) {
    if (w == vh) point.bary[corner] = 1.0;
    ++corner;
  }
  return point;
}

// The mesh itself as a remesh of itself: its faces, positions and vertex locations.
struct Remesh {
  std::vector<std::array<int, 3>> faces;
  std::vector<Eigen::Vector3d> positions;
  std::vector<SurfacePoint> locations;
};

Remesh identity_remesh(const Mesh& mesh) {
  Remesh remesh;
  for (FaceHandle f : mesh.faces()) {
    std::array<int, 3> t{};
    int c = 0;
    for (VertexHandle v : mesh.fv_range(f)) t[c++] = v.idx();
    remesh.faces.push_back(t);
  }
  for (VertexHandle v : mesh.vertices()) {
    remesh.positions.push_back(position(mesh, v));
    remesh.locations.push_back(at_vertex(mesh, v.idx()));
  }
  return remesh;
}

TEST(RemeshQuality, OctahedronOnItselfHasNoFlipAndFullArea) {
  const Mesh target = octahedron();
  const Remesh remesh = identity_remesh(target);
  const RemeshQualityResult r =
      measure_remesh_quality(remesh.faces, remesh.positions, remesh.locations, target);
  EXPECT_TRUE(r.flipped_faces.empty());
  EXPECT_EQ(r.strictly_folded_faces, 0);
  EXPECT_EQ(r.degenerate_faces, 0);
  // Eight equilateral faces of side sqrt 2: area 8 * sqrt(3)/4 * 2 = 4 sqrt 3.
  EXPECT_NEAR(r.target_area, 4.0 * std::sqrt(3.0), 1e-14);
  EXPECT_NEAR(r.area_ratio, 1.0, 1e-15);
}

TEST(RemeshQuality, ReflectedOctahedronIsFlippedEverywhere) {
  // Mirror x -> -x: every remesh vertex lands on the mirrored target vertex (+x <-> -x), the
  // surface is covered once, but every face now faces inward.
  const Mesh target = octahedron();
  Remesh remesh = identity_remesh(target);
  const int mirror[6] = {1, 0, 2, 3, 4, 5};
  for (int v = 0; v < 6; ++v) {
    remesh.positions[v].x() = -remesh.positions[v].x();
    remesh.locations[v] = at_vertex(target, mirror[v]);
    EXPECT_NEAR((position(target, remesh.locations[v]) - remesh.positions[v]).norm(), 0.0, 1e-15);
  }
  const RemeshQualityResult r =
      measure_remesh_quality(remesh.faces, remesh.positions, remesh.locations, target);
  EXPECT_EQ(r.flipped_faces, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(r.strictly_folded_faces, 8);  // each on its own target face, which it opposes
  EXPECT_NEAR(r.area_ratio, 1.0, 1e-15);
}

TEST(RemeshQuality, EdgeLocationsGiveTheSameAnswerWhicheverFaceTheyName) {
  // 1-to-4 split of every octahedron face: new vertices at edge midpoints, located once on the
  // first and once on the second face beside the edge. Neither choice may create a flip.
  const Mesh target = octahedron();
  for (int pick = 0; pick < 2; ++pick) {
    Remesh remesh = identity_remesh(target);
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      if (auto it = midpoint.find(key); it != midpoint.end()) return it->second;
      const HalfedgeHandle h = target.find_halfedge(target.vertex_handle(a), target.vertex_handle(b));
      const FaceHandle f = target.face_handle(pick == 0 ? h : target.opposite_halfedge_handle(h));
      SurfacePoint point;
      point.face = f.idx();
      int corner = 0;
      for (VertexHandle w : target.fv_range(f))
        point.bary[corner++] = (w.idx() == a || w.idx() == b) ? 0.5 : 0.0;
      remesh.positions.push_back(
          0.5 * (position(target, target.vertex_handle(a)) + position(target, target.vertex_handle(b))));
      remesh.locations.push_back(point);
      return midpoint[key] = static_cast<int>(remesh.positions.size()) - 1;
    };
    std::vector<std::array<int, 3>> split;
    for (const auto& t : remesh.faces) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      split.push_back({t[0], ab, ca});
      split.push_back({ab, t[1], bc});
      split.push_back({ca, bc, t[2]});
      split.push_back({ab, bc, ca});
    }
    for (std::size_t v = 0; v < remesh.positions.size(); ++v) {
      EXPECT_NEAR((position(target, remesh.locations[v]) - remesh.positions[v]).norm(), 0.0, 1e-15);
    }
    const RemeshQualityResult r = measure_remesh_quality(split, remesh.positions, remesh.locations, target);
    EXPECT_TRUE(r.flipped_faces.empty()) << "pick " << pick;
    EXPECT_NEAR(r.area_ratio, 1.0, 1e-14);
    for (auto& t : split) std::swap(t[1], t[2]);
    EXPECT_EQ(measure_remesh_quality(split, remesh.positions, remesh.locations, target).flipped_faces.size(),
              32u);
  }
}

TEST(RemeshQuality, ExactlyTheReversedFacesOfARealMeshAreFlipped) {
  Mesh target;
  ASSERT_TRUE(OpenMesh::IO::read_mesh(target, test::data_path("spot_low_resolution.obj").string()));
  Remesh remesh = identity_remesh(target);
  std::vector<int> reversed;
  for (int f = 3; f < static_cast<int>(remesh.faces.size()); f += 97) {
    std::swap(remesh.faces[f][1], remesh.faces[f][2]);
    reversed.push_back(f);
  }
  const RemeshQualityResult r =
      measure_remesh_quality(remesh.faces, remesh.positions, remesh.locations, target);
  EXPECT_EQ(r.flipped_faces, reversed);
  EXPECT_NEAR(r.area_ratio, 1.0, 1e-12);

  // Half of the faces cover about half of the surface; a collapsed face counts as degenerate.
  remesh.faces.resize(remesh.faces.size() / 2);
  remesh.positions[remesh.faces[0][1]] = remesh.positions[remesh.faces[0][0]];
  const RemeshQualityResult half =
      measure_remesh_quality(remesh.faces, remesh.positions, remesh.locations, target);
  EXPECT_GE(half.degenerate_faces, 1);
  EXPECT_GT(half.area_ratio, 0.2);
  EXPECT_LT(half.area_ratio, 0.8);
}

TEST(RemeshQuality, RejectsBadInput) {
  const Mesh target = octahedron();
  Remesh remesh = identity_remesh(target);
  remesh.locations.pop_back();
  EXPECT_THROW(measure_remesh_quality(remesh.faces, remesh.positions, remesh.locations, target), ParamError);
  remesh = identity_remesh(target);
  remesh.locations[2].face = 8;
  EXPECT_THROW(measure_remesh_quality(remesh.faces, remesh.positions, remesh.locations, target), ParamError);
  remesh = identity_remesh(target);
  remesh.faces[0][0] = 6;
  EXPECT_THROW(measure_remesh_quality(remesh.faces, remesh.positions, remesh.locations, target), ParamError);
}

// The octahedron's vertex normals are the axes (four faces, equal areas, symmetric): at a vertex
// the interpolated normal is its axis, at a face's centre the three axes' mean, which on the
// octahedron is the face normal (1, 1, 1) / sqrt(3) up to the octant's signs.
TEST(RemeshQuality, InterpolatedNormalOfTheOctahedron) {
  const Mesh mesh = octahedron();
  const RemeshReference reference(mesh);
  for (VertexHandle v : mesh.vertices()) {
    const Eigen::Vector3d axis = position(mesh, v);
    EXPECT_LT((reference.interpolated_normal(at_vertex(mesh, v.idx())) - axis).norm(), 1e-12) << v.idx();
  }
  for (FaceHandle f : mesh.faces()) {
    const SurfacePoint centre{f.idx(), Eigen::Vector3d::Constant(1.0 / 3.0)};
    const Eigen::Vector3d face_normal = to_eigen(mesh.calc_face_normal(f));
    EXPECT_LT((reference.interpolated_normal(centre) - face_normal).norm(), 1e-12) << f.idx();
    // Three corners on one face: the reference normal is that face's.
    EXPECT_LT((reference.normal(centre, centre, centre) - face_normal).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace xparam
