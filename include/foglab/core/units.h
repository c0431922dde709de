// foglab — units of angular rate and the kind of an input record.
//
// Inside foglab every rate is in deg/h, every time in s, every temperature in
// degC (docs/conventions.md section 1). Inputs in other units are converted once, on
// reading. An angle (phase) record is expressed in [rate unit x s]: deg for
// deg/s, rad for rad/s, and (deg/h)*s for the default deg/h, so that the
// rate is the angle's increment divided by the sample interval.
#pragma once

#include <numbers>
#include <string>
#include <string_view>

namespace foglab {

/// Unit of an angular-rate record.
enum class RateUnit {
  deg_per_hour,    ///< "deg/h" (foglab's internal unit)
  deg_per_second,  ///< "deg/s"
  rad_per_second,  ///< "rad/s"
};

/// "deg/h", "deg/s" or "rad/s".
std::string_view to_string(RateUnit unit);
/// Parses "deg/h", "deg/s", "rad/s" (also "dph", "dps", "rps");
/// throws UsageError listing the accepted names otherwise.
RateUnit rate_unit_from_string(std::string_view text);
/// Factor that converts a value in `unit` to deg/h.
double to_deg_per_hour(RateUnit unit);

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
