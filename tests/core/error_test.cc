#include "core/error.h"

#include <gtest/gtest.h>

#include "core/version.h"

namespace flexmbs {
namespace {

TEST(Check, PassingConditionDoesNotThrow) { EXPECT_NO_THROW(FLEXMBS_CHECK(1 + 1 == 2, "math")); }

TEST(Check, FailingConditionNamesConditionAndReason) {
  try {
    FLEXMBS_CHECK(1 + 1 == 3, "arithmetic is broken");
    FAIL() << "no throw";
  } catch (const InternalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("1 + 1 == 3"), std::string::npos);
    EXPECT_NE(what.find("arithmetic is broken"), std::string::npos);
  }
}

TEST(Version, IsSemantic) {
  const std::string v(Version());
  EXPECT_EQ(std::count(v.begin(), v.end(), '.'), 2) << v;
}

}  // namespace
}  // namespace flexmbs
