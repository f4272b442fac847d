// Real pairs from ../shared/data (skipped when it is absent): FAUST registrations of other poses
// and subjects against tr_reg_000 with the 73 CAESAR landmarks. They share the SMPL vertex order,
// so template vertex i belongs at target vertex i: the remesh has no folded face, covers the
// target's area to 2%, and lands near the truth. Then TOSCA's horse, and a SHREC'19 shape of its
// own connectivity against the SMPL template.
#include "intake/scan_loader.h"
#include "io/anchor_reader.h"
#include "io/mesh_loader.h"
#include "io/mesh_writer.h"
#include "map/decimation.h"
#include "map/identity_truth.h"
#include "map/pair_mapping.h"
#include "support/test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <variant>

namespace xparam {
namespace {

// The layout's tree as Kraevoy and Sheffer's greedy alone builds it
// (ConsistentLayoutSettings::unambiguous_tree_first, tree_corridor and diagonal_corridor off): the
// maps it makes on these pairs fold or squeeze where the retries and the tip anchors tested here
// repair them; the default layout leaves them nothing to repair.
void use_the_earlier_tree(PairSettings& settings) {
  settings.layout.unambiguous_tree_first = false;
  settings.layout.tree_corridor = false;
  settings.layout.diagonal_corridor = false;
}

// FAUST tr_reg_000 and another registration, which share SMPL's vertex order (template vertex i
// belongs at target vertex i), with the 73 CAESAR landmarks at the same vertex ids on both.
struct FaustMeshes {
  LoadedMesh source;
  LoadedMesh target;
  AnchorSet anchors;
};

FaustMeshes load_faust_pair(const std::filesystem::path& data, const std::string& target) {
  return {load_mesh(data / "faust_registrations/tr_reg_000.ply"),
          load_mesh(data / ("faust_registrations/" + target + ".ply")),
          read_anchors(data / "faust_landmarks/smpl_caesar_landmark_indices.json")};
}

struct FaustCase {
  std::string target;
  double gt_error_bound;  // mean distance to the truth over the diagonal; measured in the comment
};

class FaustPairs : public ::testing::TestWithParam<FaustCase> {};

TEST_P(FaustPairs, NoFoldedFaceAreaWithinTwoPercentNearTheTruth) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const auto [source, target, anchors] = load_faust_pair(data, GetParam().target);
  ASSERT_EQ(anchors.anchors.size(), 73u);
  const PairMapping map = map_pair(source.mesh, anchors, target.mesh, anchors, {});

  EXPECT_EQ(map.inverted_triangles[0], 0);
  EXPECT_EQ(map.inverted_triangles[1], 0);
  EXPECT_GE(map.untangling.flipped_before, 1);  // Gamma alone folds some: untangling is tested here
  EXPECT_TRUE(map.quality.flipped_faces.empty()) << map.quality.flipped_faces.size() << " folded";
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);
  EXPECT_LT(test::distance_to_identity_truth(map, target.mesh).mean, GetParam().gt_error_bound);
}

// Measured (xparam_evaluate, Balanced + merging): gt error 0.0042, 0.0047, 0.0034; folded faces
// before untangling 16, 36, 25; area ratio 0.985, 0.981, 0.984. The bounds leave room for
// changes of the optimization, not for a wrong map (a vertex off by one ring is about 0.4%).
INSTANTIATE_TEST_SUITE_P(CaesarLandmarks, FaustPairs,
                         ::testing::Values(FaustCase{"tr_reg_001", 0.006}, FaustCase{"tr_reg_010", 0.006},
                                           FaustCase{"tr_reg_090", 0.005}),
                         [](const ::testing::TestParamInfo<FaustCase>& pair) { return pair.param.target; });

// FAUST 090 against 000 with the 73 CAESAR landmarks: the first map already carries each fingertip
// and toe without a landmark to its partner within the tip reach on both meshes. Asked not to make
// such a round, the pair makes none. Pulling alone (whole_map_up_to 0), the round pulls the map
// onto those tips: no second map, every tip's image within its slack of its partner, and a map
// less stretched than without them. By default this small target also makes the whole map through
// them and keeps the better: the pulled one here (measured E_L2 1.0074 without tips, 1.0067 pulled
// onto them, 1.0069 through them: 0.68 s against 0.88 s for the pair).
TEST(FaustPair, ARoundOfTipsTheMapAlreadyCarriesPullsTheMapOntoThem) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const auto [source, target, anchors] = load_faust_pair(data, "tr_reg_090");
  const PairSettings defaults;
  PairSettings pulling = defaults;
  pulling.whole_map_up_to = 0;
  PairSettings mapping = defaults;
  mapping.pull_carried_tips = false;
  PairSettings skipping = defaults;
  skipping.map_carried_tips = false;
  PairSettings without_tips = skipping;
  without_tips.extremity_anchors = false;
  const PairMapping skipped = map_pair(source.mesh, anchors, target.mesh, anchors, {}, skipping);
  const PairMapping pulled = map_pair(source.mesh, anchors, target.mesh, anchors, {}, pulling);
  const PairMapping mapped = map_pair(source.mesh, anchors, target.mesh, anchors, {}, mapping);
  const PairMapping both = map_pair(source.mesh, anchors, target.mesh, anchors, {}, defaults);
  const PairMapping plain = map_pair(source.mesh, anchors, target.mesh, anchors, {}, without_tips);

  EXPECT_EQ(skipped.maps_made, 1);
  EXPECT_TRUE(skipped.extremity_anchors.empty());
  EXPECT_EQ(skipped.distortion.all.e_l2, plain.distortion.all.e_l2);

  EXPECT_EQ(pulled.maps_made, 1);
  ASSERT_FALSE(pulled.extremity_anchors.empty());  // measured 12
  EXPECT_EQ(pulled.pulled_tips, static_cast<int>(pulled.extremity_anchors.size()));
  EXPECT_EQ(pulled.anchors[0].anchors.size(), anchors.anchors.size());  // no layout through them
  EXPECT_LT(pulled.distortion.all.e_l2, skipped.distortion.all.e_l2);
  EXPECT_EQ(pulled.quality.strictly_folded_faces, 0);
  const double slack = 0.5 * pulled.settings.tip_reach * std::sqrt(surface_area(target.mesh));
  for (const ExtremityAnchor& tip : pulled.extremity_anchors) {
    EXPECT_TRUE(tip.carried_within(pulled.settings.tip_reach));
    const int on_template = std::get<AnchorVertex>(tip.specs[0].location).index;
    const int on_target = std::get<AnchorVertex>(tip.specs[1].location).index;
    EXPECT_LE((pulled.remesh_vertices.row(on_template).transpose() -
               position(target.mesh, target.mesh.vertex_handle(on_target)))
                  .norm(),
              slack * (1.0 + 1e-9))
        << tip.specs[0].name;
  }

  EXPECT_GE(mapped.maps_made, 2);
  EXPECT_EQ(mapped.pulled_tips, 0);
  EXPECT_FALSE(mapped.extremity_anchors.empty());

  // Both made; the pulled map is less stretched and kept.
  EXPECT_LT(pulled.distortion.all.e_l2, mapped.distortion.all.e_l2);
  EXPECT_EQ(both.maps_made, mapped.maps_made);
  EXPECT_EQ(both.pulled_tips, pulled.pulled_tips);
  EXPECT_EQ(both.distortion.all.e_l2, pulled.distortion.all.e_l2);
}

// FAUST tr_reg_000, another subject's registration (`original`: its vertex i is template vertex i's
// true image) and that registration decimated to 6000 vertices, the target (another connectivity),
// as the evaluation maps them.
struct DecimatedFaustPair {
  LoadedMesh source;
  LoadedMesh original;
  LoadedMesh target;
};

DecimatedFaustPair load_decimated_faust_pair(const std::filesystem::path& data, const std::string& subject) {
  const std::filesystem::path registrations = data / "faust_registrations";
  LoadedMesh original = load_mesh(registrations / (subject + ".ply"));
  const std::filesystem::path file = test::fresh_temp_dir("decimated_" + subject) / (subject + "_6000.obj");
  write_obj(file, decimate(original.mesh, 6000).mesh);
  return {load_mesh(registrations / "tr_reg_000.ply"), std::move(original), load_mesh(file)};
}

