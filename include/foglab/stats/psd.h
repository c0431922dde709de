// foglab — power spectral density of a rate record by Welch's method.
//
// Estimator: Welch (1967) averaged, modified periodograms: segments of
// `segment_length` samples with a periodic Hann window and 50 % overlap by default,
// each segment's mean removed, FFT by FFTW (one plan made per call and
// reused for every segment).
//
// Sidedness (docs/conventions.md section 5): foglab reports the TWO-SIDED rate PSD S(f) at the
// non-negative frequencies f_k = k fs / L, k = 1 .. L/2 (the DC bin is
// dropped), so that the density integrates to the variance over
// [-fs/2, fs/2]. With this convention white rate noise of density N
// [deg/h/sqrt(Hz)] is flat at N^2, and a Wiener rate random walk of
// intensity K [deg/h/sqrt(s)] follows K^2 / (2 pi f)^2 (IEEE Std 952-1997,
// Annex C). Units: (deg/h)^2/Hz; sqrt_psd in deg/h/sqrt(Hz).
//
// For display, log_smooth() averages the estimate in bins of equal width in
// log10(f) (the lab manual's SpSm function does the same job).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "foglab/core/gaps.h"

namespace foglab::stats {

inline constexpr double kMaxWelchOverlap = 0.95;

struct WelchOptions {
  /// Samples per segment; 0 chooses the largest power of two not above
  /// N/4 (at least 16, at most N, at most 2^20). Must be >= 16 and <= N when
  /// given.
  std::size_t segment_length = 0;
  /// Fraction of a segment shared with the next, in [0, kMaxWelchOverlap]
  /// (beyond it segments add FFT work, not information: 0.999999 had
  /// meant a million FFTs for a record of a few).
  double overlap = 0.5;
};

struct PsdResult {
  std::vector<double> frequency_hz;  ///< [Hz] k fs / L, k = 1 .. L/2
  std::vector<double> psd;           ///< two-sided [(unit)^2/Hz]
  std::vector<double> sqrt_psd;      ///< [unit/sqrt(Hz)]
  std::size_t segment_length = 0;    ///< [samples]
  std::size_t segments = 0;          ///< number of averaged segments
  double resolution_hz = 0.0;        ///< [Hz] bin spacing fs / L
  double sample_rate_hz = 0.0;       ///< [Hz]
};

/// Welch PSD of `rate` sampled at `sample_rate_hz`. With `gaps` (sorted,
/// core/gaps.h) only segments wholly inside one contiguous stretch are
/// averaged, and the automatic segment length and the limits below apply to
/// the longest stretch. Throws UsageError for a non-positive sample rate, a
/// bad segment length or overlap, or a bad gap list; DataError for a record
/// (longest stretch) shorter than 16 samples.
PsdResult welch_psd(std::span<const double> rate, double sample_rate_hz,
                    const WelchOptions& options = {}, std::span<const Gap> gaps = {});

/// The estimate averaged in bins of equal width in log10(f), `bins_per_decade`
/// per decade (> 0); each output point is the mean PSD of the bins it holds at
/// the geometric mean of their frequencies. Empty bins are skipped.
PsdResult log_smooth(const PsdResult& psd, double bins_per_decade = 20.0);

}  // namespace foglab::stats
