// foglab — time-interval error statistics of an angle (phase) record.
//
// For an angle record x_0 .. x_{N-1} (for a gyro: the integrated rate; for a
// clock: the time error) and an observation window of m sample intervals:
//   * MTIE(m): the largest peak-to-peak excursion of x within any window of
//     m + 1 consecutive points, max_i (max_{i..i+m} x - min_{i..i+m} x), over
//     N - m windows (NIST SP 1065 section 5.2.14; ITU-T G.810);
//   * TIE rms(m): sqrt( sum_i (x_{i+m} - x_i)^2 / (N - m) ), the rms of the
//     angle's change over m intervals (SP 1065 section 5.2.15).
// Both are in the record's own unit, not divided by tau. They match
// Stable32's tables for PHASE.DAT to their printed digits (its "MTIE (Fast)"
// at the factors 2^k - 1 is exact there).
//
// Cost: MTIE keeps the window's running maximum and minimum in two
// monotonic queues, O(N) per factor whatever m (the textbook scan is
// O(N m)); TIE rms is one O(N) pass per factor. Factors run in parallel.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "foglab/core/units.h"
#include "foglab/stats/tau_grid.h"

namespace foglab::stats {

/// MTIE at each window factor m (1 <= m <= N - 1), in the unit of `angle`.
/// Throws DataError naming the factor when one is out of range.
std::vector<double> mtie(std::span<const double> angle, std::span<const std::int64_t> factors);

/// TIE rms at each factor m (1 <= m <= N - 1), in the unit of `angle`.
std::vector<double> tie_rms(std::span<const double> angle, std::span<const std::int64_t> factors);

/// The number of windows (MTIE) or differences (TIE rms) at factor m: N - m.
inline std::int64_t time_error_count(std::int64_t points, std::int64_t m) { return points - m; }

enum class TimeErrorKind { mtie, tie_rms };
/// "mtie", "tierms".
std::string_view to_string(TimeErrorKind kind);
/// Whether `text` names one ("mtie", "tierms"), and which.
bool is_time_error_kind(std::string_view text);
TimeErrorKind time_error_kind_from_string(std::string_view text);

/// A time-error statistic on the factors of a tau grid.
struct TimeErrorResult {
  TimeErrorKind kind = TimeErrorKind::mtie;
  InputKind input = InputKind::rate;
  double sample_rate_hz = 0.0;
  std::int64_t angle_points = 0;
  std::vector<std::int64_t> m, n;
  std::vector<double> tau_s;
  std::vector<double> value;  ///< in the angle's unit: the rate's unit times s
};

/// The statistic of a record: a rate record is integrated as it is, x_0 = 0,
/// x_{k+1} = x_k + y_k / fs (compensated), its bias kept: MTIE is then the
/// largest angle excursion the output gives over any window of tau, the
/// drift of the bias included (take the bias out first to see the noise
/// alone); an angle record is used as given. Generated grids stop where fewer
/// than grid.min_clusters windows of m intervals fit; the largest factor is
/// N - 1. Throws DataError for fewer than 2 angle points.
TimeErrorResult time_error(std::span<const double> samples, double sample_rate_hz, InputKind input,
                           TimeErrorKind kind, const TauGrid& grid);

}  // namespace foglab::stats
