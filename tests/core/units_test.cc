#include <gtest/gtest.h>

#include <string>

#include "foglab/core/error.h"
#include "foglab/core/units.h"

namespace foglab {
namespace {

TEST(Units, ConversionFactorsToDegPerHour) {
  EXPECT_DOUBLE_EQ(to_deg_per_hour(RateUnit::deg_per_hour), 1.0);
  EXPECT_DOUBLE_EQ(to_deg_per_hour(RateUnit::deg_per_second), 3600.0);
  // Earth rate: 7.292115e-5 rad/s = 15.041 deg/h.
  EXPECT_NEAR(7.292115e-5 * to_deg_per_hour(RateUnit::rad_per_second), 15.0411, 1e-4);
}

TEST(Units, NamesRoundTripAndUnknownNamesAreListed) {
  for (const RateUnit u :
       {RateUnit::deg_per_hour, RateUnit::deg_per_second, RateUnit::rad_per_second}) {
    EXPECT_EQ(rate_unit_from_string(to_string(u)), u);
  }
  EXPECT_EQ(rate_unit_from_string("DPH"), RateUnit::deg_per_hour);
  try {
    rate_unit_from_string("mrad/s");
    FAIL();
  } catch (const UsageError& e) {
    EXPECT_EQ(std::string(e.what()),
              "unknown rate unit 'mrad/s': expected deg/h, deg/s or rad/s");
  }
  EXPECT_EQ(input_kind_from_string("angle"), InputKind::phase);
  EXPECT_EQ(input_kind_from_string(to_string(InputKind::rate)), InputKind::rate);
  EXPECT_THROW(input_kind_from_string("acceleration"), UsageError);
}

}  // namespace
}  // namespace foglab
