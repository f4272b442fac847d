// Issue 20's scale figure: the whole pair (reading both files as `xparam pair` does, then map_pair
// with its default settings, the working copy included) for the bundled SMPL man (6890 vertices)
// against the bundled woman refined to ~1M vertices (four 1-to-4 midpoint subdivisions, which
// keep the surface: 1.76M vertices, then quadric decimation to 1,000,000 of another connectivity,
// the landmarks' vertices kept), written as binary PLY, with the 41 landmarks of human.anchors.json
// given as vertex ids of the large file, on one thread.
//
// Counters: the pair's seconds and peak resident memory, and both over a floor measured in the
// same run: loading both files plus one sparse solve over the target (evaluate/floor_time.h), and
// that floor's own peak memory. Peaks are of the process from a reset (/proc/self/clear_refs) just
// before each part, so building the input does not count. Also the working copy's size and
// carry-back distance, E_L2, strict folds, the area ratio, the mean ground-truth error in % of
// sqrt(target area) (woman vertex k is template vertex k's counterpart; it lies on the refined
// surface within decimation error) and the largest distance of an anchor's image from its vertex.
#include "bench_inputs.h"
#include "core/midpoint_subdivision.h"
#include "evaluate/floor_time.h"
#include "intake/scan_loader.h"
#include "io/anchor_reader.h"
#include "io/mesh_writer.h"
#include "map/decimation.h"
#include "map/pair_mapping.h"

#include <benchmark/benchmark.h>
#include <malloc.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <variant>

namespace xparam {
namespace {

namespace fs = std::filesystem;

// Resets the process's peak resident memory to what it holds now (Linux >= 4.0).
void reset_peak_memory() {
  malloc_trim(0);  // give freed heap back first, so the reset starts from what is in use
  std::ofstream("/proc/self/clear_refs") << "5";
}

// The process's peak resident memory since the last reset, MB (VmHWM).
double peak_memory_mb() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
  return std::nan("");
}

struct LargeWoman {
  fs::path template_file = bench::data("human_man.obj");
  bench::TemporaryFile target_file{"woman_1m.ply"};  // the refined target, written once per process
  AnchorSet template_anchors = read_anchors(bench::data("human.anchors.json"));
  AnchorSet target_anchors;            // the same landmarks as vertex ids of the large file
  std::vector<Eigen::Vector3d> truth;  // per template vertex: its counterpart on the target

  LargeWoman() {
    const LoadedMesh woman = load_mesh(bench::data("sample_targets/woman.obj"));
    for (VertexHandle v : woman.mesh.vertices()) truth.push_back(position(woman.mesh, v));
    Mesh fine = woman.mesh;
    for (int level = 0; level < 4; ++level) fine = subdivide_midpoint(fine);  // vertex k stays vertex k
    std::vector<VertexHandle> locked;
    for (const AnchorSpec& anchor : template_anchors.anchors)
      locked.emplace_back(std::get<AnchorVertex>(anchor.location).index);
    DecimationSettings no_slivers;  // midpoint subdivision puts collinear vertices side by side
    no_slivers.max_aspect_ratio = 20.0;
    const DecimatedMesh large = decimate(fine, 1000000, locked, no_slivers);
    std::vector<int> large_vertex(fine.n_vertices(), -1);
    for (std::size_t v = 0; v < large.source_vertex.size(); ++v) large_vertex[large.source_vertex[v]] = static_cast<int>(v);
    target_anchors = template_anchors;
    for (AnchorSpec& anchor : target_anchors.anchors) {
      int& index = std::get<AnchorVertex>(anchor.location).index;
      index = large_vertex[index];
    }
    write_ply(target_file.path, large.mesh);
  }
};

void BM_LargeTarget1M(benchmark::State& state) {
  static const std::unique_ptr<LargeWoman> in = std::make_unique<LargeWoman>();
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  using Clock = std::chrono::steady_clock;
  double seconds = 0.0;
  double peak = 0.0;
  PairMapping map;
  std::size_t target_vertices = 0;
  double anchor_error = 0.0;
  double gt_error = 0.0;
  for (auto _ : state) {
    reset_peak_memory();
    const Clock::time_point start = Clock::now();
    const LoadedMesh source = load_mesh(in->template_file);
    const LoadedMesh target = load_scan(in->target_file.path, in->target_anchors, {});
    map = map_pair(source.mesh, in->template_anchors, target.mesh, in->target_anchors, {});
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
    peak = std::max(peak, peak_memory_mb());
    target_vertices = target.mesh.n_vertices();
    for (std::size_t k = 0; k < in->template_anchors.anchors.size(); ++k) {
      const int v = std::get<AnchorVertex>(in->template_anchors.anchors[k].location).index;
      const int on_target = std::get<AnchorVertex>(in->target_anchors.anchors[k].location).index;
      anchor_error = std::max(anchor_error, (map.remesh_vertices.row(v).transpose() -
                                             position(target.mesh, target.mesh.vertex_handle(on_target)))
                                                .norm());
    }
    gt_error = 0.0;
    for (std::size_t v = 0; v < in->truth.size(); ++v)
      gt_error += (map.remesh_vertices.row(static_cast<Eigen::Index>(v)).transpose() - in->truth[v]).norm();
    gt_error /= static_cast<double>(in->truth.size()) * std::sqrt(surface_area(target.mesh));
  }
  reset_peak_memory();
  const double floor = evaluate::floor_seconds(in->template_file, in->target_file.path, 1);
  const double floor_peak = peak_memory_mb();
  const double n = static_cast<double>(state.iterations());
  state.counters["target_V"] = static_cast<double>(target_vertices);
  state.counters["work_V"] = map.working_copy.vertices;
  state.counters["s_pair"] = seconds / n;
  state.counters["s_floor"] = floor;
  state.counters["floor_x"] = seconds / n / floor;
  state.counters["s_working_copy"] = map.working_copy.seconds;
  state.counters["peak_MB"] = peak;
  state.counters["floor_peak_MB"] = floor_peak;
  state.counters["peak_floor_x"] = peak / floor_peak;
  state.counters["carry_max"] = map.working_copy.max_carry_distance;
  state.counters["anchor_error"] = anchor_error;
  state.counters["E_L2"] = map.distortion.all.e_l2;
  state.counters["strict_folds"] = map.quality.strictly_folded_faces;
  state.counters["area_ratio"] = map.quality.area_ratio;
  state.counters["gt_pct_sqrtA"] = 100.0 * gt_error;
}
BENCHMARK(BM_LargeTarget1M)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace xparam
