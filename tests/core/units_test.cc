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
              "unknown unit 'mrad/s': expected deg/h, deg/s or rad/s (gyroscopes), m/s^2, g or "
              "mg (accelerometers)");
  }
  EXPECT_EQ(input_kind_from_string("angle"), InputKind::phase);
  EXPECT_EQ(input_kind_from_string(to_string(InputKind::rate)), InputKind::rate);
  EXPECT_THROW(input_kind_from_string("acceleration"), UsageError);
}

TEST(Units, AccelerationUnitsConvertToMetresPerSecondSquared) {
  for (const SampleUnit u :
       {SampleUnit::m_per_s2, SampleUnit::standard_gravity, SampleUnit::milli_g}) {
    EXPECT_EQ(rate_unit_from_string(to_string(u)), u);
    EXPECT_EQ(sensor_of(u), Sensor::accelerometer);
  }
  EXPECT_DOUBLE_EQ(to_internal_unit(SampleUnit::m_per_s2), 1.0);
  EXPECT_DOUBLE_EQ(to_internal_unit(SampleUnit::standard_gravity), 9.80665);
  EXPECT_DOUBLE_EQ(to_internal_unit(SampleUnit::milli_g), 9.80665e-3);
  EXPECT_EQ(rate_unit_from_string("m/s2"), SampleUnit::m_per_s2);
  // "G" is not gravity (giga-, or a typo): only the exact "g".
  EXPECT_THROW(rate_unit_from_string("G"), UsageError);
  EXPECT_EQ(sensor_of(SampleUnit::rad_per_second), Sensor::gyroscope);
  EXPECT_EQ(internal_unit(Sensor::accelerometer), SampleUnit::m_per_s2);
  EXPECT_EQ(internal_unit(Sensor::gyroscope), SampleUnit::deg_per_hour);
  // A rate-only API refuses an acceleration.
  EXPECT_THROW(to_deg_per_hour(SampleUnit::milli_g), UsageError);
}

TEST(Units, AccelerometerTextSaysMetresPerSecondSquared) {
  EXPECT_EQ(in_sensor_units("N [deg/h/sqrt(Hz)], (deg/h)^2/Hz", Sensor::accelerometer),
            "N [m/s^2/sqrt(Hz)], (m/s^2)^2/Hz");
  EXPECT_EQ(in_sensor_units("white rate noise (angle random walk = N/60 deg/sqrt(h))",
                            Sensor::accelerometer),
            "white acceleration noise (velocity random walk = 60 N m/s/sqrt(h))");
  EXPECT_EQ(in_sensor_units("rate random walk, 3 deg/h", Sensor::gyroscope),
            "rate random walk, 3 deg/h");
}

}  // namespace
}  // namespace foglab