// map_pair of FAUST 000 onto the decimated target with the 29 anthropometric landmarks, the target's
// placed at the registration's points, as the evaluation maps it.
PairMapping map_with_anthropometric_landmarks(const std::filesystem::path& data,
                                              const DecimatedFaustPair& pair, const PairSettings& settings) {
  const AnchorSet landmarks = read_anchors(data / "faust_landmarks/smpl_anthropometry_landmark_indices.json");
  AnchorSet on_target = landmarks;
  for (AnchorSpec& anchor : on_target.anchors)
    anchor.location = AnchorPosition{
        position(pair.original.mesh, VertexHandle(std::get<AnchorVertex>(anchor.location).index))};
  return map_pair(pair.source.mesh, landmarks, pair.target.mesh, on_target, {}, settings);
}

// Mean distance of the remesh from the truth over the template vertices within `radius` of
// `centre` (every vertex by default), as a fraction of sqrt(target area).
double truth_error(const PairMapping& map, const DecimatedFaustPair& pair,
                   const Eigen::Vector3d& centre = Eigen::Vector3d::Zero(),
                   double radius = std::numeric_limits<double>::infinity()) {
  double sum = 0.0;
  int n = 0;
  for (VertexHandle v : pair.source.mesh.vertices()) {
    if ((position(pair.source.mesh, v) - centre).norm() > radius) continue;
    sum += (map.remesh_vertices.row(v.idx()).transpose() - position(pair.original.mesh, v)).norm();
    ++n;
  }
  return sum / n / std::sqrt(surface_area(pair.target.mesh));
}

// FAUST 010 decimated to 6000 vertices (another connectivity) against 000, with the 29
// anthropometric landmarks, as the evaluation maps it (the target's landmarks are the registration's
// points). The first map squeezes the left hand, and one of its fingertips was matched through it
// with the tip of another finger, 16 cm from its own; the map through that tip beat the first
// (E_L2 2.00 -> 1.11) and wound the template's fingers on the back of the target's hand (looked
// at), and only the map made again without it mended the hand (retry_doubtful_tips). No pair is
// taken through a cell the map squeezes now (outside_squeezed_cells), and without any retry every
// tip lies within 5 cm of its true image (measured: E_L2 1.029, mean distance to the truth 0.61% of
// sqrt(area), as the retry made it; 1.40% through the wrong tip).
TEST(FaustPair, NoFingertipIsPairedThroughTheSqueezedHand) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const DecimatedFaustPair pair = load_decimated_faust_pair(data, "tr_reg_010");
  const auto& [source, original, target] = pair;
  PairSettings without_retries;
  without_retries.retry_doubtful_tips = false;
  const PairMapping map = map_with_anthropometric_landmarks(data, pair, without_retries);

  // How far the farthest tip's target point lies from its template tip's true image.
  double worst_tip = 0.0;
  for (const ExtremityAnchor& tip : map.extremity_anchors) {
    const int on_template = std::get<AnchorVertex>(tip.specs[0].location).index;
    const int on_target_mesh = std::get<AnchorVertex>(tip.specs[1].location).index;
    worst_tip = std::max(worst_tip, (position(target.mesh, VertexHandle(on_target_mesh)) -
                                     position(original.mesh, VertexHandle(on_template)))
                                        .norm());
  }
  EXPECT_FALSE(map.extremity_anchors.empty());
  EXPECT_LT(worst_tip, 0.05);
  EXPECT_LT(truth_error(map, pair), 0.008);
  EXPECT_LT(map.distortion.all.e_l2, 1.05);
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
}

// FAUST 010 decimated as above, with the 29 anthropometric landmarks: the first map turns the left
// forefoot by a toe, and the round of tips pairs every template toe with the target's next one (the
// worse foot 1.08% of sqrt(area) from the truth, 1.5 cm; looked at: each toe on its neighbour's).
// The rows' rigid fits pair them rightly, and the map through those pairs replaces the round's
// (measured: the foot 0.07%, E_L2 1.0256 -> 1.0249, no fold).
TEST(FaustPair, RigidFitsOfTheToesPutTheLeftToesOnTheirOwn) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const DecimatedFaustPair pair = load_decimated_faust_pair(data, "tr_reg_010");
  PairSettings fitted;  // the default
  PairSettings aligned = fitted;
  aligned.fitted_tip_rows = false;
  const PairMapping with_fits = map_with_anthropometric_landmarks(data, pair, fitted);
  const PairMapping without = map_with_anthropometric_landmarks(data, pair, aligned);
  // The template's left forefoot: within 12 cm of a toe tip.
  const Eigen::Vector3d toe = position(pair.source.mesh, VertexHandle(3306));
  const auto forefoot_error = [&](const PairMapping& map) { return truth_error(map, pair, toe, 0.12); };
  EXPECT_GT(forefoot_error(without), 0.008);  // the case: toes one over
  EXPECT_LT(forefoot_error(with_fits), 0.002);
  EXPECT_EQ(with_fits.quality.strictly_folded_faces, 0);
  EXPECT_TRUE(with_fits.quality.flipped_faces.empty());
  EXPECT_LT(with_fits.distortion.all.e_l2, 1.03);
}

// FAUST 080 decimated to 6000 vertices against 000, with the 72 landmarks placed on the subjects'
// scans (noisy, no fingertip but the middle one's), each inside a template face. Until session 42
// those were held where the centring left them, up to 8.7 mm off (Rt. Axilla Post.), every round of
// tips lost, and only helper anchors behind the losing map's tips opened the left hand (3.1 mm off
// the truth, 13.7 without them). Met now, a round of tips wins on its own: the left hand is right,
// the landmarks are met and nothing folds. The map through the landmarks alone folds, and since
// session 49 its later layouts and helpers wait for the tips, which win: 3 whole maps instead of 6
// (9.2 -> 3.6 s in the evaluation).
TEST(FaustPair, ScanLandmarksInsideFacesAreMetAndTheLeftHandIsRight) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const auto [source, original, target] = load_decimated_faust_pair(data, "tr_reg_080");
  const std::filesystem::path scans = data / "faust_landmarks/scan_landmarks";
  const AnchorSet on_source = read_anchors(scans / "tr_scan_000_landmarks.json");
  const AnchorSet on_target = read_anchors(scans / "tr_scan_080_landmarks.json");
  ASSERT_EQ(on_source.anchors.size(), 72u);
  const PairMapping map = map_pair(source.mesh, on_source, target.mesh, on_target, {}, PairSettings{});
  PairSettings landmarks_alone;
  landmarks_alone.retry_keeping_corners = false;
  landmarks_alone.tip_anchors = false;
  landmarks_alone.extremity_anchors = false;
  const PairMapping first = map_pair(source.mesh, on_source, target.mesh, on_target, {}, landmarks_alone);
  EXPECT_GE(first.quality.flipped_faces.size(), 1u);  // measured 3, at the right elbow
  // The first map, the first round of tips's, and the second round's beside its pull (a small target).
  EXPECT_LE(map.maps_made, 3);

  // The left hand: template vertices within 12 cm of the middle of its knuckles' landmarks.
  Eigen::Vector3d knuckles = Eigen::Vector3d::Zero();
  for (const AnchorSpec& anchor : on_source.anchors)
    if (anchor.name == "Lt. Metacarpal Phal. II" || anchor.name == "Lt. Metacarpal Phal. V")
      knuckles += 0.5 * std::get<AnchorPosition>(anchor.location).point;
  double sum = 0.0;
  int count = 0;
  for (VertexHandle v : source.mesh.vertices()) {
    if ((position(source.mesh, v) - knuckles).norm() > 0.12) continue;
    sum += (map.remesh_vertices.row(v.idx()).transpose() - position(original.mesh, v)).norm();
    ++count;
  }
  EXPECT_FALSE(map.extremity_anchors.empty());
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
  EXPECT_LT(map.distortion.all.e_l2, 1.05);  // measured 1.034
  EXPECT_LT(sum / count, 0.002);             // measured 1.2 mm
  // From the target's point nearest the remesh's: 63 of 72 within a micrometre (measured; 8.7 mm
  // worst in session 41), the worst 2.2 mm off (Rt. Dactylion, where the fingertip bends sharply under
  // its face; 3.0 mm for Lt. Dactylion before the last centring onto the nearest point).
  ASSERT_EQ(map.anchor_miss.size(), map.anchors[0].anchors.size());
  int met = 0;
  for (std::size_t k = 0; k < on_source.anchors.size(); ++k) {
    EXPECT_LT(map.anchor_miss[k], 0.0025) << map.anchors[0].anchors[k].name;
    met += map.anchor_miss[k] < 1e-6;
  }
  EXPECT_GE(met, 60);
}

