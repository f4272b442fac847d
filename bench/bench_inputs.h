#pragma once
// Inputs shared by the benchmarks: the bundled Spot meshes refined to the sizes the issues name
// (a ~12k-vertex template, a ~53k-vertex target) with 50 anchors, built once per process.
#include "core/anchors.h"
#include "core/mesh.h"
#include "core/midpoint_subdivision.h"
#include "core/provenance.h"
#include "io/mesh_loader.h"
#include "map/pair_mapping.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

namespace xparam::bench {

inline std::filesystem::path data(const std::string& relative) {
  return std::filesystem::path(XPARAM_SOURCE_DIR) / "tests" / "data" / relative;
}

// A file of this process in the temporary folder (the process id in its name, so concurrent
// benchmark runs do not meet), removed when this goes.
struct TemporaryFile {
  std::filesystem::path path;

  explicit TemporaryFile(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("xparam_bench_" + std::to_string(static_cast<long>(::getpid())) + "_" + name)) {}
  ~TemporaryFile() {
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
};

// `count` template vertices by Euclidean farthest-point sampling from vertex 0, and for each the
// nearest target vertex (the two Spot meshes share a frame).
struct SpotPair {
  Mesh source = subdivide_midpoint(load_mesh(data("spot.ply")).mesh);
  Mesh target = subdivide_midpoint(subdivide_midpoint(subdivide_midpoint(load_mesh(data("spot_low_resolution.obj")).mesh)));
  std::vector<VertexHandle> source_anchors, target_anchors;

  explicit SpotPair(int count) {
    std::vector<double> gap(source.n_vertices(), std::numeric_limits<double>::infinity());
    VertexHandle next(0);
    while (static_cast<int>(source_anchors.size()) < count) {
      source_anchors.push_back(next);
      const Eigen::Vector3d p = position(source, next);
      double widest = -1.0;
      for (VertexHandle v : source.vertices()) {
        gap[v.idx()] = std::min(gap[v.idx()], (position(source, v) - p).norm());
        if (gap[v.idx()] > widest) {
          widest = gap[v.idx()];
          next = v;
        }
      }
    }
    for (VertexHandle a : source_anchors) {
      VertexHandle best;
      double best_distance = std::numeric_limits<double>::infinity();
      for (VertexHandle v : target.vertices()) {
        const double d = (position(target, v) - position(source, a)).squaredNorm();
        if (d < best_distance) {
          best_distance = d;
          best = v;
        }
      }
      target_anchors.push_back(best);
    }
  }
};

// The 50-anchor pair of the layout, pair and optimization benchmarks.
inline const SpotPair& spot_pair_50() {
  static const SpotPair pair(50);
  return pair;
}

// Anchors named "a0", "a1", ... at the given vertices.
inline AnchorSet named_anchors(const std::vector<VertexHandle>& vertices, const std::string& source) {
  AnchorSet set;
  set.source = source;
  for (std::size_t k = 0; k < vertices.size(); ++k)
    set.anchors.push_back({"a" + std::to_string(k), AnchorVertex{vertices[k].idx()}, "", 0});
  return set;
}

// Counters every whole-pair benchmark reports: the stage seconds of `sum` (over `iterations`
// runs; the untangling is inside compose) and the process's peak resident memory.
inline void report_pair_seconds(benchmark::State& state, const PairSeconds& sum, double iterations) {
  state.counters["s_anchors"] = sum.anchors / iterations;
  state.counters["s_layout"] = sum.layout / iterations;
  state.counters["s_optimize"] = sum.optimize / iterations;
  state.counters["s_parameterize"] = sum.parameterize / iterations;
  state.counters["s_relax"] = sum.relax / iterations;  // inside s_parameterize
  state.counters["s_compose"] = sum.compose / iterations;
  state.counters["s_untangle"] = sum.untangle / iterations;
  state.counters["s_optimize_map"] = sum.optimize_map / iterations;
  state.counters["s_metrics"] = sum.metrics / iterations;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}

}  // namespace xparam::bench
