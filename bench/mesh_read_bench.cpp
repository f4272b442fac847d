// Reading stays linear (issue 20): one polygon of N corners (a scanner's cap, fanned by
// SoupBuilder::add_face; its repeated-corner check was quadratic: 40 s at 400k corners), and an
// ascii STL of N corner positions crafted so that an FNV-style hash of their bits collides (the
// welder once hashed that way, and crafted corners welded in quadratic time). Each size is read
// through read_triangle_soup from a file written beforehand; time per read should grow with N.
#include "bench_inputs.h"
#include "io/mesh_reader.h"

#include <benchmark/benchmark.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace xparam {
namespace {

namespace fs = std::filesystem;

void BM_ReadOnePolygon(benchmark::State& state) {
  const auto corners = static_cast<int>(state.range(0));
  const bench::TemporaryFile file("polygon_" + std::to_string(corners) + ".off");
  const fs::path& path = file.path;
  {
    std::ofstream off(path);
    off.precision(17);
    off << "OFF\n" << corners << " 1 0\n";
    for (int v = 0; v < corners; ++v) off << std::cos(v * 1e-5) << " " << std::sin(v * 1e-5) << " 0\n";
    off << corners;
    for (int v = 0; v < corners; ++v) off << " " << v;
    off << "\n";
  }
  for (auto _ : state) benchmark::DoNotOptimize(read_triangle_soup(path));
  state.counters["corners"] = corners;
}
BENCHMARK(BM_ReadOnePolygon)->Arg(100000)->Arg(400000)->Unit(benchmark::kMillisecond);

void BM_ReadCraftedStl(benchmark::State& state) {
  const auto positions = static_cast<int>(state.range(0));
  const bench::TemporaryFile file("crafted_" + std::to_string(positions) + ".stl");
  const fs::path& path = file.path;
  {
    // x fixed, y stepping, z chosen so that (bits(x) * P ^ bits(y)) * P ^ bits(z) is constant.
    constexpr std::uint64_t kPrime = 1000003u;
    const std::uint64_t x_bits = std::bit_cast<std::uint64_t>(1.0);
    std::ofstream stl(path);
    stl.precision(17);
    stl << "solid crafted\n";
    int written = 0;
    double previous_y = 0.0, previous_z = 0.0;
    for (std::uint64_t k = 1; written < positions; ++k) {
      const double y = 1.0 + static_cast<double>(k) * 1e-6;
      const double z =
          std::bit_cast<double>(0x3ff0000000000000ULL ^ (((x_bits * kPrime) ^ std::bit_cast<std::uint64_t>(y)) * kPrime));
      if (!std::isfinite(z)) continue;
      if (written++ > 0)
        stl << "facet normal 0 0 0\n outer loop\n  vertex -1 0.5 0.25\n  vertex 1 " << previous_y << " " << previous_z
            << "\n  vertex 1 " << y << " " << z << "\n endloop\nendfacet\n";
      previous_y = y;
      previous_z = z;
    }
    stl << "endsolid crafted\n";
  }
  for (auto _ : state) benchmark::DoNotOptimize(read_triangle_soup(path));
  state.counters["positions"] = positions;
}
BENCHMARK(BM_ReadCraftedStl)->Arg(100000)->Arg(400000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace xparam