// Anchors "a0", "a1", ... at the vertex ids of a file, the first number of each line: a TOSCA
// correspondence file (.pid) or a landmark file of Schmidt et al. 2023 (one number a line).
AnchorSet indexed_anchors(const std::filesystem::path& file) {
  AnchorSet set;
  set.source = file.string();
  std::ifstream in(file);
  for (int id = 0; in >> id;) {
    std::string rest;
    std::getline(in, rest);
    set.anchors.push_back({"a" + std::to_string(set.anchors.size()), AnchorVertex{id}, set.source});
  }
  return set;
}

// TOSCA's horse against itself in another pose (same vertex order, the 21 anchors of
// corrs/horse.pid). Its tail and ears have no anchor: the mean-value parameterizations squeeze the
// tail's patch to a mean SD near 1e6, and before those were relaxed on their own the remesh lost
// 2.3% of the area (area ratio 0.977). Gluing across curves is exercised too: it must lower the
// relaxed energy against a run without it, and every piece must stay an embedding.
TEST(ToscaHorse, SqueezedTailIsCoveredAndGluingLowersTheEnergy) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const LoadedMesh source = load_mesh(data / "tosca/horse0.off");
  const LoadedMesh target = load_mesh(data / "tosca/horse5.off");
  const AnchorSet anchors = indexed_anchors(data / "tosca/corrs/horse.pid");
  ASSERT_EQ(anchors.anchors.size(), 21u);
  PairSettings glued;
  glued.extremity_anchors = false;  // the gluing's own effect, not the tip anchors'
  glued.tip_anchors = false;        // nor the helpers' behind tips (a squeezed map tries them last)
  const PairMapping map = map_pair(source.mesh, anchors, target.mesh, anchors, {}, glued);
  PairSettings unglued = glued;
  unglued.cross_map.gluing.enabled = false;
  const PairMapping without_gluing = map_pair(source.mesh, anchors, target.mesh, anchors, {}, unglued);

  EXPECT_EQ(map.inverted_triangles[0], 0);
  EXPECT_EQ(map.inverted_triangles[1], 0);
  EXPECT_GE(map.relaxation.parameterizations[0], 1);
  EXPECT_GE(map.relaxation.parameterizations[1], 1);
  EXPECT_TRUE(map.quality.flipped_faces.empty()) << map.quality.flipped_faces.size() << " folded";
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);                             // measured 0.991
  EXPECT_LT(test::distance_to_identity_truth(map, target.mesh).mean, 0.009);  // measured 0.0074
  EXPECT_GE(map.relaxation.glued_charts, 1);
  EXPECT_EQ(without_gluing.relaxation.glued_charts, 0);
  EXPECT_LT(map.relaxation.energy_after, without_gluing.relaxation.energy_after);
  EXPECT_LT(map.distortion.all.e_l2, without_gluing.distortion.all.e_l2);  // measured 1.077 against 1.254
}

// The vertex ids of a file with one integer per line.
std::vector<int> read_vertex_ids(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<int> ids;
  for (int id = 0; in >> id;) ids.push_back(id);
  return ids;
}

// TOSCA's horse against its wolf (21 landmarks each, no ground truth). On the first layout one
// remesh face folds over the wolf's ear; the second layout, corners kept at the anchors near it,
// has none and covers the target's area to 2%.
TEST(ToscaHorseWolf, SecondLayoutUnfoldsTheEar) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const LoadedMesh source = load_mesh(data / "tosca/horse0.off");
  const LoadedMesh target = load_mesh(data / "tosca/wolf0.off");
  const AnchorSet source_anchors = indexed_anchors(data / "tosca/corrs/horse.pid");
  const AnchorSet target_anchors = indexed_anchors(data / "tosca/corrs/wolf.pid");
  PairSettings without_helpers;
  use_the_earlier_tree(without_helpers);  // the layout whose map the retries repair
  without_helpers.tip_anchors = false;
  without_helpers.extremity_anchors = false;
  without_helpers.optimize_map = false;  // the later layouts' own effect, not the optimizer's
  PairSettings first_layout_only = without_helpers;
  first_layout_only.retry_keeping_corners = false;
  const PairMapping first =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, first_layout_only);
  const PairMapping map =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, without_helpers);

  EXPECT_GE(first.quality.flipped_faces.size(), 1u);  // measured 1
  EXPECT_EQ(map.layouts_built, 2);                    // the second one has no fold: no third is built
  EXPECT_EQ(map.layout_kept, 2);
  EXPECT_TRUE(map.optimization.settings.stretching.keep_corners);
  EXPECT_TRUE(map.quality.flipped_faces.empty()) << map.quality.flipped_faces.size() << " folded";
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);  // measured 0.986
  EXPECT_EQ(map.inverted_triangles[0], 0);
  EXPECT_EQ(map.inverted_triangles[1], 0);
}

// A SHREC'19 shape against the SMPL template (shape 44): the meshes, the shape's registration
// to SMPL (`truth[i]`: the shape's vertex of SMPL vertex i, also the ground truth), and the
// CAESAR landmarks on SMPL and, carried by the registration, on the shape. A landmark the
// registration puts on the vertex of an earlier one is left out.
struct ShrecPair {
  LoadedMesh source;
  LoadedMesh target;
  std::vector<int> truth;
  AnchorSet source_anchors;
  AnchorSet target_anchors;
};

// With `intake`, the target is taken through the scan intake as `xparam pair` takes it, and the
// truth and the anchors are renumbered as the intake numbers what it keeps.
ShrecPair load_shrec_pair(const std::filesystem::path& data, const std::string& shape,
                          const std::string& landmarks_file = "smpl_caesar_landmark_indices.json",
                          bool intake = false) {
  const std::filesystem::path dir = data / "shrec19_connectivity";
  ShrecPair pair{load_mesh(dir / "44.off"), {}, read_vertex_ids(dir / (shape + ".smpl_matches.txt")), {}, {}};
  const AnchorSet landmarks = read_anchors(data / "faust_landmarks" / landmarks_file);
  pair.source_anchors.source = landmarks.source;
  pair.target_anchors.source = landmarks.source;
  std::set<int> taken;
  for (const AnchorSpec& anchor : landmarks.anchors) {
    const int on_target = pair.truth.at(std::get<AnchorVertex>(anchor.location).index);
    if (!taken.insert(on_target).second) continue;
    pair.source_anchors.anchors.push_back(anchor);
    pair.target_anchors.anchors.push_back(anchor);
    pair.target_anchors.anchors.back().location = AnchorVertex{on_target};
  }
  if (!intake) {
    pair.target = load_mesh(dir / (shape + ".off"));
    return pair;
  }
  pair.target = load_scan(dir / (shape + ".off"), pair.target_anchors, IntakeSettings{});
  const FileOrder& order = pair.target.file_order;
  for (int& vertex : pair.truth) vertex = order.mesh_vertex(vertex);
  for (AnchorSpec& anchor : pair.target_anchors.anchors) {
    int& vertex = std::get<AnchorVertex>(anchor.location).index;
    vertex = order.mesh_vertex(vertex);
  }
  return pair;
}

// The mean distance from the truth of the template vertices whose position is in `region`.
double region_error(const ShrecPair& shrec, const PairMapping& map,
                    const std::function<bool(const Eigen::Vector3d&)>& region) {
  double sum = 0.0;
  int count = 0;
  for (VertexHandle v : shrec.source.mesh.vertices()) {
    if (!region(position(shrec.source.mesh, v))) continue;
    sum += test::truth_miss(map, shrec.target.mesh, shrec.truth, v.idx());
    ++count;
  }
  EXPECT_GT(count, 100) << "the region holds too few template vertices to judge";
  return sum / count;
}

// Whether a point of the SMPL template lies on a hand, beyond its wrist: x > 0.72 for the left hand
// (side +1), x < -0.72 for the right (side -1).
bool on_hand(const Eigen::Vector3d& p, double side) { return side * p.x() > 0.72; }

// The mean distance from the truth of a hand's template vertices (on_hand).
double hand_error(const ShrecPair& shrec, const PairMapping& map, double side) {
  return region_error(shrec, map, [side](const Eigen::Vector3d& p) { return on_hand(p, side); });
}

// Whether a tip's template vertex lies on a hand (on_hand).
bool tip_on_hand(const ShrecPair& shrec, const ExtremityAnchor& tip, double side) {
  const int on_template = std::get<AnchorVertex>(tip.specs[0].location).index;
  return on_hand(position(shrec.source.mesh, VertexHandle(on_template)), side);
}

