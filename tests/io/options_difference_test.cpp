// Which options differ between a recorded run and the current one, an option the record predates
// taken at its implied value.
#include "io/options_difference.h"

#include <gtest/gtest.h>

namespace xparam {
namespace {

TEST(OptionsDifference, NamesEachOptionThatDiffersWithBothValues) {
  EXPECT_EQ(options_difference(R"({"relax":true,"optimization":{"merge":true}})",
                               R"({"relax":true,"optimization":{"merge":false}})"),
            "option \"optimization.merge\" was true, now false");
  EXPECT_EQ(options_difference(R"({"relax":true})", R"({"relax":true,"max_maps":6})"),
            "option \"max_maps\" was absent, now 6");
  EXPECT_EQ(options_difference(R"({"relax":true,"max_maps":6})", R"({"relax":true})"),
            "option \"max_maps\" was 6, now absent");
  EXPECT_EQ(options_difference(R"({"a":1,"b":2})", R"({"b":2,"a":1})"), "options differ only in their order");
  EXPECT_EQ(options_difference("not json", "{}"), "options were not json, now {}");
}

TEST(OptionsDifference, AnOptionTheRecordPredatesComparesAsItsImpliedValue) {
  const std::string implied = R"({"relax":true,"max_maps":6,"intake":{"mode":"strict","max_hole":0}})";
  // The run uses the value the recorded run had without the option: the same options.
  EXPECT_EQ(options_difference(R"({"relax":true})", R"({"relax":true,"max_maps":6})", implied), "");
  EXPECT_EQ(options_difference(R"({"relax":true})", R"({"relax":true,"max_maps":4})", implied),
            "option \"max_maps\" is not recorded (the archive predates it: 6), now 4");
  // A whole group the record predates: each of its options on its own.
  EXPECT_EQ(options_difference(R"({"relax":true})",
                               R"({"relax":true,"intake":{"mode":"repair","max_hole":0}})", implied),
            "option \"intake.mode\" is not recorded (the archive predates it: \"strict\"), now \"repair\"");
  // A recorded value is never replaced by the implied one.
  EXPECT_EQ(options_difference(R"({"relax":false})", R"({"relax":true})", implied),
            "option \"relax\" was false, now true");
}

}  // namespace
}  // namespace xparam
