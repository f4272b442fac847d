// scripts/update_evaluation.py, which turns the output of xparam_evaluate into the generated tables of
// docs/evaluation.md, run as a program on saved output (tests/data/evaluation/): the tables hold the
// printed figures, nothing outside the markers changes, and a document it cannot fill is left as it was.
#include "cli/check_program_support.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>

namespace xparam::test {
namespace {

namespace fs = std::filesystem;

const char* const kBlocks[] = {"stamp",      "table1",  "table1_folds_truth", "table1_default", "realistic",
                               "hands_feet", "summary", "benchmarks"};

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A document with every block, old text inside each and prose between them.
std::string document_with_blocks(const std::string& leave_out_end_of = "") {
  std::string text = "# Evaluation\n\nProse before, kept.\n";
  for (const char* block : kBlocks) {
    text += "<!-- BEGIN generated: " + std::string(block) + " -->\nold " + block + "\n";
    if (block != leave_out_end_of) text += "<!-- END generated: " + std::string(block) + " -->\n";
    text += "Prose after " + std::string(block) + ", kept.\n";
  }
  return text;
}

// The saved output of the script's four runs (tests/data/evaluation).
std::array<fs::path, 4> saved_output() {
  return {data_path("evaluation/table.txt"), data_path("evaluation/realistic.txt"),
          data_path("evaluation/realistic_paper.txt"), data_path("evaluation/bench.json")};
}

// The script run on `outputs` (the table set's, the realistic set's under the default and under the
// paper's map, the benchmarks'), writing `doc`.
ProgramRun update(const fs::path& doc, const std::array<fs::path, 4>& outputs, const std::string& test_name) {
  const fs::path script = fs::path(XPARAM_SOURCE_DIR) / "scripts" / "update_evaluation.py";
  std::string arguments =
      "python3 " + quoted(script) + " --doc " + quoted(doc) + " --date 2026-01-02 --from-output";
  for (const fs::path& output : outputs) arguments += " " + quoted(output);
  return run(arguments, test_name);
}

// The document with the text between each block's markers taken out: what must not change.
std::string outside_blocks(std::string text) {
  for (const char* block : kBlocks) {
    const std::string begin = "<!-- BEGIN generated: " + std::string(block) + " -->";
    const std::string end = "<!-- END generated: " + std::string(block) + " -->";
    const std::size_t from = text.find(begin);
    const std::size_t to = text.find(end);
    if (from == std::string::npos || to == std::string::npos) return text;
    text.erase(from + begin.size(), to - from - begin.size());
  }
  return text;
}

TEST(UpdateEvaluation, WritesTheFiguresBetweenTheMarkersAndNothingElse) {
  if (!have_python()) GTEST_SKIP() << "no python3";
  const fs::path doc = fresh_temp_dir("update_evaluation_writes") / "evaluation.md";
  const std::string before = document_with_blocks();
  write_text(doc, before);
  const ProgramRun result = update(doc, saved_output(), "update_evaluation_writes_run");
  ASSERT_EQ(result.status, 0) << result.out;
  const std::string after = read_text(doc);
  EXPECT_EQ(outside_blocks(after), outside_blocks(before));
  EXPECT_EQ(after.find("old table1"), std::string::npos);
  // E_L2 / E_ang per configuration, the columns in the printed order; a failed map says so.
  EXPECT_NE(after.find("| pair (anchors) | Original | Balanced + merging |"), std::string::npos) << after;
  EXPECT_NE(after.find("| FAUST 000/001 (pose) (73) | 1.129 / 0.110 | 1.008 / 0.018 |"), std::string::npos)
      << after;
  EXPECT_NE(
      after.find("| cat/horse (Yang 2020) (17) | 3764 / 0.310 | failed: <code>: the layout's curves cross"),
      std::string::npos)
      << after;
  // Strict folds / ground truth; the default's whole row; the realistic set beside the paper's map.
  EXPECT_NE(after.find("| FAUST 000/001 (pose) | 0 / 0.414 | 0 / 0.235 |"), std::string::npos) << after;
  EXPECT_NE(after.find("| FAUST 000/001 (pose) | 1.0077 | 0.0180 | 0 | 0 | 0.9933 | 0.235 | 2 | 20 | 0.188 | "
                       "0.281 | 1.375 | 36.2 | 0.084 | 0.037 |"),
            std::string::npos)
      << after;
  EXPECT_NE(
      after.find("| FAUST 000/010 (subject), decimated to 6000 [29 anthropometric] | "
                 "1.026 / 0 / 0 / 0.9894 / 0.486 / 3.778 | 151.1 | 48.3 / 14 / 9 / 0.9511 / 1.340 / 0.731 |"),
      std::string::npos)
      << after;
  EXPECT_NE(after.find("| FAUST 000/010 (subject), decimated to 6000 [29 anthropometric] | 0.097 | 1.079 |"),
            std::string::npos)
      << after;
  EXPECT_NE(after.find("on 2026-01-02"), std::string::npos);
  EXPECT_NE(after.find("- Balanced + merging: 2 pairs run (1 failed)"), std::string::npos);
  // Each benchmark's wall time and counters.
  EXPECT_NE(after.find(
                "| `BM_HumanPair50k73Landmarks/iterations:1/real_time` | 3.041 s | E_L2 1.023, floor_x 19.4, "
                "strict_folds 0 |"),
            std::string::npos)
      << after;
  EXPECT_NE(after.find("| `BM_ReadOnePolygon/100000` | 82.1 ms |  |"), std::string::npos) << after;
}

TEST(UpdateEvaluation, LeavesADocumentWithoutAllMarkersAsItWas) {
  if (!have_python()) GTEST_SKIP() << "no python3";
  const fs::path doc = fresh_temp_dir("update_evaluation_markers") / "evaluation.md";
  const std::string before = document_with_blocks("hands_feet");
  write_text(doc, before);
  const ProgramRun result = update(doc, saved_output(), "update_evaluation_markers_run");
  EXPECT_NE(result.status, 0);
  EXPECT_NE(result.out.find("block 'hands_feet'"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("is unchanged"), std::string::npos) << result.out;
  EXPECT_EQ(read_text(doc), before);
}

TEST(UpdateEvaluation, LeavesTheDocumentAsItWasWhenNoPairWasMapped) {
  if (!have_python()) GTEST_SKIP() << "no python3";
  const fs::path dir = fresh_temp_dir("update_evaluation_empty");
  const fs::path doc = dir / "evaluation.md";
  const std::string before = document_with_blocks();
  write_text(doc, before);
  const fs::path empty = dir / "empty.txt";
  write_text(empty, "\nSummary over the pairs run (per configuration):\n");
  const ProgramRun result = update(doc, {empty, empty, empty, empty}, "update_evaluation_empty_run");
  EXPECT_NE(result.status, 0);
  EXPECT_NE(result.out.find("no pair was mapped"), std::string::npos) << result.out;
  EXPECT_EQ(read_text(doc), before);
}

}  // namespace
}  // namespace xparam::test
