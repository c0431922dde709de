#include "foglab/core/units.h"

#include <string>

#include "foglab/core/error.h"
#include "foglab/core/text.h"

namespace foglab {
std::string_view to_string(Sensor sensor) {
  return sensor == Sensor::gyroscope ? "gyroscope" : "accelerometer";
}

std::string in_sensor_units(std::string_view text, Sensor sensor, Language language) {
  std::string out(text);
  if (sensor == Sensor::gyroscope) return out;
  auto replace_all = [&out](std::string_view from, std::string_view to) {
    for (std::size_t at = out.find(from); at != std::string::npos;
         at = out.find(from, at + to.size())) {
      out.replace(at, from.size(), to);
    }
  };
  if (language == Language::ru) {
    replace_all("случайное блуждание угловой скорости", "случайное блуждание ускорения");
    replace_all("°/ч", "м/с²");
    return out;
  }
  // The words first (they hold units), then the unit.
  replace_all("angle random walk = N/60 deg/sqrt(h)", "velocity random walk = 60 N m/s/sqrt(h)");
  replace_all("white rate noise", "white acceleration noise");
  replace_all("rate random walk", "acceleration random walk");
  replace_all("rate ramp", "acceleration ramp");
  replace_all("angle quantisation", "velocity quantisation");
  replace_all("deg/h", "m/s^2");
  return out;
}

std::string_view to_string(SampleUnit unit) {
  switch (unit) {
    case SampleUnit::deg_per_hour:
      return "deg/h";
    case SampleUnit::deg_per_second:
      return "deg/s";
    case SampleUnit::rad_per_second:
      return "rad/s";
    case SampleUnit::m_per_s2:
      return "m/s^2";
    case SampleUnit::standard_gravity:
      return "g";
    case SampleUnit::milli_g:
      return "mg";
  }
  return "?";
}

SampleUnit rate_unit_from_string(std::string_view text) {
  // "g" and "mg" are case-sensitive: "G" and "MG" are not units of acceleration.
  if (text == "g") return SampleUnit::standard_gravity;
  if (text == "mg" || text == "milli-g") return SampleUnit::milli_g;
  const std::string t = ascii_lower(text);
  if (t == "deg/h" || t == "dph" || t == "deg/hr") return SampleUnit::deg_per_hour;
  if (t == "deg/s" || t == "dps" || t == "deg/sec") return SampleUnit::deg_per_second;
  if (t == "rad/s" || t == "rps" || t == "rad/sec") return SampleUnit::rad_per_second;
  if (t == "m/s^2" || t == "m/s2" || t == "mps2" || t == "m/s/s") return SampleUnit::m_per_s2;
  throw UsageError("unknown unit '" + std::string(text) +
                   "': expected deg/h, deg/s or rad/s (gyroscopes), m/s^2, g or mg "
                   "(accelerometers)");
}

Sensor sensor_of(SampleUnit unit) {
  switch (unit) {
    case SampleUnit::deg_per_hour:
    case SampleUnit::deg_per_second:
    case SampleUnit::rad_per_second:
      return Sensor::gyroscope;
    case SampleUnit::m_per_s2:
    case SampleUnit::standard_gravity:
    case SampleUnit::milli_g:
      return Sensor::accelerometer;
  }
  return Sensor::gyroscope;
}

SampleUnit internal_unit(Sensor sensor) {
  return sensor == Sensor::gyroscope ? SampleUnit::deg_per_hour : SampleUnit::m_per_s2;
}

double to_internal_unit(SampleUnit unit) {
  switch (unit) {
    case SampleUnit::deg_per_hour:
      return 1.0;
    case SampleUnit::deg_per_second:
      return kSecondsPerHour;
    case SampleUnit::rad_per_second:
      return kDegPerRad * kSecondsPerHour;
    case SampleUnit::m_per_s2:
      return 1.0;
    case SampleUnit::standard_gravity:
      return kStandardGravity;
    case SampleUnit::milli_g:
      return kStandardGravity / 1000.0;
  }
  return 1.0;
}

double to_deg_per_hour(SampleUnit unit) {
  if (sensor_of(unit) != Sensor::gyroscope) {
    throw UsageError("'" + std::string(to_string(unit)) +
                     "' is a unit of acceleration, not of angular rate");
  }
  return to_internal_unit(unit);
}

std::string_view to_string(InputKind kind) {
  return kind == InputKind::rate ? "rate" : "phase";
}

InputKind input_kind_from_string(std::string_view text) {
  const std::string t = ascii_lower(text);
  if (t == "rate") return InputKind::rate;
  if (t == "phase" || t == "angle") return InputKind::phase;
  throw UsageError("unknown input kind '" + std::string(text) +
                   "': expected rate or phase");
}

}  // namespace foglab
