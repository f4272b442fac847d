// `xparam check` over every mesh of ../shared/data against the tables of its SOURCE.txt files
// (label `real_data`: skipped when the folder is absent).
#include "check_program_support.h"

#include <gtest/gtest.h>

#include <string>

namespace xparam {
namespace {

using test::compare_script;
using test::have_python;
using test::ProgramRun;

TEST(CheckSharedData, AgreesWithEverySourceTable) {
  const auto data = test::shared_data_dir();
  if (data.empty()) GTEST_SKIP() << "no ../shared/data";
  if (!have_python()) GTEST_SKIP() << "python3 not available";
  const ProgramRun r = compare_script(data, "check_shared_data");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find(": all agree"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("MISMATCH"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace xparam
