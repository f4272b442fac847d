// Accuracy of the body measurements through the map (issue 23; docs/measurements.md): the
// bundled SMPL template (tests/data/human_man.obj) mapped onto FAUST registrations of other
// subjects decimated to another connectivity, the bundled measurement set taken on each target
// through the map, against the same measurements on the registration itself (it shares SMPL's
// vertex order, so template vertex k's true counterpart is the registration's vertex k). The
// target's landmarks are the registration's positions of the template's landmark vertices,
// snapped onto the decimated surface, as a user places landmarks on a scan.
//
// Usage: xparam_measure_accuracy [--landmarks human|caesar] [--vertices N] [SUBJECT...]
// (SUBJECT: tr_reg_010 ...; default: the six other subjects of ../shared/data, 010 020 030 040 080 090). Prints one row per target and
// measurement (mm) and a summary against ISO 20685-1's limits. Reads ../shared/data; exits 0
// with a note when it is absent.
#include "core/anchors.h"
#include "evaluate/decimated_target.h"
#include "io/anchor_reader.h"
#include "io/measurement_reader.h"
#include "io/mesh_loader.h"
#include "map/pair_mapping.h"
#include "measure/body_measurements.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace xparam;

namespace {

// ISO 20685-1's allowed error of a scan-derived measurement, mm: large girths 9, small girths
// and heights 4, segment lengths 5.
double iso_limit(const std::string& name) {
  static const std::map<std::string, double> limits = {
      {"stature", 4},       {"neck_girth", 4},      {"chest_girth", 9},        {"waist_girth", 9},
      {"hip_girth", 9},     {"thigh_girth", 9},     {"calf_girth", 4},         {"upper_arm_girth", 4},
      {"arm_length", 5},    {"inside_leg_height", 4}, {"shoulder_width", 5}};
  const auto it = limits.find(name);
  return it == limits.end() ? NAN : it->second;
}

Eigen::MatrixX3d vertex_rows(const Mesh& mesh) {
  Eigen::MatrixX3d rows(static_cast<Eigen::Index>(mesh.n_vertices()), 3);
  for (const VertexHandle v : mesh.vertices()) rows.row(v.idx()) = position(mesh, v).transpose();
  return rows;
}

// The template's landmarks: the 41 of human.anchors.json, or the 73 CAESAR landmarks (SMPL vertices).
AnchorSet template_landmarks(const std::string& which, const fs::path& source, const fs::path& data) {
  if (which == "human") return read_anchors(source / "tests/data/human.anchors.json");
  const fs::path file = data / "faust_landmarks/smpl_caesar_landmark_indices.json";
  std::ifstream in(file);
  const nlohmann::ordered_json table = nlohmann::ordered_json::parse(in);
  AnchorSet set{file.string(), {}};
  for (const auto& [name, id] : table.items()) set.anchors.push_back({name, AnchorVertex{id.get<int>()}, file.string(), 0});
  return set;
}

}  // namespace

int main(int argc, char** argv) try {
  const fs::path source = XPARAM_SOURCE_DIR;
  const fs::path data = source / ".." / "shared" / "data";
  if (!fs::exists(data / "faust_registrations")) {
    std::printf("no ../shared/data/faust_registrations beside the checkout: nothing to measure\n");
    return 0;
  }
  std::string landmarks = "human";
  int vertices = 6000;
  std::vector<std::string> subjects;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--landmarks" && i + 1 < argc) landmarks = argv[++i];
    else if (arg == "--vertices" && i + 1 < argc) vertices = std::stoi(argv[++i]);
    else subjects.push_back(arg);
  }
  if (subjects.empty()) subjects = {"tr_reg_010", "tr_reg_020", "tr_reg_030", "tr_reg_040", "tr_reg_080", "tr_reg_090"};

  const LoadedMesh smpl = load_mesh(source / "tests/data/human_man.obj");
  const AnchorSet template_anchors = template_landmarks(landmarks, source, data);
  MeasurementTemplate on{{}, {}, vertex_rows(smpl.mesh)};
  for (const AnchorSpec& a : template_anchors.anchors) {
    on.anchor_names.push_back(a.name);
    on.anchor_vertices.push_back(std::get<AnchorVertex>(a.location).index);
  }
  const MeasurementSet set = read_measurements(source / "tests/data/human.measurements.json", on);
  const fs::path work = fs::temp_directory_path() / "xparam_measure_accuracy";
  fs::create_directories(work);

  std::map<std::string, std::vector<double>> errors;  // mm, per measurement
  std::printf("target,measurement,registration_mm,through_map_mm,error_mm,iso_limit_mm\n");
  for (const std::string& subject : subjects) {
    const LoadedMesh registration = load_mesh(data / "faust_registrations" / (subject + ".ply"));
    const std::vector<double> truth = measure_surface(set, registration.mesh, vertex_rows(registration.mesh));
    const LoadedMesh target = evaluate::write_and_load_genus0(evaluate::decimate(registration.mesh, vertices),
                                                             work / (subject + "_" + std::to_string(vertices) + ".obj"));
    AnchorSet target_anchors{subject, {}};
    for (std::size_t a = 0; a < on.anchor_names.size(); ++a)
      target_anchors.anchors.push_back({on.anchor_names[a],
                                        AnchorPosition{position(registration.mesh, VertexHandle(on.anchor_vertices[a]))},
                                        subject, 0});
    const PairMapping map = map_pair(smpl.mesh, template_anchors, target.mesh, target_anchors, {});
    const std::vector<double> through = measure_surface(set, target.mesh, map.remesh_vertices);
    std::fprintf(stderr, "%s: E_L2 %.3f, strict folds %d, %.1f s\n", subject.c_str(), map.distortion.all.e_l2,
                 map.quality.strictly_folded_faces, map.seconds.total);
    for (std::size_t m = 0; m < set.measurements.size(); ++m) {
      const std::string& name = set.measurements[m].name;
      const double error = 1000.0 * (through[m] - truth[m]);
      errors[name].push_back(error);
      std::printf("%s,%s,%.1f,%.1f,%+.1f,%.0f\n", subject.c_str(), name.c_str(), 1000.0 * truth[m],
                  1000.0 * through[m], error, iso_limit(name));
    }
    std::fflush(stdout);
  }
  std::printf("\nmeasurement | ISO 20685-1 limit (mm) | mean |error| (mm) | max |error| (mm) | within the limit\n");
  for (const MeasurementDefinition& m : set.measurements) {
    const std::vector<double>& e = errors[m.name];
    double mean = 0.0, worst = 0.0;
    int within = 0;
    for (const double x : e) {
      mean += std::abs(x) / static_cast<double>(e.size());
      worst = std::max(worst, std::abs(x));
      within += std::abs(x) <= iso_limit(m.name);
    }
    std::printf("%s | %.0f | %.1f | %.1f | %d of %zu\n", m.name.c_str(), iso_limit(m.name), mean, worst, within,
                e.size());
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "xparam_measure_accuracy: %s\n", e.what());
  return 1;
}
