// foglab — a quantised temperature channel (temperature_quantisation.h).
#include "foglab/model/temperature_quantisation.h"

#include <algorithm>
#include <cmath>

#include "foglab/model/output_quantisation.h"

namespace foglab::model {

TemperatureQuantisation find_temperature_quantisation(std::span<const double> temperature_c,
                                                      double sample_rate_hz) {
  TemperatureQuantisation q;
  const std::size_t n = temperature_c.size();
  if (n < 100 || !(sample_rate_hz > 0.0) || !std::isfinite(temperature_c[0])) return q;
  // The changes, while they stay at most a quarter of the samples: a
  // channel that moves on most samples is not a staircase, and is left
  // after a quarter of a pass (nothing stored). Then the reading of each run.
  std::size_t changes = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (!std::isfinite(temperature_c[k])) return q;
    if (temperature_c[k] != temperature_c[k - 1] && 4 * ++changes > n) return q;
  }
  std::vector<double> readings{temperature_c[0]};
  readings.reserve(changes + 1);
  for (std::size_t k = 1; k < n; ++k) {
    if (temperature_c[k] != temperature_c[k - 1]) readings.push_back(temperature_c[k]);
  }
  q.changes = static_cast<std::int64_t>(changes);
  q.mean_hold_s = static_cast<double>(n) / static_cast<double>(readings.size()) / sample_rate_hz;
  std::sort(readings.begin(), readings.end());
  const ValueGrid grid = value_grid(readings);
  q.distinct_values = grid.distinct_values;
  if (grid.step == 0.0) return q;
  const double lsb = grid.step;
  q.detected = true;
  q.lsb_c = lsb;
  return q;
}

std::vector<double> reconstruct_quantised_temperature(std::span<const double> temperature_c,
                                                      double lsb_c) {
  const std::size_t n = temperature_c.size();
  std::vector<double> out(temperature_c.begin(), temperature_c.end());
  // The knots: half-way between the samples either side of a change, at the
  // boundary between the two readings. A run of changes back and forth
  // between the same two readings (the sensor's noise while the
  // temperature is near their boundary) is one crossing, at their mean.
  std::vector<double> at, value;
  double low = 0.0, high = 0.0, sum = 0.0;  // the run of changes being gathered
  std::size_t count = 0;
  auto close = [&] {
    if (count == 0) return;
    at.push_back(sum / static_cast<double>(count));
    value.push_back(0.5 * (low + high));
  };
  for (std::size_t k = 1; k < n; ++k) {
    const double a = temperature_c[k - 1], b = temperature_c[k];
    if (a == b) continue;
    if (count == 0 || std::min(a, b) != low || std::max(a, b) != high) {
      close();
      low = std::min(a, b), high = std::max(a, b), sum = 0.0, count = 0;
    }
    sum += static_cast<double>(k) - 0.5;
    ++count;
  }
  close();
  if (at.empty()) return out;
  const double half = 0.5 * lsb_c;
  auto slope = [&](std::size_t i) {  // between knots i and i + 1
    return (value[i + 1] - value[i]) / (at[i + 1] - at[i]);
  };
  const double first_slope = at.size() > 1 ? slope(0) : 0.0;
  const double last_slope = at.size() > 1 ? slope(at.size() - 2) : 0.0;
  std::size_t i = 0;  // the knot at or after k
  for (std::size_t k = 0; k < n; ++k) {
    const double x = static_cast<double>(k);
    while (i < at.size() && at[i] < x) ++i;
    double t = 0.0;
    if (i == 0) {  // before the first change: within the first reading's step
      t = std::clamp(value[0] + first_slope * (x - at[0]), temperature_c[0] - half,
                     temperature_c[0] + half);
    } else if (i == at.size()) {  // after the last
      t = std::clamp(value.back() + last_slope * (x - at.back()), temperature_c[n - 1] - half,
                     temperature_c[n - 1] + half);
    } else {
      t = value[i - 1] + slope(i - 1) * (x - at[i - 1]);
    }
    out[k] = t;
  }
  return out;
}

}  // namespace foglab::model
