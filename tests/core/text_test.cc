// The one lower-case helper (core/text.h): names, units and extensions are
// compared through it.
#include "foglab/core/text.h"

#include <gtest/gtest.h>

#include <string>

namespace foglab {
namespace {

TEST(Text, AsciiLowerChangesOnlyTheLettersAToZ) {
  EXPECT_EQ(ascii_lower("Gyro_X [DEG/S] .MAT"), "gyro_x [deg/s] .mat");
  EXPECT_EQ(ascii_lower(""), "");
  EXPECT_EQ(ascii_lower("@[`{"), "@[`{");  // the neighbours of A-Z and a-z
}

TEST(Text, AsciiLowerLeavesEveryOtherByteAsItIs) {
  // "ГИРО_X" in UTF-8 and a Latin-1 "Ä": bytes above 0x7F are never letters
  // to it, so a Russian channel name keeps its capitals and stays UTF-8.
  EXPECT_EQ(ascii_lower("\xD0\x93\xD0\x98\xD0\xA0\xD0\x9E_X"),
            "\xD0\x93\xD0\x98\xD0\xA0\xD0\x9E_x");
  EXPECT_EQ(ascii_lower("\xC4"), "\xC4");
}

}  // namespace
}  // namespace foglab
