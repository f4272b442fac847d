// Folded faces credited to their nearest anchor, on the bundled man with his anchors: faces
// around an anchor's vertex go to that anchor, the list is ordered by count (ties in anchor
// order), and bad arguments are refused.
#include "map/fold_report.h"

#include "core/errors.h"
#include "layout/layout_fixtures.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace xparam {
namespace {

struct Man {
  Mesh mesh = test::load(test::data_path("human_man.obj"));
  std::vector<VertexHandle> anchors = test::handles(test::anchor_vertex_ids("human_man.anchors.json"));
  std::vector<std::string> names;
  std::vector<std::array<int, 3>> faces;

  Man() {
    for (size_t k = 0; k < anchors.size(); ++k) names.push_back("a" + std::to_string(k));
    for (FaceHandle f : mesh.faces()) {
      std::array<int, 3> corners{};
      int c = 0;
      for (VertexHandle v : mesh.fv_range(f)) corners[c++] = v.idx();
      faces.push_back(corners);
    }
  }

  // The first `n` faces around anchor k's vertex.
  std::vector<int> faces_at(int k, int n) const {
    std::vector<int> ids;
    for (FaceHandle f : mesh.vf_range(anchors[k])) {
      if (static_cast<int>(ids.size()) < n) ids.push_back(f.idx());
    }
    return ids;
  }
};

std::vector<int> sorted_union(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  return a;
}

TEST(FoldsByAnchor, FacesAroundAnAnchorGoToItMostFoldsFirst) {
  const Man man;
  ASSERT_GE(man.anchors.size(), 6u);
  const std::vector<AnchorFolds> folds = folds_by_anchor(
      man.mesh, man.anchors, man.names, man.faces, sorted_union(man.faces_at(0, 2), man.faces_at(5, 3)));
  ASSERT_EQ(folds.size(), 2u);
  EXPECT_EQ(folds[0].anchor, 5);
  EXPECT_EQ(folds[0].name, "a5");
  EXPECT_EQ(folds[0].folded_faces, 3);
  EXPECT_EQ(folds[1].anchor, 0);
  EXPECT_EQ(folds[1].name, "a0");
  EXPECT_EQ(folds[1].folded_faces, 2);
}

TEST(FoldsByAnchor, TiesKeepTheAnchorOrderAndNoFoldGivesNothing) {
  const Man man;
  const std::vector<AnchorFolds> folds = folds_by_anchor(
      man.mesh, man.anchors, man.names, man.faces, sorted_union(man.faces_at(5, 2), man.faces_at(3, 2)));
  ASSERT_EQ(folds.size(), 2u);
  EXPECT_EQ(folds[0].name, "a3");
  EXPECT_EQ(folds[1].name, "a5");
  EXPECT_TRUE(folds_by_anchor(man.mesh, man.anchors, man.names, man.faces, {}).empty());
}

TEST(FoldsByAnchor, RefusesMismatchedNamesAndUnknownFaces) {
  const Man man;
  std::vector<std::string> fewer = man.names;
  fewer.pop_back();
  EXPECT_THROW(folds_by_anchor(man.mesh, man.anchors, fewer, man.faces, {0}), ParamError);
  EXPECT_THROW(
      folds_by_anchor(man.mesh, man.anchors, man.names, man.faces, {static_cast<int>(man.faces.size())}),
      ParamError);
}

}  // namespace
}  // namespace xparam
