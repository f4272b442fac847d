// The checker on hand-built layouts: the octahedron's own edges on a subdivided octahedron is a
// consistent layout; rerouted chains, a mirrored side and broken bookkeeping must be rejected.
#include "layout/layout_check.h"
#include "layout/layout.h"
#include "layout_fixtures.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

using test::subdivided_octahedron;
using test::vertex_at;

constexpr int kDivisions = 4;
const Eigen::Vector3d kCorner[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
enum { kPx, kNx, kPy, kNy, kPz, kNz };
const std::array<int, 2> kEdges[12] = {{kPx, kPy}, {kPx, kNy}, {kPx, kPz}, {kPx, kNz},
                                       {kNx, kPy}, {kNx, kNy}, {kNx, kPz}, {kNx, kNz},
                                       {kPy, kPz}, {kPy, kNz}, {kNy, kPz}, {kNy, kNz}};

// Lattice point of face (+x, +y, +z) with integer weights summing to kDivisions.
Eigen::Vector3d lattice(int wx, int wy, int wz) { return Eigen::Vector3d(wx, wy, wz) / kDivisions; }

// The straight chain between two octahedron corners (positions given), through lattice points.
std::vector<VertexHandle> straight_chain(const Mesh& mesh, const Eigen::Vector3d& a,
                                         const Eigen::Vector3d& b) {
  std::vector<VertexHandle> chain;
  for (int t = 0; t <= kDivisions; ++t) chain.push_back(vertex_at(mesh, a + (b - a) * t / kDivisions));
  return chain;
}

std::vector<VertexHandle> chain_through(const Mesh& mesh, const std::vector<Eigen::Vector3d>& points) {
  std::vector<VertexHandle> chain;
  for (const auto& p : points) chain.push_back(vertex_at(mesh, p));
  return chain;
}

// Anchors at the octahedron corners; side 1 may place anchor k at corner `placement[k]`.
Layout octahedron_layout(const std::array<int, 6>& placement = {0, 1, 2, 3, 4, 5}) {
  Layout layout;
  layout.n_anchors = 6;
  for (const auto& e : kEdges) layout.edges.push_back({e});
  for (int side = 0; side < 2; ++side) {
    LayoutSide& s = layout.sides[side];
    s.mesh = subdivided_octahedron(kDivisions);
    for (int k = 0; k < 6; ++k) s.anchor_vertices.push_back(VertexHandle(side == 0 ? k : placement[k]));
    for (const auto& e : kEdges) {
      const int a = side == 0 ? e[0] : placement[e[0]];
      const int b = side == 0 ? e[1] : placement[e[1]];
      s.chains.push_back(straight_chain(s.mesh, kCorner[a], kCorner[b]));
    }
  }
  std::vector<std::vector<int>> rotations;
  for (int a = 0; a < 6; ++a) rotations.push_back(mesh_rotation(layout, 0, a));
  layout.patches = faces_of_rotation(layout, rotations);
  assign_patches(layout);
  return layout;
}

bool mentions(const LayoutCheck& check, const std::string& word) {
  for (const auto& line : check.violations) {
    if (line.find(word) != std::string::npos) return true;
  }
  return false;
}

TEST(LayoutCheck, AcceptsTheOctahedronOnItsSubdivision) {
  const Layout layout = octahedron_layout();
  ASSERT_EQ(layout.patches.size(), 8u);
  for (const auto& patch : layout.patches) EXPECT_EQ(patch.size(), 3u);
  test::expect_consistent(layout, "octahedron");
  // Each patch is one octant: 16 mesh faces of the 128.
  std::vector<int> faces(8, 0);
  for (FaceHandle f : layout.sides[1].mesh.faces()) ++faces[patch_of(layout.sides[1].mesh, f)];
  for (int count : faces) EXPECT_EQ(count, kDivisions * kDivisions);
}

TEST(LayoutCheck, RotationAtAnchorIsCounterClockwiseSeenFromOutside) {
  const Layout layout = octahedron_layout();
  // Around +x seen from outside: +y, +z, -y, -z (edges 0, 2, 1, 3, all leaving +x).
  std::vector<int> rotation = mesh_rotation(layout, 0, kPx);
  std::rotate(rotation.begin(), std::find(rotation.begin(), rotation.end(), 0), rotation.end());
  EXPECT_EQ(rotation, (std::vector<int>{0, 4, 2, 6}));
}

TEST(LayoutCheck, AcceptsABentChain) {
  Layout layout = octahedron_layout();
  // Edge 0 (+x -> +y) leaves the octahedron edge and runs through the inside of face (+x, +y, +z).
  layout.sides[1].chains[0] =
      chain_through(layout.sides[1].mesh, {lattice(4, 0, 0), lattice(3, 1, 0), lattice(2, 1, 1),
                                           lattice(1, 2, 1), lattice(1, 3, 0), lattice(0, 4, 0)});
  assign_patches(layout);
  test::expect_consistent(layout, "bent chain");
}

TEST(LayoutCheck, RejectsChainsSharingAVertex) {
  Layout layout = octahedron_layout();
  // Edge 0 touches edge 2 (+x -> +z) at its first interior vertex.
  layout.sides[1].chains[0] =
      chain_through(layout.sides[1].mesh, {lattice(4, 0, 0), lattice(3, 0, 1), lattice(2, 1, 1),
                                           lattice(1, 2, 1), lattice(1, 3, 0), lattice(0, 4, 0)});
  assign_patches(layout);
  const LayoutCheck check = check_layout(layout);
  EXPECT_FALSE(check.consistent());
  EXPECT_TRUE(mentions(check, "target: edges 0 and 2 share vertex")) << check.violations.front();
}

TEST(LayoutCheck, RejectsCrossingChains) {
  Layout layout = octahedron_layout();
  // Edge 0 crosses edge 8 (+y -> +z) into face (-x, +y, +z) and crosses back.
  const Eigen::Vector3d inside_nx_face = Eigen::Vector3d(-1, 2, 1) / kDivisions;
  layout.sides[1].chains[0] =
      chain_through(layout.sides[1].mesh,
                    {lattice(4, 0, 0), lattice(3, 1, 0), lattice(2, 1, 1), lattice(1, 1, 2), lattice(0, 2, 2),
                     inside_nx_face, lattice(0, 3, 1), lattice(1, 3, 0), lattice(0, 4, 0)});
  assign_patches(layout);
  const LayoutCheck check = check_layout(layout);
  EXPECT_FALSE(check.consistent());
  EXPECT_TRUE(mentions(check, "target: edges 0 and 8 share vertex")) << check.violations.front();
}

TEST(LayoutCheck, RejectsAMirroredSide) {
  // The target swaps the poles: a valid embedding of the mirror image, every rotation reversed.
  const Layout layout = octahedron_layout({kPx, kNx, kPy, kNy, kNz, kPz});
  const LayoutCheck check = check_layout(layout);
  EXPECT_FALSE(check.consistent());
  EXPECT_TRUE(mentions(check, "anchor 0: rotation")) << check.violations.front();
}

TEST(LayoutCheck, RejectsAFaceInTheWrongPatch) {
  Layout layout = octahedron_layout();
  Mesh& mesh = layout.sides[0].mesh;
  OpenMesh::FPropHandleT<int> patch;
  ASSERT_TRUE(mesh.get_property_handle(patch, "xparam:patch"));
  // A face in the middle of octant (+x, +y, +z) claims another patch.
  const VertexHandle centre = vertex_at(mesh, lattice(2, 1, 1));
  const FaceHandle f = *mesh.vf_range(centre).begin();
  mesh.property(patch, f) = (mesh.property(patch, f) + 1) % 8;
  const LayoutCheck check = check_layout(layout);
  EXPECT_FALSE(check.consistent());
  EXPECT_TRUE(mentions(check, "source: mesh edge")) << check.violations.front();
  EXPECT_TRUE(mentions(check, "falls into 2 pieces"));
}

TEST(LayoutCheck, RejectsAMissingEdgeAndAJump) {
  Layout missing = octahedron_layout();
  missing.edges.pop_back();
  for (auto& side : missing.sides) side.chains.pop_back();
  EXPECT_TRUE(mentions(check_layout(missing), "6 anchors need 12 edges; layout has 11"));

  Layout jump = octahedron_layout();
  auto& chain = jump.sides[0].chains[0];
  chain.erase(chain.begin() + 2);
  EXPECT_TRUE(mentions(check_layout(jump), "source: edge 0 chain jumps from vertex"));
}

}  // namespace
}  // namespace xparam
