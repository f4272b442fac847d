// Target discovery (folder convention and manifest) and sharding.
#include "batch/target_discovery.h"

#include "batch_test_support.h"
#include "core/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace xparam {
namespace {

using test::fs::path;
using test::write_file;

const TargetSpec& find(const std::vector<TargetSpec>& targets, const std::string& name) {
  const auto it = std::find_if(targets.begin(), targets.end(), [&](const TargetSpec& t) { return t.name == name; });
  EXPECT_NE(it, targets.end()) << name;
  return *it;
}

std::vector<std::string> names(const std::vector<TargetSpec>& targets) {
  std::vector<std::string> out;
  for (const TargetSpec& t : targets) out.push_back(t.name);
  return out;
}

TEST(TargetDiscovery, SampleFolderHasFourTargetsWithAnchorsAndGroundTruth) {
  const std::vector<TargetSpec> targets = discover_targets(test::sample_targets());
  EXPECT_EQ(names(targets), (std::vector<std::string>{"man_bent", "man_flipped", "woman", "woman_turned"}));
  for (const TargetSpec& t : targets) {
    EXPECT_TRUE(t.problem.empty()) << t.problem;
    EXPECT_TRUE(std::filesystem::is_regular_file(t.mesh)) << t.mesh;
    EXPECT_TRUE(std::filesystem::is_regular_file(t.anchors)) << t.anchors;
    EXPECT_TRUE(std::filesystem::is_regular_file(t.ground_truth)) << t.ground_truth;
  }
  EXPECT_EQ(find(targets, "man_flipped").anchors.filename(), "man_flipped.pp");
  EXPECT_EQ(find(targets, "woman_turned").anchors.filename(), "woman_turned.anchors.txt");
  EXPECT_EQ(find(targets, "woman").anchors.filename(), "woman.anchors.json");
}

TEST(TargetDiscovery, FolderConventionRecordsEveryProblemAsATarget) {
  const path dir = test::fresh_temp_dir("discovery_folder");
  // Created in reverse name order: the result must not follow creation or directory order.
  for (const char* file : {"z.OBJ", "z.anchors.json", "dup.ply", "dup.obj", "dup.pp", "lonely.anchors.txt",
                           "two.off", "two.anchors.json", "two.pp", "bare.stl", "a.Ply", "a.PP", "a.gt.txt",
                           "README.md", "notes.txt", "lonely_gt.gt.txt"})
    write_file(dir / file, "x");
  std::filesystem::create_directories(dir / "sub.obj");  // a folder is never a target

  const std::vector<TargetSpec> targets = discover_targets(dir);
  EXPECT_EQ(names(targets), (std::vector<std::string>{"a", "bare", "dup", "lonely", "two", "z"}));

  const TargetSpec& a = find(targets, "a");
  EXPECT_TRUE(a.problem.empty()) << a.problem;
  EXPECT_EQ(a.mesh, dir / "a.Ply");
  EXPECT_EQ(a.anchors, dir / "a.PP");
  EXPECT_EQ(a.ground_truth, dir / "a.gt.txt");

  const TargetSpec& bare = find(targets, "bare");
  EXPECT_NE(bare.problem.find("no anchors for " + (dir / "bare.stl").string()), std::string::npos) << bare.problem;
  EXPECT_NE(bare.problem.find("bare.anchors.json"), std::string::npos) << bare.problem;

  const TargetSpec& dup = find(targets, "dup");
  EXPECT_NE(dup.problem.find("two meshes"), std::string::npos) << dup.problem;
  EXPECT_NE(dup.problem.find((dir / "dup.obj").string()), std::string::npos) << dup.problem;
  EXPECT_NE(dup.problem.find((dir / "dup.ply").string()), std::string::npos) << dup.problem;

  const TargetSpec& lonely = find(targets, "lonely");
  EXPECT_TRUE(lonely.mesh.empty());
  EXPECT_NE(lonely.problem.find("no mesh"), std::string::npos) << lonely.problem;
  EXPECT_NE(lonely.problem.find("lonely.anchors.txt"), std::string::npos) << lonely.problem;

  const TargetSpec& two = find(targets, "two");
  EXPECT_NE(two.problem.find("two anchor files"), std::string::npos) << two.problem;
  EXPECT_NE(two.problem.find("two.pp"), std::string::npos) << two.problem;

  EXPECT_TRUE(find(targets, "z").problem.empty());
}

TEST(TargetDiscovery, ManifestResolvesPathsAndRecordsDuplicatesAndMissingAnchors) {
  const path dir = test::fresh_temp_dir("discovery_manifest");
  write_file(dir / "list.json", R"([
    {"name": "b", "mesh": "meshes/b.obj", "anchors": "/abs/b.pp", "ground_truth": "gt/b.txt"},
    {"name": "a", "mesh": "a.ply", "anchors": "a.json"},
    {"name": "c", "mesh": "c.off"},
    {"name": "a", "mesh": "other_a.ply", "anchors": "other_a.json"}
  ])");
  const std::vector<TargetSpec> targets = discover_targets(dir / "list.json");
  EXPECT_EQ(names(targets), (std::vector<std::string>{"a", "b", "c"}));
  const TargetSpec& b = find(targets, "b");
  EXPECT_EQ(b.mesh, dir / "meshes/b.obj");
  EXPECT_EQ(b.anchors, path("/abs/b.pp"));
  EXPECT_EQ(b.ground_truth, dir / "gt/b.txt");
  EXPECT_TRUE(b.problem.empty());
  const TargetSpec& a = find(targets, "a");
  EXPECT_EQ(a.mesh, dir / "a.ply");  // the first entry is kept, the second named in the problem
  EXPECT_NE(a.problem.find("listed twice"), std::string::npos) << a.problem;
  EXPECT_NE(a.problem.find("other_a.ply"), std::string::npos) << a.problem;
  EXPECT_NE(a.problem.find("list.json:5"), std::string::npos) << a.problem;
  EXPECT_NE(find(targets, "c").problem.find("no anchors"), std::string::npos);
}

