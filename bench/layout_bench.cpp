// Consistent layout of 50 anchors on a ~12k-vertex template and a ~53k-vertex target (the
// bundled Spot meshes, midpoint-subdivided), at one thread and at the default thread count.
// Reports seconds per stage and the process's peak resident memory.
#include "core/provenance.h"
#include "layout/consistent_layout.h"

#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <OpenMesh/Core/IO/MeshIO.hh>

#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace xparam {
namespace {

Mesh read(const std::string& relative) {
  Mesh mesh;
  const std::string path = std::string(XPARAM_SOURCE_DIR) + "/tests/data/" + relative;
  if (!OpenMesh::IO::read_mesh(mesh, path)) throw std::runtime_error("cannot read " + path);
  return mesh;
}

// One 1-to-4 midpoint subdivision (the surface stays the same, only finer).
Mesh subdivide(const Mesh& mesh) {
  Mesh fine;
  for (VertexHandle v : mesh.vertices()) fine.add_vertex(mesh.point(v));
  std::vector<VertexHandle> midpoint(mesh.n_edges());
  for (EdgeHandle e : mesh.edges()) {
    const HalfedgeHandle h = mesh.halfedge_handle(e, 0);
    midpoint[e.idx()] = fine.add_vertex(
        0.5 * (mesh.point(mesh.from_vertex_handle(h)) + mesh.point(mesh.to_vertex_handle(h))));
  }
  for (FaceHandle f : mesh.faces()) {
    VertexHandle c[3], m[3];
    int k = 0;
    for (HalfedgeHandle h : mesh.fh_range(f)) {
      c[k] = mesh.from_vertex_handle(h);
      m[k] = midpoint[mesh.edge_handle(h).idx()];  // midpoint of edge c[k] -> c[k+1]
      ++k;
    }
    fine.add_face(c[0], m[0], m[2]);
    fine.add_face(c[1], m[1], m[0]);
    fine.add_face(c[2], m[2], m[1]);
    fine.add_face(m[0], m[1], m[2]);
  }
  init_provenance(fine);
  return fine;
}

// 50 anchors by farthest-point sampling on the template and their nearest target vertices.
struct Inputs {
  Mesh source = subdivide(read("spot.ply"));
  Mesh target = subdivide(subdivide(subdivide(read("spot_low_resolution.obj"))));
  std::vector<VertexHandle> source_anchors, target_anchors;

  Inputs() {
    std::vector<double> gap(source.n_vertices(), std::numeric_limits<double>::infinity());
    VertexHandle next(0);
    while (source_anchors.size() < 50) {
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

const Inputs& inputs() {
  static const Inputs data;
  return data;
}

void BM_ConsistentLayout50(benchmark::State& state) {
  const Inputs& in = inputs();
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  LayoutTimings sum;
  std::array<int, 2> refined{};
  for (auto _ : state) {
    const auto result = build_consistent_layout(in.source, in.source_anchors, in.target, in.target_anchors);
    benchmark::DoNotOptimize(result.layout.edges.data());
    sum.candidates += result.seconds.candidates;
    sum.tree += result.seconds.tree;
    sum.diagonals += result.seconds.diagonals;
    sum.patches += result.seconds.patches;
    refined = result.refined_vertices;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["source_V"] = static_cast<double>(in.source.n_vertices());
  state.counters["target_V"] = static_cast<double>(in.target.n_vertices());
  state.counters["refined_source"] = refined[0];
  state.counters["refined_target"] = refined[1];
  state.counters["s_candidates"] = sum.candidates / n;
  state.counters["s_tree"] = sum.tree / n;
  state.counters["s_diagonals"] = sum.diagonals / n;
  state.counters["s_patches"] = sum.patches / n;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}
// Argument: thread count (1 = the single-core figure of the issue).
BENCHMARK(BM_ConsistentLayout50)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace xparam
