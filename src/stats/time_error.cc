#include "foglab/stats/time_error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <deque>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/stats/allan.h"

namespace foglab::stats {
namespace {

void check_factors(std::int64_t points, std::span<const std::int64_t> factors,
                   const char* statistic) {
  for (const std::int64_t m : factors) {
    if (m < 1 || m > points - 1) {
      throw DataError(
          fmt::format("{} at factor {} needs more data: {} angle points allow factors "
                      "1 to {}",
                      statistic, m, points, points - 1));
    }
  }
}

// The largest max - min over the windows [i, i + m] of x: the candidates for
// the window's maximum (minimum) are kept in a queue of indices whose values
// decrease (increase); each index enters and leaves each queue once.
double largest_excursion(std::span<const double> x, std::int64_t m) {
  const auto n = static_cast<std::int64_t>(x.size());
  std::deque<std::int64_t> high, low;
  double largest = 0.0;
  for (std::int64_t i = 0; i < n; ++i) {
    while (!high.empty() && x[high.back()] <= x[i]) high.pop_back();
    high.push_back(i);
    while (!low.empty() && x[low.back()] >= x[i]) low.pop_back();
    low.push_back(i);
    if (high.front() < i - m) high.pop_front();
    if (low.front() < i - m) low.pop_front();
    if (i >= m) largest = std::max(largest, x[high.front()] - x[low.front()]);
  }
  return largest;
}

double change_rms(std::span<const double> x, std::int64_t m) {
  const auto n = static_cast<std::int64_t>(x.size());
  CompensatedSum total;
  for (std::int64_t c = 0; c < n - m; c += static_cast<std::int64_t>(kChunkSamples)) {
    const std::int64_t end = std::min(n - m, c + static_cast<std::int64_t>(kChunkSamples));
    double s = 0.0;
#pragma omp simd reduction(+ : s)
    for (std::int64_t i = c; i < end; ++i) {
      const double d = x[i + m] - x[i];
      s += d * d;
    }
    total.add(s);
  }
  return std::sqrt(total.value() / static_cast<double>(n - m));
}

template <typename Statistic>
std::vector<double> per_factor(std::span<const double> x, std::span<const std::int64_t> factors,
                               Statistic statistic) {
  std::vector<double> values(factors.size());
  const auto count = static_cast<std::int64_t>(factors.size());
#pragma omp parallel for schedule(dynamic, 1) if (x.size() > kChunkSamples)
  for (std::int64_t k = 0; k < count; ++k) values[k] = statistic(x, factors[k]);
  return values;
}

}  // namespace

std::vector<double> mtie(std::span<const double> angle, std::span<const std::int64_t> factors) {
  check_factors(static_cast<std::int64_t>(angle.size()), factors, "MTIE");
  return per_factor(angle, factors, largest_excursion);
}

std::vector<double> tie_rms(std::span<const double> angle, std::span<const std::int64_t> factors) {
  check_factors(static_cast<std::int64_t>(angle.size()), factors, "TIE rms");
  return per_factor(angle, factors, change_rms);
}

std::string_view to_string(TimeErrorKind kind) {
  return kind == TimeErrorKind::mtie ? "mtie" : "tierms";
}

bool is_time_error_kind(std::string_view text) { return text == "mtie" || text == "tierms"; }

TimeErrorKind time_error_kind_from_string(std::string_view text) {
  if (text == "mtie") return TimeErrorKind::mtie;
  if (text == "tierms") return TimeErrorKind::tie_rms;
  throw UsageError(fmt::format("unknown time-error statistic '{}': expected mtie or tierms", text));
}

TimeErrorResult time_error(std::span<const double> samples, double sample_rate_hz, InputKind input,
                           TimeErrorKind kind, const TauGrid& grid) {
  detail::check_sample_rate(sample_rate_hz);
  std::vector<double> angle;
  if (input == InputKind::rate) {
    angle.reserve(samples.size() + 1);
    CompensatedSum x;
    angle.push_back(0.0);
    for (const double y : samples) {
      x.add(y / sample_rate_hz);
      angle.push_back(x.value());
    }
  } else {
    angle.assign(samples.begin(), samples.end());
  }
  const auto points = static_cast<std::int64_t>(angle.size());
  if (points < 2) {
    throw DataError(fmt::format("{} needs at least {} {} samples, the record has {}",
                                to_string(kind), input == InputKind::rate ? 1 : 2, to_string(input),
                                samples.size()));
  }
  TimeErrorResult r;
  r.kind = kind;
  r.input = input;
  r.sample_rate_hz = sample_rate_hz;
  r.angle_points = points;
  r.m = averaging_factors(grid, points, sample_rate_hz, points - 1);
  if (r.m.empty()) {
    throw DataError(
        fmt::format("{} {} samples are too few for {} with at least {} windows per "
                    "tau; lower the minimum or list the taus",
                    samples.size(), to_string(input), to_string(kind), grid.min_clusters));
  }
  for (const std::int64_t m : r.m) {
    r.n.push_back(time_error_count(points, m));
    r.tau_s.push_back(static_cast<double>(m) / sample_rate_hz);
  }
  r.value = kind == TimeErrorKind::mtie ? mtie(angle, r.m) : tie_rms(angle, r.m);
  return r;
}

}  // namespace foglab::stats