// How far a tip's target point lies from its template tip's true image, target units.
double tip_off_truth(const ShrecPair& shrec, const ExtremityAnchor& tip) {
  const int on_template = std::get<AnchorVertex>(tip.specs[0].location).index;
  const int on_target = std::get<AnchorVertex>(tip.specs[1].location).index;
  return (position(shrec.target.mesh, VertexHandle(on_target)) -
          position(shrec.target.mesh, VertexHandle(shrec.truth[on_template])))
      .norm();
}

// Expects each of a hand's tips to lie on its own finger: its target point nearer the true image of
// its own template tip than of any other tip of the hand. Returns the hand's tips.
std::vector<const ExtremityAnchor*> expect_tips_on_their_own_fingers(const ShrecPair& shrec,
                                                                     const PairMapping& map, double side) {
  std::vector<const ExtremityAnchor*> tips;
  for (const ExtremityAnchor& tip : map.extremity_anchors) {
    if (tip_on_hand(shrec, tip, side)) tips.push_back(&tip);
  }
  for (const ExtremityAnchor* tip : tips) {
    const Eigen::Vector3d on_target =
        position(shrec.target.mesh, VertexHandle(std::get<AnchorVertex>(tip->specs[1].location).index));
    for (const ExtremityAnchor* other : tips) {
      if (other == tip) continue;
      const int other_truth = shrec.truth[std::get<AnchorVertex>(other->specs[0].location).index];
      EXPECT_LT(tip_off_truth(shrec, *tip),
                (on_target - position(shrec.target.mesh, VertexHandle(other_truth))).norm())
          << tip->specs[0].name << " lies nearer " << other->specs[0].name << "'s truth";
    }
  }
  return tips;
}

// SHREC'19 shape 1 with the 29 anthropometric landmarks on one layout: the layout's map squeezes
// the unanchored hands and feet (E_L2 254) and folds 2 faces by the strict count; optimized on
// the target it stretches little (E_L2 measured 1.84), folds no more by either count, keeps the
// area and the anchors, and lands nearer the truth.
TEST(ShrecHuman, OptimizingTheMapUnsqueezesTheHand) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "1", "smpl_anthropometry_landmark_indices.json");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  PairSettings layout_map;
  layout_map.retry_keeping_corners = false;
  layout_map.tip_anchors = false;
  layout_map.optimize_map = false;
  layout_map.extremity_anchors = false;  // the optimizer's own effect, not the tip anchors'
  // The diagonals traced without the corridor: with it the layout's own map has no strict fold
  // here for the optimizer to remove.
  layout_map.layout.diagonal_corridor = false;
  PairSettings optimized = layout_map;
  optimized.optimize_map = true;
  const PairMapping before = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, layout_map);
  const PairMapping after = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, optimized);

  EXPECT_GT(before.distortion.all.e_l2, 10.0);  // measured 254
  EXPECT_LT(after.distortion.all.e_l2, 2.5);    // measured 1.84
  EXPECT_LE(after.quality.flipped_faces.size(), before.quality.flipped_faces.size());
  EXPECT_LT(after.quality.strictly_folded_faces, before.quality.strictly_folded_faces);
  EXPECT_NEAR(after.quality.area_ratio, 1.0, 0.02);
  EXPECT_LT(test::distance_to_truth(after, target.mesh, truth).mean,
            test::distance_to_truth(before, target.mesh, truth).mean);
  EXPECT_LT(after.map_optimization.energy_after, after.map_optimization.energy_before);
  for (double miss : after.anchor_miss) EXPECT_LT(miss, 1e-12);
}

// SHREC'19 shape 26 with the 73 CAESAR landmarks, none on the top of the head: traced on its own,
// the target's diagonal from Sellion to Nuchale passed round the left of the head where the
// template's passed round the right, and the map squeezed the template's crown into a band from
// the eye to the back of the head (E_L2 1.37, a strictly folded face at the left ear; looked at).
// Traced in the corridor about the template's, the map lies on the head as it should.
TEST(ShrecHuman, DiagonalsTracedInACorridorKeepTheCrownOnTheCrown) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "26");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  PairSettings own_way;
  own_way.layout.diagonal_corridor = false;
  const PairMapping squeezed =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, own_way);
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {});
  EXPECT_GT(squeezed.distortion.all.e_l2, 1.3);  // measured 1.37
  EXPECT_LT(map.distortion.all.e_l2, 1.2);       // measured 1.11
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_LT(test::distance_to_truth(map, target.mesh, truth).mean,
            test::distance_to_truth(squeezed, target.mesh, truth).mean);
}

// SHREC'19 shape 41 (FAUST tr_reg_068 in its own numbering) with the 29 anthropometric landmarks,
// which stop at the wrists: the map squeezes each template finger into a rosette on the target's
// palm. Through helper anchors at the fingertips matched through that map, every template tip
// lands on its own finger of the target (its true image, by the registration, nearby), and the
// map is less stretched, folds no more and lands nearer the truth.
TEST(ShrecHuman, TipAnchorsPutTheFingersOnTheTargetsFingers) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "41", "smpl_anthropometry_landmark_indices.json");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  PairSettings with_tips;
  use_the_earlier_tree(with_tips);  // the layout whose map the retries repair
  PairSettings without_tips = with_tips;
  without_tips.extremity_anchors = false;
  const PairMapping squeezed = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, without_tips);
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, with_tips);

  ASSERT_GE(map.extremity_anchors.size(), 8u);  // measured 12: ten fingertips and two toes
  const auto miss = [&](const PairMapping& mapping, int v) { return test::truth_miss(mapping, target.mesh, truth, v); };
  // Template tips within 2 cm of their true image (on their own finger), with and without.
  int on_finger = 0;
  int on_finger_without = 0;
  for (const ExtremityAnchor& tip : map.extremity_anchors) {
    const int v = std::get<AnchorVertex>(tip.specs[0].location).index;
    on_finger += miss(map, v) < 0.02;
    on_finger_without += miss(squeezed, v) < 0.02;
  }
  // Measured 13 of 16 (every fingertip; toes, shallow on the template, may be matched to another
  // toe) against 6 without the tip anchors.
  EXPECT_GE(on_finger, 10);
  EXPECT_GE(on_finger - on_finger_without, 5)
      << on_finger << " with, " << on_finger_without << " without, of " << map.extremity_anchors.size();
  EXPECT_LT(map.distortion.all.e_l2, squeezed.distortion.all.e_l2);
  EXPECT_LE(map.quality.strictly_folded_faces, squeezed.quality.strictly_folded_faces);
  EXPECT_LE(map.quality.flipped_faces.size(), squeezed.quality.flipped_faces.size());
  EXPECT_LT(test::distance_to_truth(map, target.mesh, truth).mean,
            test::distance_to_truth(squeezed, target.mesh, truth).mean);
}

// SHREC'19 shape 18 with the 29 anthropometric landmarks: the first map draws the template's
// whole left hand into the target's wrist (every template vertex beyond the wrist within a few
// centimetres of it), so no fingertip pair is near through it; the wrist landmark's cell matches
// the middle fingertip with the end of the target's mitten-like hand, and the map through it
// covers the hand: measured E_L2 8592 -> 1.06, the hand's mean distance to the truth 12.5 cm ->
// 3 cm. Its last strict fold is opened by a corner moved across the folded face's far side (it
// stayed when corners only moved towards their neighbours' centroid).
TEST(ShrecHuman, TheWristsCellPullsTheSqueezedHandOut) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "18", "smpl_anthropometry_landmark_indices.json");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  PairSettings with_tips;
  with_tips.max_maps = 2;  // the first map and the one through the tips
  PairSettings without_tips = with_tips;
  without_tips.extremity_anchors = false;
  without_tips.tip_anchors = false;  // the first map itself (helpers behind tips would unsqueeze it too)
  const PairMapping squeezed = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, without_tips);
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, with_tips);

  constexpr double kLeft = 1.0;
  EXPECT_GT(squeezed.distortion.all.e_l2, 100.0);      // measured 8592
  EXPECT_LT(map.distortion.all.e_l2, 1.3);             // measured 1.06
  EXPECT_GT(hand_error(shrec, squeezed, kLeft), 0.08);  // measured 0.125 m
  EXPECT_LT(hand_error(shrec, map, kLeft), 0.05);
  EXPECT_FALSE(map.extremity_anchors.empty());
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.03);
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_LT(test::distance_to_truth(map, target.mesh, truth).mean,
            test::distance_to_truth(squeezed, target.mesh, truth).mean);
}

