// The scan intake's figures over a batch: which targets it repaired and the totals, from metrics
// rows and diagnoses (rows kept from an archive older than the diagnosis's record included).
#include "batch/intake_totals.h"
#include "batch/summary_json.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

TargetOutcome finished(const std::string& name, int dropped_faces, int holes, int on_filled) {
  TargetOutcome outcome;
  outcome.name = name;
  outcome.ok = true;
  outcome.diagnosis = R"({"reasons":[]})";
  outcome.metrics.dropped_faces = dropped_faces;
  outcome.metrics.dropped_area = 0.5 * dropped_faces;
  outcome.metrics.holes_filled = holes;
  outcome.metrics.filled_area = 0.25 * holes;
  outcome.metrics.on_filled_vertices = on_filled;
  return outcome;
}

std::vector<TargetOutcome> batch_of_five() {
  TargetOutcome reoriented = finished("reoriented", 0, 0, 0);  // repaired, but nothing dropped or filled
  reoriented.diagnosis =
      R"({"reasons":[],"intake":{"applied":true,"reversed_faces":3,"steps":["3 faces turned"]}})";
  TargetOutcome holed = finished("holed", 0, 2, 14);
  holed.diagnosis = R"({"reasons":[],"intake":{"applied":true,"steps":["2 holes filled"]}})";
  TargetOutcome failed;
  failed.name = "failed";
  failed.error = "failed.ply: genus 1";
  // A row of an older archive: no record in its diagnosis, but its metrics show parts dropped.
  return {finished("clean", 0, 0, 0), reoriented, holed, finished("older_row", 8, 0, 0), failed};
}

TEST(IntakeTotals, CountRepairedTargetsAndSumTheirFigures) {
  const IntakeTotals totals = intake_totals(batch_of_five());
  EXPECT_EQ(totals.repaired, 3u);
  EXPECT_EQ(totals.with_parts_dropped, 1u);
  EXPECT_EQ(totals.with_holes_filled, 1u);
  EXPECT_EQ(totals.dropped_faces, 8u);
  EXPECT_EQ(totals.dropped_area, 4.0);
  EXPECT_EQ(totals.holes_filled, 2u);
  EXPECT_EQ(totals.filled_area, 0.5);
  EXPECT_EQ(totals.on_filled_vertices, 14u);
}

TEST(IntakeTotals, SummaryJsonHasTheTotalsAndEachRepairedTargetsRecord) {
  BatchSummary summary;
  summary.targets = batch_of_five();
  const nlohmann::ordered_json json = summary_json(summary);
  EXPECT_EQ(json["intake"]["repaired"], 3);
  EXPECT_EQ(json["intake"]["dropped_faces"], 8);
  EXPECT_EQ(json["intake"]["on_filled_vertices"], 14);
  EXPECT_FALSE(json["targets"][0].contains("intake"));
  EXPECT_EQ(json["targets"][1]["intake"]["reversed_faces"], 3);
  EXPECT_EQ(json["targets"][2]["intake"]["steps"][0], "2 holes filled");
  EXPECT_FALSE(json["targets"][4].contains("intake"));
}

}  // namespace
}  // namespace xparam
