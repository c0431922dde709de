// foglab — units of angular rate and acceleration, the sensor a unit
// belongs to, and the kind of an input record.
//
// Inside foglab every rate is in deg/h, every acceleration in m/s^2, every
// time in s, every temperature in degC (docs/conventions.md section 1).
// Inputs in other units are converted once, on reading. The statistics and
// the noise model do not depend on the unit (they scale with it), so an
// accelerometer channel is analysed like a gyroscope's, in m/s^2, and only
// its report speaks in accelerometer terms. An angle (phase) record is expressed in [rate unit x
// s]: deg for deg/s, rad for rad/s, and (deg/h)*s for the default deg/h, so that the rate is the
// angle's increment divided by the sample interval.
#pragma once

#include <numbers>
#include <string>
#include <string_view>

#include "foglab/core/language.h"

namespace foglab {

/// What a channel measures.
enum class Sensor {
  gyroscope,      ///< angular rate, analysed in deg/h
  accelerometer,  ///< specific force, analysed in m/s^2
};
/// "gyroscope" or "accelerometer".
std::string_view to_string(Sensor sensor);

/// Unit of a record's samples: an angular rate or an acceleration.
enum class SampleUnit {
  deg_per_hour,      ///< "deg/h" (foglab's internal rate unit)
  deg_per_second,    ///< "deg/s"
  rad_per_second,    ///< "rad/s"
  m_per_s2,          ///< "m/s^2" (foglab's internal acceleration unit)
  standard_gravity,  ///< "g" (9.80665 m/s^2)
  milli_g,           ///< "mg"
};
/// The name the rate-only API had; every unit above is accepted.
using RateUnit = SampleUnit;

/// "deg/h", "deg/s", "rad/s", "m/s^2", "g" or "mg".
std::string_view to_string(SampleUnit unit);
/// Parses the names above (also "dph", "dps", "rps", "m/s2", "mps2",
/// "milli-g"); throws UsageError listing the accepted names otherwise.
SampleUnit rate_unit_from_string(std::string_view text);
/// The sensor whose samples `unit` measures.
Sensor sensor_of(SampleUnit unit);
/// The unit foglab analyses a sensor's samples in: deg/h or m/s^2.
SampleUnit internal_unit(Sensor sensor);
/// Factor that converts a value in `unit` to its sensor's internal unit
/// (deg/h or m/s^2).
double to_internal_unit(SampleUnit unit);
/// Factor that converts a rate in `unit` to deg/h; throws UsageError for an
/// acceleration unit.
double to_deg_per_hour(SampleUnit unit);

/// `text` (a unit, a label, a sentence foglab wrote) with the rate unit deg/h
/// in the internal unit of `sensor`: unchanged for a gyroscope; for an
/// accelerometer every deg/h becomes m/s^2, so that the noise units built
/// on it follow (deg/h/sqrt(Hz) -> m/s^2/sqrt(Hz), (deg/h)^2/Hz ->
/// (m/s^2)^2/Hz, deg/h/s -> m/s^2/s), and the gyroscope's names of the
/// noise terms become the accelerometer's (white rate noise -> white
/// acceleration noise, angle random walk N/60 -> velocity random walk 60 N,
/// rate random walk -> acceleration random walk, ...). A Russian text the
/// same in its words: °/ч -> м/с², случайное блуждание
/// угловой скорости -> случайное блуждание ускорения.
std::string in_sensor_units(std::string_view text, Sensor sensor, Language language = Language::en);

/// [m/s^2] The standard acceleration of gravity, 1 g (3rd CGPM, 1901; ISO
/// 80000-3), by which g and mg are converted.
inline constexpr double kStandardGravity = 9.80665;

/// What the samples of a record are.
enum class InputKind {
  rate,   ///< angular rate samples (the analogue of fractional frequency)
  phase,  ///< integrated angle samples (the analogue of phase/time error)
};

/// "rate" or "phase".
std::string_view to_string(InputKind kind);
/// Parses "rate" or "phase" (also "angle"); throws UsageError otherwise.
InputKind input_kind_from_string(std::string_view text);

inline constexpr double kSecondsPerHour = 3600.0;

/// The sample rates foglab takes [Hz], from files, options and the
/// generator: one sample in 11.6 days to 1 GHz. Outside them a rate is a
/// mistake (an `f` of 1e300 or 1e-300 in a file), and the statistics'
/// frequencies and times would overflow.
inline constexpr double kMinSampleRateHz = 1e-6;
inline constexpr double kMaxSampleRateHz = 1e9;

/// The largest magnitude of a sample [deg/h] (or degC) foglab reads or
/// generates: far beyond any gyro's rate or temperature, and small enough
/// that the sums of squares and powers the statistics form over a record
/// cannot overflow (1e308 would).
inline constexpr double kMaxSampleMagnitude = 1e30;
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;

}  // namespace foglab