// SHREC'19 shape 18 with the 29 anthropometric landmarks: the first round of tips pulls the left
// hand out of the wrist by one fingertip (the map with the cell's rival tip: see the test below), and
// the thumb stays squeezed towards the palm; a second round matches the thumb through that map and
// maps again through it too, with the other fingers. Measured: tips 7 -> 13, E_L2 1.032 -> 1.026,
// the template's left thumb tip paired with the target's, the mirror image of the right thumb's
// partner (the target is left-right symmetric), and no target vertex left farther than the coverage
// gap (1 before). (The registration's ground truth is not asserted on that hand: it pairs the
// template's middle fingertip with the target's index one.)
TEST(ShrecHuman, ASecondRoundOfTipsFindsTheThumb) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "18", "smpl_anthropometry_landmark_indices.json");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  PairSettings two_rounds;
  // The default budget: the first map; the first round, its rival by cell and the map without its
  // doubtful tip (1.88 reaches off, losing); the second round and its map without a doubtful tip
  // (1.56 reaches, losing).
  two_rounds.max_maps = 6;
  PairSettings one_round = two_rounds;
  one_round.tip_rounds = 1;
  const PairMapping first = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, one_round);
  const PairMapping second = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, two_rounds);
  // The target vertex paired with template vertex `on_template` by a tip, -1 when none is.
  const auto partner = [](const PairMapping& map, int on_template) {
    for (const ExtremityAnchor& tip : map.extremity_anchors)
      if (std::get<AnchorVertex>(tip.specs[0].location).index == on_template)
        return std::get<AnchorVertex>(tip.specs[1].location).index;
    return -1;
  };
  constexpr int kLeftThumb = 2745;  // SMPL's thumb tips
  constexpr int kRightThumb = 6207;
  EXPECT_EQ(partner(first, kLeftThumb), -1);
  EXPECT_GT(second.extremity_anchors.size(), first.extremity_anchors.size());
  const int left = partner(second, kLeftThumb);
  const int right = partner(second, kRightThumb);
  ASSERT_GE(left, 0);
  ASSERT_GE(right, 0);
  Eigen::Vector3d mirrored = position(target.mesh, VertexHandle(right));
  mirrored.x() = -mirrored.x();
  EXPECT_LT((position(target.mesh, VertexHandle(left)) - mirrored).norm(), 0.005);
  EXPECT_LE(second.coverage.uncovered_vertices, first.coverage.uncovered_vertices);
  EXPECT_LT(second.distortion.all.e_l2, first.distortion.all.e_l2);
  EXPECT_EQ(second.quality.strictly_folded_faces, 0);
}

// SHREC'19 shape 1 with the 29 anthropometric landmarks: the first round paired a left fingertip
// with a target tip 9 cm from its own (another finger's), through a first map that squeezes the
// left hand; the map through it won and kept 1 strictly folded face (E_L2 1.23), and the map made
// again without it replaced it. No pair is taken through that cell now, and every tip of the map
// lands within 8 cm of its true image (measured: E_L2 1.09, no fold). The left ring and little
// fingertips, matched by their distances, were crossed (the hand 2.4 cm from the truth); tried one
// over, each is on its own finger (looked at; E_L2 1.0945 -> 1.0921, the hand 1.7 cm).
TEST(ShrecHuman, EveryTipOfTheMapLiesOnItsOwnFinger) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "1", "smpl_anthropometry_landmark_indices.json");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  const PairMapping map =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, PairSettings{});
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_LT(map.distortion.all.e_l2, 1.15);
  EXPECT_FALSE(map.extremity_anchors.empty());
  for (const ExtremityAnchor& tip : map.extremity_anchors)
    EXPECT_LT(tip_off_truth(shrec, tip), 0.08) << tip.specs[0].name;
  constexpr double kLeft = 1.0;
  EXPECT_GE(expect_tips_on_their_own_fingers(shrec, map, kLeft).size(), 4u);
  EXPECT_LT(hand_error(shrec, map, kLeft), 0.02);
}

// SHREC'19 shape 18 (a left-right symmetric base mesh with closed fingers) with the 29
// anthropometric landmarks: the first map squeezes the left hand, whose first tip is matched through
// the wrist's cell, the farthest from the wrist on each mesh: the template's middle fingertip and
// the target's index one, whose middle fingertip lies nearly as far. Through that map the next round
// pairs the ring fingertip with the middle one; the template's index finger and thumb were left
// squeezed into whorls on the back of the target's hand (looked at). The map with the cell's other
// tip wins (E_L2 1.047 -> 1.032 in the first round, 1.040 -> 1.026 in the end), and the left hand is
// then matched as the right one is (through the map): each left fingertip's partner is the mirror
// image of its right twin's. The registration pairs the middle fingertip with the index one too,
// so its ground truth cannot tell.
TEST(ShrecHuman, AFingertipNearlyAsFarFromTheWristRivalsTheCellsMatch) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "18", "smpl_anthropometry_landmark_indices.json");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  PairSettings retrying;  // the default
  PairSettings keeping = retrying;
  keeping.retry_doubtful_tips = false;
  const PairMapping retried =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, retrying);
  const PairMapping kept = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, keeping);

  // SMPL's left fingertips and their right twins (thumb, index, middle, ring, little finger).
  const std::array<std::array<int, 2>, 5> twins = {
      {{2745, 6207}, {2319, 5782}, {2445, 5905}, {2546, 6007}, {2663, 6124}}};
  const auto partner = [](const PairMapping& map, int on_template) {
    for (const ExtremityAnchor& tip : map.extremity_anchors)
      if (std::get<AnchorVertex>(tip.specs[0].location).index == on_template)
        return std::get<AnchorVertex>(tip.specs[1].location).index;
    return -1;
  };
  // Left fingertips whose partner lies within 5 mm of the mirror image (x -> -x) of their twin's
  // (adjacent fingertips of that target lie 1.5 cm apart), and those farther.
  const auto mirrored = [&](const PairMapping& map) {
    std::array<int, 2> count{};
    for (const auto& [left, right] : twins) {
      const int a = partner(map, left);
      const int b = partner(map, right);
      if (a < 0 || b < 0) continue;
      Eigen::Vector3d image = position(target.mesh, VertexHandle(b));
      image.x() = -image.x();
      ++count[(position(target.mesh, VertexHandle(a)) - image).norm() <= 0.005 ? 0 : 1];
    }
    return count;
  };
  EXPECT_GE(mirrored(kept)[1], 1);  // the case: a left fingertip paired with another finger's
  EXPECT_EQ(mirrored(retried)[1], 0);
  EXPECT_GE(mirrored(retried)[0], 3);  // measured 3 (5 before session 46: the index and ring fingertips of
                                       // one hand are now left unpaired)
  ASSERT_FALSE(retried.doubtful_tips.empty());
  EXPECT_EQ(std::get<AnchorVertex>(retried.doubtful_tips.back().specs[0].location).index, 2445);
  EXPECT_LT(retried.distortion.all.e_l2, kept.distortion.all.e_l2);
  EXPECT_EQ(retried.quality.strictly_folded_faces, 0);
}

// SHREC'19 shape 21 (loose parts, dropped by the scan intake) with the 73 CAESAR landmarks, without
// the retries of doubtful tips: the second round's map through its 2 tips folds 1 face and loses to
// the first round's (E_L2 1.041 against 1.047, no fold). It folds, but a trial's later layouts are
// made only when its first layout wins, so the round costs one map and changes nothing. (Until
// session 46 the case was SHREC'19 1 with the 29 anthropometric landmarks, whose first round then
// kept a wrong fingertip; that round cost three maps, 7 s of the pair's 11, before the rule.)
TEST(ShrecHuman, ALosingRoundOfTipsMakesOneMap) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "21", "smpl_caesar_landmark_indices.json", true);
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  PairSettings two_rounds;
  two_rounds.retry_doubtful_tips = false;
  PairSettings one_round = two_rounds;
  one_round.tip_rounds = 1;
  const PairMapping first = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, one_round);
  const PairMapping second =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, two_rounds);
  EXPECT_EQ(second.maps_made, first.maps_made + 1);
  EXPECT_EQ(second.extremity_anchors.size(), first.extremity_anchors.size());
  EXPECT_EQ(second.distortion.all.e_l2, first.distortion.all.e_l2);
}

