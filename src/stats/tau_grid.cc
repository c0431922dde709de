#include "foglab/stats/tau_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <set>

#include "foglab/core/error.h"

namespace foglab::stats {
namespace {

double parse_seconds(std::string_view item, std::string_view whole) {
  double value = 0.0;
  const char* first = item.data();
  const char* last = item.data() + item.size();
  while (first < last && *first == ' ') ++first;
  while (last > first && last[-1] == ' ') --last;
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || ptr != last) {
    throw UsageError(fmt::format(
        "parse_tau_grid(\"{}\"): expected octave, decade, all, N-per-decade or a comma-separated "
        "list of seconds, but '{}' is not a number",
        whole, item));
  }
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw UsageError(fmt::format("parse_tau_grid(\"{}\"): tau {} s is not positive", whole, item));
  }
  return value;
}

}  // namespace

TauGrid parse_tau_grid(std::string_view text) {
  TauGrid grid;
  if (text == "octave") return grid;
  if (text == "decade") {
    grid.kind = TauGridKind::decade;
    return grid;
  }
  if (text == "all") {
    grid.kind = TauGridKind::all;
    return grid;
  }
  constexpr std::string_view kSuffix = "-per-decade";
  if (text.size() > kSuffix.size() && text.ends_with(kSuffix)) {
    const std::string_view number = text.substr(0, text.size() - kSuffix.size());
    int n = 0;
    const auto [ptr, ec] = std::from_chars(number.data(), number.data() + number.size(), n);
    if (ec != std::errc() || ptr != number.data() + number.size() || n < 1 || n > 1000) {
      throw UsageError(fmt::format(
          "parse_tau_grid(\"{}\"): the number of points per decade must be an integer from 1 to "
          "1000",
          text));
    }
    grid.kind = TauGridKind::per_decade;
    grid.per_decade = n;
    return grid;
  }
  grid.kind = TauGridKind::list;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? text.size() : comma;
    grid.taus_s.push_back(parse_seconds(text.substr(start, end - start), text));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return grid;
}

std::string to_string(const TauGrid& grid) {
  switch (grid.kind) {
    case TauGridKind::octave: return "octave";
    case TauGridKind::decade: return "decade";
    case TauGridKind::all: return "all";
    case TauGridKind::per_decade: return fmt::format("{}-per-decade", grid.per_decade);
    case TauGridKind::list: return fmt::format("{}", fmt::join(grid.taus_s, ","));
  }
  return "?";
}

std::vector<std::int64_t> averaging_factors(const TauGrid& grid, std::int64_t phase_points,
                                            double sample_rate_hz, std::int64_t max_factor) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw UsageError(fmt::format("sample rate {} Hz is not positive", sample_rate_hz));
  }
  if (grid.min_clusters < 1) {
    throw UsageError(fmt::format("TauGrid::min_clusters {} must be at least 1", grid.min_clusters));
  }
  std::vector<std::int64_t> factors;
  if (grid.kind == TauGridKind::list) {
    for (const double tau_s : grid.taus_s) {
      if (!(tau_s > 0.0) || !std::isfinite(tau_s)) {
        throw UsageError(fmt::format("tau {} s is not positive", tau_s));
      }
      const double exact = tau_s * sample_rate_hz;
      const auto m = static_cast<std::int64_t>(std::llround(exact));
      if (m < 1) {
        throw UsageError(fmt::format("tau {} s is shorter than the sample interval {} s", tau_s,
                                     1.0 / sample_rate_hz));
      }
      if (m > max_factor) {
        throw DataError(fmt::format(
            "tau {} s needs more samples than the record has: {} samples allow tau up to {} s "
            "for this statistic",
            tau_s, phase_points, static_cast<double>(max_factor) / sample_rate_hz));
      }
      factors.push_back(m);
    }
    return factors;  // honoured as given, duplicates and order included
  }
  const std::int64_t rate_samples = phase_points - 1;
  const std::int64_t cluster_limit = rate_samples / grid.min_clusters;
  const std::int64_t limit = std::min(max_factor, cluster_limit);
  switch (grid.kind) {
    case TauGridKind::octave:
      for (std::int64_t m = 1; m <= limit; m *= 2) factors.push_back(m);
      break;
    case TauGridKind::decade:
      for (std::int64_t decade = 1; decade <= limit; decade *= 10) {
        for (const std::int64_t k : {1, 2, 4}) {
          if (decade * k <= limit) factors.push_back(decade * k);
        }
      }
      break;
    case TauGridKind::per_decade: {
      if (grid.per_decade < 1) {
        throw UsageError(fmt::format("{} points per decade: expected at least 1", grid.per_decade));
      }
      std::set<std::int64_t> unique;
      for (int k = 0;; ++k) {
        const double value = std::pow(10.0, static_cast<double>(k) / grid.per_decade);
        const auto m = static_cast<std::int64_t>(std::llround(value));
        if (m > limit) break;
        unique.insert(m);
      }
      factors.assign(unique.begin(), unique.end());
      break;
    }
    case TauGridKind::all: {
      const auto by_work = static_cast<std::int64_t>(
          std::max(100.0, kAllGridWorkSamples / static_cast<double>(phase_points)));
      const std::int64_t count = std::min({limit, kAllGridMaxFactors, by_work});
      for (std::int64_t m = 1; m <= count; ++m) factors.push_back(m);
      break;
    }
    case TauGridKind::list: break;
  }
  return factors;
}

}  // namespace foglab::stats
