// xparam_evaluate: the structure of the paper's Table 1 on real pairs from ../shared/data.
//
// For every pair of the list below and every configuration (Original: the initial layout as
// built, no stretching, swapping or merging; Stretched: boundaries straightened only; By SDL:
// greedy swapping on eq. 13 for every curve; Balanced: section 4.3; Balanced + merging: section
// 5 after it), it runs the whole pair pipeline (map_pair) and prints E_L2 (eq. 6), E_ang (eq. 3),
// the optimization's seconds, the swaps and merges, and, for pairs whose meshes share a vertex
// order (exact ground truth), the mean distance from each template vertex's image to its true
// counterpart as a fraction of the target's bounding-box diagonal.
//
// Usage: xparam_evaluate [--data DIR] [--only SUBSTRING]
// DIR defaults to ../shared/data beside the source tree; pairs whose files are absent are skipped.
#include "bench_inputs.h"
#include "core/anchors.h"
#include "core/errors.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "map/pair_mapping.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace xparam;

// Landmark vertex ids: .json {"name": id} in file order; .pid first column; otherwise the last
// integer of every non-empty line (".pinned" lines read "lk 847", plain lists "5259").
std::vector<int> read_ids(const fs::path& path) {
  std::vector<int> ids;
  std::ifstream in(path);
  if (path.extension() == ".json") {
    const nlohmann::ordered_json table = nlohmann::ordered_json::parse(in);
    for (const auto& [name, value] : table.items()) ids.push_back(value.get<int>());
    return ids;
  }
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream tokens(line);
    std::vector<std::string> words;
    for (std::string word; tokens >> word;) words.push_back(word);
    if (!words.empty()) ids.push_back(std::stoi(path.extension() == ".pid" ? words.front() : words.back()));
  }
  return ids;
}

AnchorSet anchors_at(const std::vector<int>& ids, const fs::path& source) {
  std::vector<VertexHandle> vertices;
  for (int id : ids) vertices.emplace_back(id);
  return bench::named_anchors(vertices, source.string());
}

struct PairSpec {
  std::string name;
  fs::path source, target;              // relative to the data directory (or absolute)
  fs::path source_ids, target_ids;      // landmark files (read_ids)
  bool same_vertex_order = false;       // vertex i of the source is vertex i of the target
};

// The documented list (README, "Evaluation"): humans in other poses and of other subjects with
// the 73 CAESAR landmarks, TOSCA pairs within a class (exact ground truth) and across classes,
// and two pairs of Schmidt et al. 2023.
std::vector<PairSpec> pair_list() {
  const fs::path caesar = "faust_landmarks/smpl_caesar_landmark_indices.json";
  return {
      {"FAUST 000/001 (pose)", "faust_registrations/tr_reg_000.ply", "faust_registrations/tr_reg_001.ply", caesar,
       caesar, true},
      {"FAUST 000/010 (subject)", "faust_registrations/tr_reg_000.ply", "faust_registrations/tr_reg_010.ply", caesar,
       caesar, true},
      {"FAUST 000/090 (subject, pose)", "faust_registrations/tr_reg_000.ply", "faust_registrations/tr_reg_090.ply",
       caesar, caesar, true},
      {"TOSCA centaur0/1", "tosca/centaur0.off", "tosca/centaur1.off", "tosca/corrs/centaur.pid",
       "tosca/corrs/centaur.pid", true},
      {"TOSCA wolf0/2", "tosca/wolf0.off", "tosca/wolf2.off", "tosca/corrs/wolf.pid", "tosca/corrs/wolf.pid", true},
      {"TOSCA horse0/wolf0", "tosca/horse0.off", "tosca/wolf0.off", "tosca/corrs/horse.pid", "tosca/corrs/wolf.pid",
       false},
      {"cat/horse (Yang 2020)", "landmark_pairs_schmidt2023/yang2020_cat_horse/input0.obj",
       "landmark_pairs_schmidt2023/yang2020_cat_horse/input1.obj",
       "landmark_pairs_schmidt2023/yang2020_cat_horse/landmarks0.txt",
       "landmark_pairs_schmidt2023/yang2020_cat_horse/landmarks1.txt", false},
      {"hand plain/vulcan", "landmark_pairs_schmidt2023/hand/hand_plain.obj",
       "landmark_pairs_schmidt2023/hand/hand_vulcan.obj", "landmark_pairs_schmidt2023/hand/hand_plain.pinned",
       "landmark_pairs_schmidt2023/hand/hand_vulcan_0.pinned", false},
  };
}