TEST(TargetDiscovery, FolderManifestWinsOverTheConvention) {
  const path dir = test::fresh_temp_dir("discovery_folder_manifest");
  write_file(dir / "x.obj", "x");
  write_file(dir / "x.anchors.json", "x");
  write_file(dir / kManifestFileName, R"([{"name": "only", "mesh": "x.obj", "anchors": "x.anchors.json"}])");
  EXPECT_EQ(names(discover_targets(dir)), std::vector<std::string>{"only"});
}

TEST(TargetDiscovery, MalformedManifestsAreInputErrorsNamingTheEntry) {
  const path dir = test::fresh_temp_dir("discovery_bad_manifest");
  const auto error_of = [&](const std::string& text) -> std::string {
    write_file(dir / "m.json", text);
    try {
      discover_targets(dir / "m.json");
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(error_of(R"({"name": "a"})").find("JSON array"), std::string::npos);
  EXPECT_NE(error_of("[\n {\"mesh\": \"a.obj\"}]").find("m.json:2: entry 0: missing \"name\""), std::string::npos);
  EXPECT_NE(error_of(R"([{"name": "a", "mesh": "a.obj", "anchor": "a.json"}])").find("unknown member \"anchor\""),
            std::string::npos);
  EXPECT_NE(error_of(R"([{"name": "", "mesh": "a.obj"}])").find("non-empty string"), std::string::npos);
  EXPECT_NE(error_of(R"([{"name": "a", "mesh": 3}])").find("\"mesh\""), std::string::npos);
  EXPECT_NE(error_of("[1]").find("not an object"), std::string::npos);
  EXPECT_NE(error_of("[").find("m.json"), std::string::npos);
  EXPECT_THROW(discover_targets(dir / "missing"), InputError);
}

TEST(Shard, ParseAcceptsOnlyIndexBelowCount) {
  EXPECT_EQ(parse_shard("0/1").count, 1);
  const Shard s = parse_shard("3/4");
  EXPECT_EQ(s.index, 3);
  EXPECT_EQ(s.count, 4);
  for (const char* bad : {"4/4", "1/0", "-1/2", "1", "a/2", "1/2/3", "/2", "1/", " 1/2", "1/2x"})
    EXPECT_THROW(parse_shard(bad), InputError) << bad;
}

TEST(Shard, ShardsAreDisjointCoverTheListAndBalance) {
  std::vector<TargetSpec> targets;
  for (int i = 0; i < 11; ++i) targets.push_back({"t" + std::to_string(10 + i), {}, {}, {}, {}});
  for (int count = 1; count <= 13; ++count) {
    std::multiset<std::string> seen;
    std::size_t smallest = targets.size();
    std::size_t largest = 0;
    for (int index = 0; index < count; ++index) {
      const std::vector<TargetSpec> shard = select_shard(targets, {index, count});
      for (const TargetSpec& t : shard) seen.insert(t.name);
      EXPECT_TRUE(std::is_sorted(shard.begin(), shard.end(),
                                 [](const TargetSpec& x, const TargetSpec& y) { return x.name < y.name; }));
      smallest = std::min(smallest, shard.size());
      largest = std::max(largest, shard.size());
    }
    EXPECT_EQ(seen.size(), targets.size()) << count;
    for (const TargetSpec& t : targets) EXPECT_EQ(seen.count(t.name), 1u) << count;
    EXPECT_LE(largest - smallest, 1u) << count;
  }
}

}  // namespace
}  // namespace xparam