// SHREC'19 shape 41 (FAUST tr_reg_068) with the 29 anthropometric landmarks: the first map
// matches the thumb of the raised right hand but squeezes its four fingers into the palm, which
// long flat triangles then cover (E_L2 1.10). Their tips are matched by their distances to the
// thumb and the two wrist landmarks, and every one lands on its own finger.
TEST(ShrecHuman, FingersSqueezedIntoThePalmAreMatchedByTheirDistances) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "41", "smpl_anthropometry_landmark_indices.json");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, PairSettings{});
  int by_distances = 0;
  int on_finger = 0;
  for (const ExtremityAnchor& tip : map.extremity_anchors) {
    if (tip.matched_by != TipMatching::by_distances) continue;
    ++by_distances;
    on_finger += test::truth_miss(map, target.mesh, truth, std::get<AnchorVertex>(tip.specs[0].location).index) < 0.02;
  }
  // Measured: 8 tips matched by distances (the four fingers and four toes), 7 of them within 2 cm
  // of their true image (a toe is not); the hand's mean error 2.8 mm; E_L2 1.10 -> 1.02.
  EXPECT_GE(by_distances, 4);
  EXPECT_GE(on_finger, by_distances - 1);
  constexpr double kRight = -1.0;
  EXPECT_LT(hand_error(shrec, map, kRight), 0.01);
  EXPECT_LT(map.distortion.all.e_l2, 1.05);
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
}

// SHREC'19 shape 1 with the 29 anthropometric landmarks: the map without tips leaves 342 faces
// stretched over ten times the map's scale, most over the target's left hand (E_L2 1.68, the
// hand's mean error 8.9 cm); the map through the tips folds 4 faces by the strict count but pulls
// two fingers of that hand out (E_L2 1.23, 6.5 cm), and losing far fewer faces it replaces it.
TEST(ShrecHuman, AMapThroughTheTipsLosingFarFewerFacesReplacesOneThatFoldsLess) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "1", "smpl_anthropometry_landmark_indices.json");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, PairSettings{});
  constexpr double kLeft = 1.0;
  EXPECT_FALSE(map.extremity_anchors.empty());
  EXPECT_LT(map.distortion.all.e_l2, 1.35);        // measured 1.23 (1.68 without the tips)
  EXPECT_LT(hand_error(shrec, map, kLeft), 0.075);  // measured 0.065 (0.089)
  EXPECT_LE(map.quality.strictly_folded_faces, 5);  // measured 4 (0)
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);
}

// SHREC'19 shape 1 (SHREC'07 human 1, 4706 vertices of its own connectivity) against the SMPL
// template (shape 44) with the CAESAR landmarks, carried to shape 1 by its SMPL registration
// (which is also the truth; one landmark is left out, the registration puts it on the vertex of
// another). Straightened, the curves from the left Dactylion (a fingertip) to the knuckles run
// side by side down the template's middle finger, a corner of 0.3 degrees, while on shape 1's
// coarse hand they spread to 39: the map folds near the knuckles. The second layout, whose
// stretching leaves such curves as traced, has no fold.
TEST(ShrecHuman, CornersKeptOpenUnfoldTheHand) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "1");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  ASSERT_EQ(source_anchors.anchors.size(), 72u);
  PairSettings without_helpers;  // helpers behind the tips would unfold the first map already
  use_the_earlier_tree(without_helpers);  // the layout whose map the retries repair
  without_helpers.tip_anchors = false;
  without_helpers.optimize_map = false;  // and so would optimizing the map
  without_helpers.extremity_anchors = false;  // and mapping through the fingertips
  PairSettings first_layout_only = without_helpers;
  first_layout_only.retry_keeping_corners = false;
  const PairMapping first =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, first_layout_only);
  const PairMapping map =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, without_helpers);

  EXPECT_GE(first.quality.flipped_faces.size(), 1u);  // measured 1, at the left index knuckle
  EXPECT_EQ(first.layouts_built, 1);
  EXPECT_EQ(map.layout_kept, 2);
  // The second layout keeps the corners at the anchors near the folds and their neighbours,
  // among them the fingertip.
  const StretchSettings& kept = map.optimization.settings.stretching;
  EXPECT_TRUE(kept.keep_corners);
  int fingertip = 0;
  while (source_anchors.anchors[fingertip].name != "Lt. Dactylion") ++fingertip;
  EXPECT_NE(std::find(kept.keep_corners_at.begin(), kept.keep_corners_at.end(), fingertip),
            kept.keep_corners_at.end());
  EXPECT_GE(map.optimization.unstretched_curves, 2);
  EXPECT_TRUE(map.quality.flipped_faces.empty()) << map.quality.flipped_faces.size() << " folded";
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);  // measured 0.982
  EXPECT_EQ(map.inverted_triangles[0], 0);
  EXPECT_EQ(map.inverted_triangles[1], 0);
  // The registration itself is off by 7 mm at the median (SOURCE.txt); measured 0.0117.
  EXPECT_LT(test::distance_to_truth(map, target.mesh, truth).mean, 0.015);
}

// SHREC'19 shape 17, a raw CAESAR scan, against the SMPL template: its registration puts the
// right hand's knuckle landmarks about a quarter turn round the hand from SMPL's, and every layout
// folds there (measured 41 folds, the most, 12, nearest the index knuckle). Released from that
// anchor, the map has no fold, still covers the target's area to 2%, and reports how far it
// lands from the released landmark.
TEST(ShrecHuman, ReleasingTheMisplacedKnuckleUnfoldsTheScan) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "17");
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  PairSettings releasing;
  use_the_earlier_tree(releasing);  // the layout whose map the retries repair
  releasing.max_released_anchors = 3;
  releasing.tip_anchor_reaches = {0.1};  // one try with helpers shows which way is kept
  releasing.optimize_map = false;  // releasing's own effect, not the optimizer's
  releasing.max_maps = 20;         // nor the budget's: the later layouts and helpers come first
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, releasing);

  const std::string knuckle = "Rt. Metacarpal Phal. II";
  // Helpers behind the tips leave folds (1 after all three reaches by default); releasing from the map
  // through the given anchors leaves none, so that way is kept, and it needs no helper.
  EXPECT_TRUE(map.tip_anchors.empty());
  ASSERT_EQ(map.released_anchors.size(), 1u);
  EXPECT_EQ(map.released_anchors[0].name, knuckle);
  EXPECT_GE(map.released_anchors[0].folded_faces, 1);  // measured 12
  EXPECT_TRUE(map.quality.flipped_faces.empty()) << map.quality.flipped_faces.size() << " folded";
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);  // measured 0.981
  EXPECT_EQ(map.inverted_triangles[0], 0);
  EXPECT_EQ(map.inverted_triangles[1], 0);
  // The released landmark is missed, but by about a knuckle's width (measured 1.0 cm), not by
  // a hand's length: the map still carries the knuckle to the hand.
  EXPECT_GT(map.released_anchors[0].miss_distance, 1e-3);
  EXPECT_LT(map.released_anchors[0].miss_distance, 0.03);
  EXPECT_EQ(map.anchors[0].anchors.size(), source_anchors.anchors.size() - 1);
  for (const PlacedAnchor& placed : map.anchors[0].anchors) EXPECT_NE(placed.name, knuckle);
  // The registration itself is off by 7 mm at the median (SOURCE.txt); measured 0.0104.
  EXPECT_LT(test::distance_to_truth(map, target.mesh, truth).mean, 0.015);
}

// SHREC'19 shape 22 (SPRING0176: two non-manifold edges at an ankle and a duplicated face, taken
// through the scan intake) with the 73 CAESAR landmarks: its hands are mittens, and at the right
// middle fingertip (Dactylion) the layout's corners disagree. Without helpers the map squeezes the
// template's ring and little fingers to a point at the knuckle, and no face folds, so no retry for
// folds sees it (E_L2 2.64, 279 faces over 10 times the map's scale, measured). Last, the map is
// made again through helpers behind the disagreeing tips: none squeezed so, E_L2 1.10.
TEST(ShrecHuman, HelpersBehindTheTipsUnsqueezeAMittensFingers) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "22", "smpl_caesar_landmark_indices.json", true);
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  PairSettings no_helpers;
  no_helpers.tip_anchors = false;
  const PairMapping squeezed =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, no_helpers);
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {});

  const auto squeezed_faces = [](const PairMapping& m) {
    const double scale = std::sqrt(m.distortion.all_sums.image_area / m.distortion.all_sums.source_area);
    return std::count_if(m.distortion.face_l2_stretch.begin(), m.distortion.face_l2_stretch.end(),
                         [&](double l2) { return !(l2 <= 10.0 * scale); });
  };
  EXPECT_GT(squeezed.distortion.all.e_l2, 2.0);  // measured 2.64
  EXPECT_GT(squeezed_faces(squeezed), 100);      // measured 279
  EXPECT_TRUE(squeezed.quality.flipped_faces.empty());

  EXPECT_LT(map.distortion.all.e_l2, 1.2);  // measured 1.10
  EXPECT_EQ(squeezed_faces(map), 0);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);
  std::vector<std::string> tips;
  for (const TipAnchor& helper : map.tip_anchors) tips.push_back(helper.tip);
  EXPECT_NE(std::find(tips.begin(), tips.end(), "Rt. Dactylion"), tips.end());
  // Every landmark exact (the helpers come after them): none shares a template vertex with a helper.
  for (std::size_t k = 0; k < source_anchors.anchors.size(); ++k)
    EXPECT_LT(map.anchor_miss[k], 1e-12) << map.anchors[0].anchors[k].name;
}

