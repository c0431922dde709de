// foglab — the lab manual's graphical readings, done by the program.
//
// Lab 2 asks the student to read the noise parameters off two plots
// (manual section 2.2, Figs. 18, 21, 22; IEEE Std 952-1997 Annex C):
//   * from the Allan deviation: the -1/2 line's value at tau = 1 s is the
//     white-noise density N [deg/h/sqrt(Hz)] (AVAR = N^2/tau); the +1/2
//     line's value at tau = 3 s is the Wiener intensity K [deg/h/sqrt(s)]
//     (AVAR = K^2 tau/3); the minimum is the bias instability and its tau
//     (read beyond the output filter's memory where one was found: the
//     filter, not the gyro's noise, lowers the first taus' deviation);
//   * from the two-sided PSD: the level of the flat part is N^2, and the -2
//     slope continued to 1 Hz gives K^2/(2 pi)^2 (S = K^2/(2 pi f)^2).
// The program finds each line where the curve actually has that slope: the
// stretch of adjacent points (three at least) whose local log-log slope lies
// within +-0.2 of the ideal (the longest such run), and averages the implied
// parameter over it in log space. On the PSD the low-frequency -2 region
// scatters too much for point-to-point slopes: there the bins standing a
// factor 4 above the white level are taken, and their least-squares slope
// must be -2 +- 0.5. A slope that never shows gives no reading (null), which
// is itself the answer "not visible in this record".
#pragma once

#include <limits>
#include <optional>
#include <span>

#include "foglab/core/language.h"

namespace foglab::model {

struct AdevReadings {
  std::optional<double> N;          ///< [deg/h/sqrt(Hz)] -1/2 line at tau = 1 s
  std::optional<double> K;          ///< [deg/h/sqrt(s)] +1/2 line at tau = 3 s
  /// [deg/h] minimum of the deviation over the taus from `from_tau_s` on
  double bias_instability_deg_h = 0.0;
  double bias_instability_tau_s = 0.0;  ///< where it is [s]
  /// The minimum is the last (or the first read) point: the true minimum
  /// may lie outside the taus read.
  bool minimum_at_edge = false;
  /// [s] `from_tau_s` as read_adev() used it: 0 when every tau was read
  /// (none given, or no tau reaches it).
  double from_tau_s = 0.0;
  /// [deg/h] and [s]: the deviation's minimum over all taus when it lies
  /// below `from_tau_s` and under the reading (inside an output filter's
  /// memory); NaN otherwise.
  double lower_inside_filter_deg_h = std::numeric_limits<double>::quiet_NaN();
  double lower_inside_filter_tau_s = std::numeric_limits<double>::quiet_NaN();
};

struct PsdReadings {
  std::optional<double> N;  ///< [deg/h/sqrt(Hz)] sqrt of the flat level
  std::optional<double> K;  ///< [deg/h/sqrt(s)] from the -2 slope at 1 Hz
};

/// Readings from an (overlapping) Allan deviation curve: tau [s] increasing,
/// dev [deg/h]; the minimum over the taus from `from_tau_s` [s] on (all of
/// them when none is that long: NoiseFitResult::filter_memory_end_tau_s).
/// Throws UsageError for fewer than 2 points or mismatched sizes.
AdevReadings read_adev(std::span<const double> tau_s, std::span<const double> adev_deg_h,
                       double from_tau_s = 0.0);

/// The note that the deviation is lower inside the output filter's memory
/// than the reading beyond it, with both values; empty when it is not.
Message minimum_inside_filter_note(const AdevReadings& readings);

/// Readings from a two-sided rate PSD (best a log-smoothed one): frequency
/// [Hz] increasing, psd [(deg/h)^2/Hz]. Same errors.
PsdReadings read_psd(std::span<const double> frequency_hz, std::span<const double> psd);

}  // namespace foglab::model
