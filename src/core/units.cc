#include "foglab/core/units.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "foglab/core/error.h"

namespace foglab {
namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

}  // namespace

std::string_view to_string(RateUnit unit) {
  switch (unit) {
    case RateUnit::deg_per_hour: return "deg/h";
    case RateUnit::deg_per_second: return "deg/s";
    case RateUnit::rad_per_second: return "rad/s";
  }
  return "?";
}

RateUnit rate_unit_from_string(std::string_view text) {
  const std::string t = lower(text);
  if (t == "deg/h" || t == "dph" || t == "deg/hr") return RateUnit::deg_per_hour;
  if (t == "deg/s" || t == "dps" || t == "deg/sec") return RateUnit::deg_per_second;
  if (t == "rad/s" || t == "rps" || t == "rad/sec") return RateUnit::rad_per_second;
  throw UsageError("unknown rate unit '" + std::string(text) +
                   "': expected deg/h, deg/s or rad/s");
}

double to_deg_per_hour(RateUnit unit) {
  switch (unit) {
    case RateUnit::deg_per_hour: return 1.0;
    case RateUnit::deg_per_second: return kSecondsPerHour;
    case RateUnit::rad_per_second: return kDegPerRad * kSecondsPerHour;
  }
  return 1.0;
}

std::string_view to_string(InputKind kind) {
  return kind == InputKind::rate ? "rate" : "phase";
}

InputKind input_kind_from_string(std::string_view text) {
  const std::string t = lower(text);
  if (t == "rate") return InputKind::rate;
  if (t == "phase" || t == "angle") return InputKind::phase;
  throw UsageError("unknown input kind '" + std::string(text) +
                   "': expected rate or phase");
}

}  // namespace foglab
