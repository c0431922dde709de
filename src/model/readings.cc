#include "foglab/model/readings.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/units.h"

namespace foglab::model {
namespace {

constexpr double kSlopeTolerance = 0.2;

void check(std::span<const double> x, std::span<const double> y, const char* what) {
  if (x.size() != y.size() || x.size() < 2) {
    throw UsageError(fmt::format("{}: need at least 2 points of equal count, got {} and {}", what,
                                 x.size(), y.size()));
  }
}

// The longest run of adjacent points over which every local slope of log y
// against log x lies within the tolerance of `slope`, at least three points
// (two segments) long. Returns the points [begin, end), empty when none.
std::pair<std::size_t, std::size_t> longest_run(std::span<const double> x,
                                                std::span<const double> y, double slope) {
  const std::size_t segments = x.size() - 1;
  auto ok = [&](std::size_t i) {
    return y[i] > 0 && y[i + 1] > 0 && x[i] > 0 && x[i + 1] > x[i] &&
           std::fabs(std::log(y[i + 1] / y[i]) / std::log(x[i + 1] / x[i]) - slope) <=
               kSlopeTolerance;
  };
  std::size_t best_begin = 0, best_end = 0;
  for (std::size_t i = 0; i < segments;) {
    if (!ok(i)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < segments && ok(j)) ++j;  // segments i .. j-1: points i .. j
    if (j + 1 - i > best_end - best_begin) {
      best_begin = i;
      best_end = j + 1;
    }
    i = j;
  }
  if (best_end - best_begin < 3) return {0, 0};
  return {best_begin, best_end};
}

// Geometric mean of y x^(-slope) over the run, times at^slope: the value at
// x = at of the line of that slope through the run.
std::optional<double> line_value(std::span<const double> x, std::span<const double> y,
                                 double slope, double at) {
  const auto [begin, end] = longest_run(x, y, slope);
  if (end == begin) return std::nullopt;
  double sum = 0.0;
  for (std::size_t i = begin; i < end; ++i) sum += std::log(y[i]) - slope * std::log(x[i]);
  return std::exp(sum / static_cast<double>(end - begin) + slope * std::log(at));
}

}  // namespace

AdevReadings read_adev(std::span<const double> tau_s, std::span<const double> adev_deg_h,
                       double from_tau_s) {
  check(tau_s, adev_deg_h, "read_adev");
  AdevReadings r;
  r.N = line_value(tau_s, adev_deg_h, -0.5, 1.0);  // AVAR = N^2/tau: N = ADEV(1 s)
  r.K = line_value(tau_s, adev_deg_h, +0.5, 3.0);  // AVAR = K^2 tau/3: K = ADEV(3 s)
  // The first tau read: the first at or beyond from_tau_s (to rounding).
  std::size_t first = 0;
  while (first < tau_s.size() && tau_s[first] < from_tau_s * (1.0 - 1e-9)) ++first;
  if (first == tau_s.size()) first = 0;
  if (first > 0) r.from_tau_s = from_tau_s;
  const auto min =
      std::min_element(adev_deg_h.begin() + static_cast<std::ptrdiff_t>(first), adev_deg_h.end());
  const auto i = static_cast<std::size_t>(min - adev_deg_h.begin());
  r.bias_instability_deg_h = *min;
  r.bias_instability_tau_s = tau_s[i];
  r.minimum_at_edge = i == first || i + 1 == adev_deg_h.size();
  const auto lowest = std::min_element(adev_deg_h.begin(), adev_deg_h.end());
  if (*lowest < *min) {
    r.lower_inside_filter_deg_h = *lowest;
    r.lower_inside_filter_tau_s = tau_s[static_cast<std::size_t>(lowest - adev_deg_h.begin())];
  }
  return r;
}

Message minimum_inside_filter_note(const AdevReadings& a) {
  if (!std::isfinite(a.lower_inside_filter_deg_h)) return {};
  return Message(Text::note_minimum_inside_filter, a.lower_inside_filter_deg_h,
                 a.lower_inside_filter_tau_s, a.from_tau_s, a.bias_instability_deg_h,
                 a.bias_instability_tau_s);
}

PsdReadings read_psd(std::span<const double> frequency_hz, std::span<const double> psd) {
  check(frequency_hz, psd, "read_psd");
  PsdReadings r;
  const auto [flat_begin, flat_end] = longest_run(frequency_hz, psd, 0.0);
  if (flat_end > flat_begin) {
    double sum = 0.0;
    for (std::size_t i = flat_begin; i < flat_end; ++i) sum += std::log(psd[i]);
    r.N = std::sqrt(std::exp(sum / static_cast<double>(flat_end - flat_begin)));
  }
  // The -2 slope: the low-frequency bins standing well above the white level
  // (a factor 4), below the flat part. The PSD estimate scatters too much
  // there for point-to-point slopes, so the slope is a least-squares fit over
  // the region, and must be -2 +- 0.5 (a Gauss-Markov plateau is flatter).
  // S = K^2/(2 pi f)^2, so each bin implies K = 2 pi f sqrt(S).
  const std::size_t stop = flat_end > flat_begin ? flat_begin : frequency_hz.size() / 3;
  const double floor = r.N ? 4.0 * *r.N * *r.N : 0.0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0, k_log = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < stop; ++i) {
    if (!(frequency_hz[i] > 0.0) || !(psd[i] > floor)) continue;
    const double x = std::log(frequency_hz[i]);
    const double y = std::log(psd[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    k_log += std::log(2.0 * std::numbers::pi * frequency_hz[i]) + 0.5 * y;
    ++count;
  }
  if (count >= 3) {
    const double c = static_cast<double>(count);
    const double slope = (c * sxy - sx * sy) / (c * sxx - sx * sx);
    if (std::fabs(slope + 2.0) <= 0.5) r.K = std::exp(k_log / c);
  }
  return r;
}

}  // namespace foglab::model
