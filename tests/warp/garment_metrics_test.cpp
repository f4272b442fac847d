// Edge ratios, stretch and penetration on garments whose answers are known.
#include "warp/garment_metrics.h"

#include "warp/garment_warp.h"
#include "support/warp_shapes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

namespace xparam {
namespace {

TEST(GarmentMetrics, ScaledGarmentHasRatioAndStretchOfTheScale) {
  const TriangleSoup garment = test::sphere_soup(2, 1.0);
  std::vector<Eigen::Vector3d> doubled = garment.vertices;
  for (Eigen::Vector3d& p : doubled) p *= 2.0;
  const ShapeChange change = shape_change(garment.vertices, doubled, garment.triangles);
  for (const ValueSummary& s : {change.edge_ratio, change.stretch}) {
    EXPECT_NEAR(s.mean, 2.0, 1e-12);
    EXPECT_NEAR(s.p95, 2.0, 1e-12);
    EXPECT_NEAR(s.max, 2.0, 1e-12);
    EXPECT_NEAR(s.min, 2.0, 1e-12);
  }
}

TEST(GarmentMetrics, OneStretchedTriangle) {
  // Two triangles; moving vertex 3 from (1, 1) to (3, 1) stretches only the second one: its edge
  // to vertex 2 triples, its edge to vertex 1 grows to sqrt(5), and its map [[3, 2], [0, 1]] has
  // largest singular value sqrt(7 + sqrt(40)).
  const std::vector<Eigen::Vector3d> rest = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  std::vector<Eigen::Vector3d> warped = rest;
  const std::vector<std::array<int, 3>> triangles = {{0, 1, 2}, {1, 3, 2}};
  warped[3] = {3, 1, 0};
  const ShapeChange change = shape_change(rest, warped, triangles);
  EXPECT_NEAR(change.edge_ratio.max, 3.0, 1e-12);
  EXPECT_NEAR(change.edge_ratio.min, 1.0, 1e-12);
  EXPECT_NEAR(change.edge_ratio.mean, (3.0 + std::sqrt(5.0) + 3.0) / 5.0, 1e-12);  // 5 edges, 3 unchanged
  EXPECT_NEAR(change.stretch.min, 1.0, 1e-12);
  EXPECT_NEAR(change.stretch.max, std::sqrt(7.0 + std::sqrt(40.0)), 1e-12);
}

TEST(GarmentMetrics, SummaryPercentileIsNearestRank) {
  std::vector<double> values;
  for (int i = 100; i >= 1; --i) values.push_back(i);
  const ValueSummary s = summarize(values);
  EXPECT_DOUBLE_EQ(s.p95, 95.0);
  EXPECT_DOUBLE_EQ(s.mean, 50.5);
  EXPECT_DOUBLE_EQ(s.max, 100.0);
  EXPECT_TRUE(std::isnan(summarize({}).mean));
}

TEST(GarmentMetrics, PenetrationCountsVerticesInsideAndTheDeepest) {
  const BodyDistance body(test::box_soup(2, 1.0));
  const Penetration p = penetration({{0, 0, 0.5}, {0, 0, 0.9}, {0, 0, 1.5}, {2, 0, 0}}, body);
  EXPECT_EQ(p.count, 2);
  EXPECT_NEAR(p.max_depth, 0.5, 1e-12);
}

TEST(GarmentWarp, SameResultAtAnyThreadCount) {
  const TriangleSoup body = test::sphere_soup(3);
  TriangleSoup garment = test::sphere_soup(2, 1.02);
  const GarmentBinding binding = bind_garment(body, garment.vertices);
  std::vector<WarpTarget> targets;
  for (int k = 0; k < 4; ++k) {
    TriangleSoup image = body;
    for (Eigen::Vector3d& p : image.vertices) p = Eigen::Vector3d(1.0 + 0.1 * k, 1.0, 1.0 - 0.05 * k).asDiagonal() * p;
    targets.push_back({"t" + std::to_string(k), image});
  }
  WarpSettings settings;
  settings.clearance = ClearanceSettings{0.03};
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return warp_garment_onto(garment, binding, targets, settings);
  };
  const std::vector<WarpedGarment> one = run(1);
  const std::vector<WarpedGarment> two = run(2);
  for (std::size_t t = 0; t < targets.size(); ++t) {
    EXPECT_TRUE(one[t].error.empty()) << one[t].error;
    EXPECT_EQ(one[t].vertices, two[t].vertices);
    EXPECT_EQ(one[t].penetration.count, 0);
    EXPECT_EQ(one[t].change.stretch.p95, two[t].change.stretch.p95);
  }
}

TEST(GarmentWarp, ImageOfAnotherTemplateIsAnError) {
  const TriangleSoup body = test::sphere_soup(3);
  const TriangleSoup garment = test::sphere_soup(2, 1.02);
  const GarmentBinding binding = bind_garment(body, garment.vertices);
  const std::vector<WarpedGarment> results = warp_garment_onto(garment, binding, {{"small", test::sphere_soup(1)}}, {});
  EXPECT_NE(results[0].error.find("not an image of the template"), std::string::npos) << results[0].error;
}

}  // namespace
}  // namespace xparam
