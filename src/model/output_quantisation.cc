// foglab — the output word's LSB (output_quantisation.h).
#include "foglab/model/output_quantisation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace foglab::model {

ValueGrid value_grid(std::span<const double> sorted) {
  ValueGrid grid;
  if (sorted.empty()) return grid;
  const double scale = std::max(std::fabs(sorted.front()), std::fabs(sorted.back()));
  const double same = 1e-9 * std::max(scale, 1e-300);
  std::vector<double> distinct;
  for (double v : sorted) {
    if (distinct.empty() || v - distinct.back() > same) distinct.push_back(v);
  }
  grid.distinct_values = static_cast<std::int64_t>(distinct.size());
  if (distinct.size() < 3) return grid;
  double step = distinct[1] - distinct[0];
  for (std::size_t k = 2; k < distinct.size(); ++k) {
    step = std::min(step, distinct[k] - distinct[k - 1]);
  }
  if (!(step > same)) return grid;
  std::size_t whole = 0;
  for (std::size_t k = 1; k < distinct.size(); ++k) {
    const double multiple = (distinct[k] - distinct[k - 1]) / step;
    if (std::fabs(multiple - std::round(multiple)) < 1e-6 * std::max(1.0, multiple)) ++whole;
  }
  if (whole * 100 < (distinct.size() - 1) * 99) return grid;
  grid.step = step;
  return grid;
}

OutputQuantisation find_output_quantisation(std::span<const double> rate_deg_h,
                                            double sample_rate_hz, std::size_t max_samples) {
  OutputQuantisation q;
  std::vector<double> values;
  values.reserve(std::min(rate_deg_h.size(), max_samples));
  for (double v : rate_deg_h.first(std::min(rate_deg_h.size(), max_samples))) {
    if (std::isfinite(v)) values.push_back(v);
  }
  q.samples_examined = static_cast<std::int64_t>(values.size());
  if (values.size() < 100 || !(sample_rate_hz > 0.0)) return q;
  double mean = 0.0;
  for (double v : values) mean += v;
  mean /= static_cast<double>(values.size());
  double ss = 0.0;
  for (double v : values) ss += (v - mean) * (v - mean);
  q.sample_sd_deg_h = std::sqrt(ss / static_cast<double>(values.size() - 1));
  double squared_steps = 0.0;  // before sorting: neighbours in time
  for (std::size_t k = 1; k < values.size(); ++k) {
    squared_steps += (values[k] - values[k - 1]) * (values[k] - values[k - 1]);
  }
  const double step_variance = 0.5 * squared_steps / static_cast<double>(values.size() - 1);

  std::sort(values.begin(), values.end());
  const ValueGrid grid = value_grid(values);
  q.distinct_values = grid.distinct_values;
  if (grid.step == 0.0 || static_cast<std::size_t>(grid.distinct_values) * 4 > values.size()) {
    return q;
  }
  const double lsb = grid.step;
  q.detected = true;
  q.lsb_deg_h = lsb;
  q.white_level_deg_h_sqrt_hz = lsb / std::sqrt(12.0 * sample_rate_hz);
  q.step_sd_deg_h = std::sqrt(std::max(0.0, step_variance - lsb * lsb / 12.0));
  constexpr double kMostLsbPerSigma = 2.0;  // Widrow: departures 0.7 % at 2 sigma
  q.noise_like = lsb <= kMostLsbPerSigma * q.step_sd_deg_h;
  if (q.step_sd_deg_h > 0.0) {
    const double ratio = q.step_sd_deg_h / lsb;
    q.white_variance_departure =
        4.0 * std::exp(-2.0 * std::numbers::pi * std::numbers::pi * ratio * ratio);
  }
  return q;
}

}  // namespace foglab::model