struct Configuration {
  std::string name;
  DomainOptimizationSettings settings;
};

std::vector<Configuration> configurations() {
  std::vector<Configuration> list;
  DomainOptimizationSettings s;
  s.stretch = false;
  s.metric = SwapMetric::none;
  s.merge = false;
  list.push_back({"Original", s});
  s.stretch = true;
  list.push_back({"Stretched", s});
  s.metric = SwapMetric::sdl;
  list.push_back({"By SDL", s});
  s.metric = SwapMetric::balanced;
  list.push_back({"Balanced", s});
  s.merge = true;
  list.push_back({"Balanced + merging", s});
  return list;
}

double bbox_diagonal(const Mesh& mesh) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (VertexHandle v : mesh.vertices()) {
    lo = lo.cwiseMin(position(mesh, v));
    hi = hi.cwiseMax(position(mesh, v));
  }
  return (hi - lo).norm();
}

// Mean distance from the image of template vertex i to target vertex i, over the diagonal.
double ground_truth_error(const PairMapping& map, const Mesh& target) {
  const Eigen::Index n = map.remesh_vertices.rows();
  double sum = 0.0;
  for (Eigen::Index v = 0; v < n; ++v)
    sum += (map.remesh_vertices.row(v).transpose() - position(target, VertexHandle(static_cast<int>(v)))).norm();
  return sum / static_cast<double>(n) / bbox_diagonal(target);
}

void evaluate(const PairSpec& pair, const fs::path& data) {
  const LoadedMesh source = load_mesh(data / pair.source);
  const LoadedMesh target = load_mesh(data / pair.target);
  const AnchorSet source_anchors = anchors_at(read_ids(data / pair.source_ids), pair.source_ids);
  const AnchorSet target_anchors = anchors_at(read_ids(data / pair.target_ids), pair.target_ids);
  std::printf("\n%s: %zu anchors, %zu / %zu vertices\n", pair.name.c_str(), source_anchors.anchors.size(),
              source.mesh.n_vertices(), target.mesh.n_vertices());
  std::printf("| configuration | E_L2 | E_ang | flipped | gt error | swaps | merges | optimize s | total s |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const Configuration& configuration : configurations()) {
    PairSettings settings;
    settings.optimization = configuration.settings;
    try {
      const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, settings);
      const std::string gt =
          pair.same_vertex_order ? std::to_string(ground_truth_error(map, target.mesh)) : std::string("-");
      std::printf("| %s | %.4f | %.4f | %zu | %s | %d | %d | %.3f | %.3f |\n", configuration.name.c_str(),
                  map.distortion.all.e_l2, map.distortion.all.e_ang, map.quality.flipped_faces.size(), gt.c_str(),
                  map.optimization.swaps, map.optimization.merges, map.seconds.optimize, map.seconds.total);
    } catch (const Error& e) {
      std::printf("| %s | failed: %s |\n", configuration.name.c_str(), e.what());
    }
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  fs::path data = fs::path(XPARAM_SOURCE_DIR).parent_path() / "shared" / "data";
  std::string only;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--data") {
      data = argv[i + 1];
    } else if (flag == "--only") {
      only = argv[i + 1];
    } else {
      std::cerr << "usage: xparam_evaluate [--data DIR] [--only SUBSTRING]\n";
      return 1;
    }
  }
  if (!fs::is_directory(data)) {
    std::cout << "xparam_evaluate: no data directory " << data << ": nothing to evaluate\n";
    return 0;
  }
  for (const PairSpec& pair : pair_list()) {
    if (!only.empty() && pair.name.find(only) == std::string::npos) continue;
    if (!fs::exists(data / pair.source) || !fs::exists(data / pair.target)) {
      std::cout << "\n" << pair.name << ": skipped (files absent)\n";
      continue;
    }
    try {
      evaluate(pair, data);
    } catch (const std::exception& e) {
      std::cout << "\n" << pair.name << ": cannot evaluate: " << e.what() << "\n";
    }
  }
  return 0;
}
