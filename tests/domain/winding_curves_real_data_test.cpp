// The balanced algorithm with DomainOptimizationSettings::swap_winding_curves on a layout of the
// real data of ../shared/data (skipped when absent): the SMPL template against SHREC'19 shape 26
// with the 73 CAESAR landmarks, whose layout holds curves that wind round the body on both meshes.
#include "domain/base_domain_optimization.h"
#include "domain/layout_measures.h"
#include "domain/swap_metrics.h"
#include "io/mesh_loader.h"
#include "layout/consistent_layout.h"
#include "layout/layout_check.h"
#include "support/test_data.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>
#include <vector>

namespace xparam {
namespace {

namespace fs = std::filesystem;

std::vector<VertexHandle> handles(const std::vector<int>& ids) {
  std::vector<VertexHandle> result;
  for (int id : ids) result.emplace_back(id);
  return result;
}

// The curves that wind on both sides (winds()).
int winding_curves(const Layout& layout) {
  int count = 0;
  for (int e = 0; e < static_cast<int>(layout.edges.size()); ++e) {
    std::array<double, 2> lengths{}, chords{};
    for (int side = 0; side < 2; ++side) {
      const LayoutSide& embedding = layout.sides[side];
      lengths[side] = curve_length(layout, side, e);
      chords[side] = (position(embedding.mesh, embedding.anchor_vertices[layout.edges[e].anchors[0]]) -
                      position(embedding.mesh, embedding.anchor_vertices[layout.edges[e].anchors[1]]))
                         .norm();
    }
    count += winds(lengths, chords);
  }
  return count;
}

TEST(WindingCurves, TheBalancedAlgorithmSwapsTheCurvesThatWindOnBothMeshes) {
  const fs::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "no ../shared/data beside the checkout";
  const fs::path shrec = data / "shrec19_connectivity";
  const Mesh smpl = load_mesh(shrec / "44.off").mesh;
  const Mesh shape = load_mesh(shrec / "26.off").mesh;
  std::ifstream landmarks(data / "faust_landmarks" / "smpl_caesar_landmark_indices.json");
  std::ifstream matches_file(shrec / "26.smpl_matches.txt");
  std::vector<int> matches;
  for (int id; matches_file >> id;) matches.push_back(id);
  std::vector<int> on_smpl, on_shape;
  const nlohmann::json by_name = nlohmann::json::parse(landmarks);
  for (const auto& [name, id] : by_name.items()) {
    on_smpl.push_back(id.get<int>());
    on_shape.push_back(matches.at(on_smpl.back()));
  }
  ASSERT_EQ(on_smpl.size(), 73u);

  const Layout built = build_consistent_layout(smpl, handles(on_smpl), shape, handles(on_shape)).layout;
  const auto optimized = [&](bool swap_winding_curves) {
    Layout layout = built;
    DomainOptimizationSettings settings;
    settings.swap_winding_curves = swap_winding_curves;
    const DomainOptimizationResult result = optimize_base_domain(layout, settings);
    LayoutCheckSettings merged;
    merged.triangles = false;
    EXPECT_TRUE(check_layout(layout, merged).consistent());
    return std::pair{result, layout};
  };
  // The paper's balanced algorithm leaves curves that wind (Sellion to Supramenton, 10 cm
  // apart, by a 1.04 m curve down the back and round the chest on both meshes).
  const auto [paper, paper_layout] = optimized(false);
  EXPECT_GE(winding_curves(paper_layout), 3);
  // Taking them as candidates swaps them for shorter diagonals.
  const auto [ours, our_layout] = optimized(true);
  EXPECT_GT(ours.swaps, paper.swaps);
  EXPECT_LT(winding_curves(our_layout), winding_curves(paper_layout));
}

}  // namespace
}  // namespace xparam