// SHREC'19 shape 9 (a handle, cut by the scan intake) with the 29 anthropometric landmarks: the
// target creases sharply in the crotch, and a remesh face there was left strictly folded (its
// corners' target faces all face against it) while the remesh's own count saw none. Every move of
// a corner that opens it raises the energy of the corner's ring (12.8 -> 32.5, measured), so the
// openings take such a move when it folds nothing by the own count.
TEST(ShrecHuman, AStrictFoldOnASharpCreaseIsOpenedAtACostInEnergy) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "9", "smpl_anthropometry_landmark_indices.json", true);
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {});
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
  EXPECT_LT(map.distortion.all.e_l2, 1.1);  // measured 1.07
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);
}

// SHREC'19 shape 19 (a loose part, dropped by the scan intake) with the 29 anthropometric landmarks,
// which hold the left leg at the heel, ankle, calf and thigh: the target's path between the left
// heel and ankle was traced round the outside of the ankle where the template's ran round the inside,
// in a corridor placed by a similarity fitted over the leg's anchors that missed them by 4-8 cm. The
// left foot then lay in different patches on the two meshes, and every map drew it into rings at the
// ankle (E_L2 1.22 at best, the left foot's template vertices 5.1 cm from their truth on average;
// looked at). Checked in the frame of the edge itself and traced again, the path runs round the
// inside on both meshes and the foot maps onto the foot (measured: E_L2 1.05, the foot 1.2 cm).
TEST(ShrecHuman, APathRoundTheOtherSideOfTheAnkleIsTracedAgain) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "19", "smpl_anthropometry_landmark_indices.json", true);
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {});
  // The left foot's template vertices, below the ankle (SMPL: x > 0, y < -1.05).
  const double left_foot_error =
      region_error(shrec, map, [](const Eigen::Vector3d& p) { return p.x() > 0.0 && p.y() < -1.05; });
  EXPECT_LT(left_foot_error, 0.03) << "the left foot's mean distance to the truth, m";
  EXPECT_LT(map.distortion.all.e_l2, 1.15);
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
}

// SHREC'19 shape 15 (loose parts, dropped by the scan intake) with the 29 anthropometric landmarks,
// which hold each hand at the wrist alone: the first map draws the hands into the wrists, and the
// tips matched through it paired the template's left thumb with the target's index finger and the
// right little finger with the index (the left hand's template vertices 1.35 cm from their truth
// on average, the right's 7.8 cm, its fingers squeezed into spikes; looked at). With no pair taken
// through a cell the map squeezes, and the right wrist's and ulnar styloid's cells, which split
// the right hand differently on the two meshes, searched as one limb, the cells match the middle
// fingertips and the next round the rest through the map they open (measured: 0.78 and 0.90 cm,
// every tip within 2 cm of its truth, E_L2 1.073 -> 1.033; looked at: every finger on its own).
TEST(ShrecHuman, NoFingertipIsPairedThroughAMapThatSqueezesTheHand) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "15", "smpl_anthropometry_landmark_indices.json", true);
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {});
  constexpr double kLeft = 1.0;
  constexpr double kRight = -1.0;
  EXPECT_LT(hand_error(shrec, map, kLeft), 0.012) << "the left hand's mean distance to the truth, m";
  EXPECT_LT(hand_error(shrec, map, kRight), 0.012) << "the right hand's mean distance to the truth, m";
  EXPECT_GE(map.extremity_anchors.size(), 8u);  // measured 9: every fingertip but the right little one
  for (const ExtremityAnchor& tip : map.extremity_anchors)
    EXPECT_LT(tip_off_truth(shrec, tip), 0.02) << tip.specs[0].name;
  EXPECT_LT(map.distortion.all.e_l2, 1.04);
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
}

// SHREC'19 shape 20 (loose parts, dropped by the scan intake) with the 29 anthropometric landmarks:
// the left hand is held at the wrist alone. Once the wrist's cell has matched the middle fingertips,
// the other tips are matched by their distances to the wrist and the middle fingertip, which an
// index and a ring fingertip share (mirror images about the middle finger): the template's index
// fingertip was paired with the target's ring one, and the index and ring fingers were drawn across
// the middle into spikes (the left hand's template vertices 4.6 cm from their truth on average,
// E_L2 1.045; looked at). The side of the plane through the wrist, its normal and the middle
// fingertip tells them apart (measured: 0.8 cm, each of its tips within 1 cm of its truth, E_L2 1.035;
// looked at: every finger on its own).
TEST(ShrecHuman, AFingertipIsNotPairedWithItsMirrorImageAboutTheMiddleFinger) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "20", "smpl_anthropometry_landmark_indices.json", true);
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {});
  constexpr double kLeft = 1.0;
  EXPECT_LT(hand_error(shrec, map, kLeft), 0.012) << "the left hand's mean distance to the truth, m";
  int left_hand_tips = 0;
  for (const ExtremityAnchor& tip : map.extremity_anchors) {
    if (!tip_on_hand(shrec, tip, kLeft)) continue;
    EXPECT_LT(tip_off_truth(shrec, tip), 0.01) << tip.specs[0].name;
    ++left_hand_tips;
  }
  EXPECT_GE(left_hand_tips, 3);  // measured 3: the middle (its landmark's cell), index and thumb
  EXPECT_LT(map.distortion.all.e_l2, 1.04);
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
}

// SHREC'19 shape 19 (a loose part, dropped by the scan intake) with the 29 anthropometric landmarks:
// the right wrist's cell holds the target's index and middle fingertips at the same distance from
// the landmark (0.133 sqrt(area)), and its farthest, the index, was paired with the template's
// middle fingertip: the middle finger came out a spike between the target's fingers (looked at;
// the right hand's template vertices 2.4 cm from their truth). The map with the rival tip is 0.6%
// less stretched in all, under the 1% a whole map needs, but 19% about the hand, and replaces it
// (the middle fingertip on its own, the hand 1.4 cm, E_L2 1.050 -> 1.043). The left wrist's cell
// is ambiguous too (0.137 and 0.134): its rival, tried on top of the right's, wins as well
// (measured: the left hand 4.0 -> 1.3 cm, E_L2 1.043 -> 1.021; looked at: the thumb on the thumb
// instead of long faces across the palm, the index finger no longer squeezed on the back of the
// hand). The dataset's registration puts the left index and middle fingertips 0.8 cm apart, so
// the left tips are not held to it one by one.
TEST(ShrecHuman, EachWristsRivalTipLessStretchedAboutTheHandWins) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "19", "smpl_anthropometry_landmark_indices.json", true);
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {});
  constexpr double kLeft = 1.0;
  constexpr double kRight = -1.0;
  EXPECT_LT(hand_error(shrec, map, kRight), 0.018) << "the right hand's mean distance to the truth, m";
  EXPECT_LT(hand_error(shrec, map, kLeft), 0.018) << "the left hand's mean distance to the truth, m";
  int right_cell_tips = 0;
  for (const ExtremityAnchor& tip : map.extremity_anchors) {
    if (!tip_on_hand(shrec, tip, kRight) || tip.matched_by != TipMatching::by_cell) continue;
    EXPECT_LT(tip_off_truth(shrec, tip), 0.01) << tip.specs[0].name;
    ++right_cell_tips;
  }
  EXPECT_EQ(right_cell_tips, 1);
  // Each wrist's farthest tip was replaced by its rival.
  int replaced_cell_tips = 0;
  for (const ExtremityAnchor& tip : map.doubtful_tips)
    replaced_cell_tips += tip.matched_by == TipMatching::by_cell;
  EXPECT_EQ(replaced_cell_tips, 2);
  EXPECT_LT(map.distortion.all.e_l2, 1.03);
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
}

