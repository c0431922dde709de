// foglab — grids of averaging times for the Allan family.
//
//   octave          m = 1, 2, 4, 8, ...
//   decade          m = 1, 2, 4, 10, 20, 40, 100, ... (1-2-4 per decade, as Stable32)
//   N-per-decade    m = round(10^(k/N)), duplicates removed (e.g. "10-per-decade")
//   all             every m = 1, 2, 3, ... (bounded: at most kAllGridMaxFactors,
//                   and at most kAllGridWorkSamples / N factors, at least 100,
//                   so that a long record does not take hours)
//   list            explicit averaging times in seconds, honoured as given
//                   (each rounded to the nearest multiple of the sample interval)
//
// Generated grids stop where fewer than `min_clusters` non-overlapping
// clusters, floor(M / m) with M = N - 1 rate samples, remain (default 10: the
// lab manual's L_m >= 10) and where the statistic is no longer defined.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace foglab::stats {

enum class TauGridKind { octave, decade, per_decade, all, list };

/// Upper bound on the number of factors of the "all" grid.
inline constexpr std::int64_t kAllGridMaxFactors = 10000;
/// Work bound of the "all" grid: factors x phase points.
inline constexpr double kAllGridWorkSamples = 2e10;

struct TauGrid {
  TauGridKind kind = TauGridKind::octave;
  int per_decade = 10;                ///< for per_decade (> 0)
  std::vector<double> taus_s;         ///< [s] for list (> 0)
  std::int64_t min_clusters = 10;     ///< generated grids: floor(M/m) >= this (>= 1)
};

/// Parses "octave", "decade", "all", "N-per-decade" or a comma-separated
/// list of seconds ("1,10,100"); throws UsageError otherwise.
TauGrid parse_tau_grid(std::string_view text);
/// Text form, e.g. "octave", "5-per-decade", "1,10,100".
std::string to_string(const TauGrid& grid);

/// The averaging factors of `grid` for N phase points at `sample_rate_hz`,
/// none above `max_factor`. Generated grids are truncated there; an explicit
/// list throws DataError naming the first tau above it. Throws UsageError for
/// a non-positive tau or one below the sample interval.
std::vector<std::int64_t> averaging_factors(const TauGrid& grid, std::int64_t phase_points,
                                            double sample_rate_hz, std::int64_t max_factor);

}  // namespace foglab::stats
