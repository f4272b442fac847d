// Micro benchmarks of the parameterization building blocks: point location, one patch solve,
// the n-gon LPBD and the Wachspress domain map.

#include "domain/lpbd.h"
#include "param/domain_map.h"
#include "param/patch_parameterization.h"
#include "param/point_locator.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>

namespace xparam {
namespace {

// A jittered n x n grid over [0, 1]^2 split into 2 n^2 triangles.
void jittered_grid(int n, std::vector<Eigen::Vector2d>& uv, std::vector<std::array<int, 3>>& triangles) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const bool inside = i > 0 && i < n && j > 0 && j < n;
      uv.emplace_back((i + (inside ? jitter(rng) : 0.0)) / n, (j + (inside ? jitter(rng) : 0.0)) / n);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      triangles.push_back({a, b, c});
      triangles.push_back({a, c, d});
    }
  }
}

// 10k queries against 50k triangles (a 158 x 158 grid has 49,928).
void BM_PointLocatorQueries(benchmark::State& state) {
  std::vector<Eigen::Vector2d> uv;
  std::vector<std::array<int, 3>> triangles;
  jittered_grid(158, uv, triangles);
  const PointLocator locator(uv, triangles);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector2d> queries;
  for (int q = 0; q < 10000; ++q) queries.emplace_back(unit(rng), unit(rng));
  for (auto _ : state) {
    int sum = 0;
    for (const auto& p : queries) sum += locator.locate(p).triangle;
    benchmark::DoNotOptimize(sum);
  }
  state.counters["triangles"] = static_cast<double>(triangles.size());
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(queries.size()));
}
BENCHMARK(BM_PointLocatorQueries)->Unit(benchmark::kMillisecond);

void BM_PointLocatorBuild(benchmark::State& state) {
  std::vector<Eigen::Vector2d> uv;
  std::vector<std::array<int, 3>> triangles;
  jittered_grid(158, uv, triangles);
  for (auto _ : state) {
    const PointLocator locator(uv, triangles);
    benchmark::DoNotOptimize(locator.triangle_count());
  }
}
BENCHMARK(BM_PointLocatorBuild)->Unit(benchmark::kMillisecond);

// One patch: a hemisphere of rings x 4 rings vertices onto a quad (mean-value weights + SparseLU).
void BM_ParameterizeHemisphere(benchmark::State& state) {
  const int rings = static_cast<int>(state.range(0));
  const int segments = 4 * rings;
  DiskPatch patch;
  patch.positions.emplace_back(0.0, 0.0, 1.0);
  for (int r = 1; r <= rings; ++r) {
    const double polar = 0.5 * std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2.0 * std::numbers::pi * s / segments;
      patch.positions.emplace_back(std::sin(polar) * std::cos(azimuth), std::sin(polar) * std::sin(azimuth),
                                   std::cos(polar));
    }
  }
  auto ring = [segments](int r, int s) { return 1 + (r - 1) * segments + s % segments; };
  for (int s = 0; s < segments; ++s) patch.triangles.push_back({0, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      patch.triangles.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      patch.triangles.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
  }
  for (int s = 0; s < segments; ++s) patch.boundary_loop.push_back(ring(rings, s));
  patch.corner_positions = {0, segments / 4, segments / 2, 3 * segments / 4};
  patch.polygon = {{0.0, 0.0}, {1.0, 0.0}, {1.2, 1.0}, {-0.1, 0.9}};
  for (auto _ : state) benchmark::DoNotOptimize(parameterize_patch(patch).uv.data());
  state.counters["vertices"] = static_cast<double>(patch.positions.size());
}
BENCHMARK(BM_ParameterizeHemisphere)->Arg(25)->Arg(50)->Unit(benchmark::kMillisecond);

void BM_QuadLpbd(benchmark::State& state) {
  const std::vector<double> lengths = {2.0, 1.1, 1.9, 1.2};
  const std::vector<double> theta = {1.5, 1.7, 1.4, 1.8};
  for (auto _ : state) benchmark::DoNotOptimize(polygon_lpbd(lengths, theta).area);
}
BENCHMARK(BM_QuadLpbd);

void BM_WachspressQuadMap(benchmark::State& state) {
  const DomainMap map({{0.0, 0.0}, {2.0, 0.1}, {1.8, 1.5}, {0.1, 1.0}},
                      {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}});
  const Eigen::Vector2d p(0.9, 0.6);
  for (auto _ : state) benchmark::DoNotOptimize(map(p).x());
}
BENCHMARK(BM_WachspressQuadMap);

}  // namespace
}  // namespace xparam