// SHREC'19 shape 21 (loose parts, dropped by the scan intake) with the 73 CAESAR landmarks, which
// hold the right hand at its middle fingertip, two knuckles and the wrist: the first map squeezed
// the template's ring and little fingers onto the target's little finger, and the pair through it
// took the ring fingertip for the little one. The template's little finger came out a disc on the
// back of the hand and the target's ring finger lay under long faces (looked at; the right hand's
// template vertices 1.7 cm from their truth). Tried one over, the ring fingertip with the target's
// ring one and the little with the little, the map is 12% less stretched about the hand and wins
// (measured: every right fingertip on its own finger, the hand 0.9 cm, E_L2 1.046 -> 1.043; 1.039
// with the left little fingertip below).
TEST(ShrecHuman, APairOneFingerOverIsTriedWithItsNeighbours) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const ShrecPair shrec = load_shrec_pair(data, "21", "smpl_caesar_landmark_indices.json", true);
  const auto& [source, target, truth, source_anchors, target_anchors] = shrec;
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {});
  constexpr double kRight = -1.0;
  EXPECT_LT(hand_error(shrec, map, kRight), 0.012) << "the right hand's mean distance to the truth, m";
  // Each right-hand tip's target point lies nearer the true image of its own template tip than of
  // any other (its own finger, not the next).
  const std::vector<const ExtremityAnchor*> right_tips = expect_tips_on_their_own_fingers(shrec, map, kRight);
  const int one_over_tips =
      static_cast<int>(std::count_if(right_tips.begin(), right_tips.end(), [](const ExtremityAnchor* tip) {
        return tip->matched_by == TipMatching::one_over;
      }));
  EXPECT_GE(right_tips.size(), 4u);  // measured 4: the thumb, index, ring and little; the middle a landmark
  EXPECT_EQ(one_over_tips, 2);
  // The left little fingertip, pressed against the ring finger, matches its partner by distances at
  // 0.101 (kMaxDescriptorMismatch): below 0.1 it was left out, the map without the ring fingertip won
  // and the little finger was squeezed into a disc on the side of the hand (looked at; 2 left tips,
  // the hand 1.23 cm from the truth, now 4 and 0.80 cm).
  constexpr double kLeft = 1.0;
  EXPECT_GE(expect_tips_on_their_own_fingers(shrec, map, kLeft).size(), 4u);
  EXPECT_LT(hand_error(shrec, map, kLeft), 0.01);
  EXPECT_LT(map.distortion.all.e_l2, 1.042);
  EXPECT_EQ(map.quality.strictly_folded_faces, 0);
  EXPECT_TRUE(map.quality.flipped_faces.empty());
}

// Schmidt et al. 2023's cat (template) and horse with their 17 landmarks.
struct CatHorsePair {
  LoadedMesh source;
  LoadedMesh target;
  AnchorSet source_anchors;
  AnchorSet target_anchors;
};

CatHorsePair load_cat_horse(const std::filesystem::path& data) {
  const std::filesystem::path dir = data / "landmark_pairs_schmidt2023/yang2020_cat_horse";
  return {load_mesh(dir / "input0.obj"), load_mesh(dir / "input1.obj"),
          indexed_anchors(dir / "landmarks0.txt"), indexed_anchors(dir / "landmarks1.txt")};
}

// Schmidt et al. 2023's cat against its horse (17 landmarks, no ground truth). The first layout
// folds 11 remesh faces over 6 anchors; the second, corners kept near them and at their layout
// neighbours, does not fold fewer; the third, corners kept at the fold anchors alone, folds 6.
TEST(CatHorse, ThirdLayoutFoldsLess) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const CatHorsePair pair = load_cat_horse(data);
  const auto& [source, target, source_anchors, target_anchors] = pair;
  ASSERT_EQ(source_anchors.anchors.size(), 17u);
  PairSettings without_helpers;  // helpers behind the tips would unfold the first map already
  use_the_earlier_tree(without_helpers);  // the layout whose map the retries repair
  without_helpers.tip_anchors = false;
  without_helpers.optimize_map = false;  // and so would optimizing the map
  without_helpers.extremity_anchors = false;  // and mapping through the fingertips
  PairSettings first_layout_only = without_helpers;
  first_layout_only.retry_keeping_corners = false;
  const PairMapping first =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, first_layout_only);
  const PairMapping map =
      map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, without_helpers);

  ASSERT_GE(first.folds_by_anchor.size(), 2u);  // measured 11 folds over 6 anchors
  EXPECT_EQ(map.layouts_built, 3);
  EXPECT_EQ(map.layout_kept, 3);
  // Corners kept at exactly the anchors nearest the first map's folds.
  std::vector<int> fold_anchors;
  for (const AnchorFolds& folds : first.folds_by_anchor) fold_anchors.push_back(folds.anchor);
  std::sort(fold_anchors.begin(), fold_anchors.end());
  EXPECT_EQ(map.optimization.settings.stretching.keep_corners_at, fold_anchors);
  EXPECT_LT(map.quality.flipped_faces.size(), first.quality.flipped_faces.size());  // measured 6 against 11
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);                                   // measured 0.9996
  EXPECT_TRUE(map.released_anchors.empty());  // it folds, but releasing anchors is opt-in
  // The anchor with the most folds is one whose corners disagree (measured at a5: 57/66/237
  // degrees on the cat, 162/116/82 on the horse); every anchor listed disagrees by 120 or more.
  ASSERT_FALSE(map.folds_by_anchor.empty());
  bool most_folds_listed = false;
  for (const CornerMismatch& corners : map.mismatched_corners) {
    most_folds_listed = most_folds_listed || corners.anchor == map.folds_by_anchor.front().anchor;
    double worst = 0.0;
    for (std::size_t i = 0; i < corners.template_degrees.size(); ++i)
      worst = std::max(worst, std::abs(corners.template_degrees[i] - corners.target_degrees[i]));
    EXPECT_GE(worst, 120.0) << corners.name;
  }
  EXPECT_TRUE(most_folds_listed);
  EXPECT_EQ(map.inverted_triangles[0], 0);
  EXPECT_EQ(map.inverted_triangles[1], 0);
}

// The same pair by default: the map above still folds where its corners disagree, so it is
// mapped again through a helper anchor behind each such tip, and that map has no fold.
TEST(CatHorse, HelperAnchorsBehindTheTipsUnfoldIt) {
  const std::filesystem::path data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is not here";
  const CatHorsePair pair = load_cat_horse(data);
  const auto& [source, target, source_anchors, target_anchors] = pair;
  PairSettings helpers;
  helpers.optimize_map = false;        // the helpers' own effect, not the optimizer's
  helpers.extremity_anchors = false;   // nor the tip anchors' (which keep one map of the budget back)
  const PairMapping map = map_pair(source.mesh, source_anchors, target.mesh, target_anchors, {}, helpers);

  EXPECT_TRUE(map.quality.flipped_faces.empty());  // measured 0, against 6 without helpers
  EXPECT_EQ(map.distortion.degenerate_faces, 0);
  EXPECT_NEAR(map.quality.area_ratio, 1.0, 0.02);  // measured 1.0066
  EXPECT_EQ(map.inverted_triangles[0], 0);
  EXPECT_EQ(map.inverted_triangles[1], 0);
  // Helpers behind the tips whose corners disagreed (a3, a5, a7, a9, a12 measured), among them
  // a5, where the map without them folds most; each is an anchor of the map on both meshes.
  std::vector<std::string> tips;
  for (const TipAnchor& helper : map.tip_anchors) {
    tips.push_back(helper.tip);
    EXPECT_EQ(helper.specs[0].name, helper.tip + " (behind)");
    for (int side = 0; side < 2; ++side) {
      const auto& placed = map.anchors[side].anchors;
      EXPECT_TRUE(std::any_of(placed.begin(), placed.end(), [&](const PlacedAnchor& anchor) {
        return anchor.name == helper.specs[0].name;
      }));
    }
  }
  EXPECT_NE(std::find(tips.begin(), tips.end(), "a5"), tips.end());
  EXPECT_EQ(map.anchors[0].anchors.size(), source_anchors.anchors.size() + map.tip_anchors.size());
}

}  // namespace
}  // namespace xparam
