// The CSV cells foglab writes (core/csv.h).
#include "foglab/core/csv.h"

#include <gtest/gtest.h>

#include <limits>

namespace foglab {
namespace {

TEST(Csv, NumbersKeepTenDigitsAndNoneIsAnEmptyCell) {
  EXPECT_EQ(csv_number(0.1234567890123), "0.123456789");
  EXPECT_EQ(csv_number(-2.5e-12), "-2.5e-12");
  EXPECT_EQ(csv_number(std::numeric_limits<double>::quiet_NaN()), "");
  EXPECT_EQ(csv_number(std::numeric_limits<double>::infinity()), "");
}

TEST(Csv, TextIsQuotedOnlyWhenItHoldsASeparatorAQuoteOrALineBreak) {
  EXPECT_EQ(csv_field("FOG1"), "FOG1");
  EXPECT_EQ(csv_field(""), "");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\r"), "\"cr\r\"");
}

}  // namespace
}  // namespace foglab
