// foglab — the quantisation of a sensor's output word (the LSB each sample
// is rounded to), found from the samples themselves.
//
// A digital gyro outputs integers times a scale factor: every sample is a
// whole number of LSBs q from some offset. Rounding to q adds white noise of
// variance q^2 / 12 per sample (when the noise spans several LSBs), i.e. a
// white rate noise of level q / sqrt(12 fs) [deg/h/sqrt(Hz)] inside the
// fitted N, and an Allan deviation q / sqrt(12 m) at tau = m tau0. This is
// not IEEE Std 952's angle quantisation Q (the angle readout's step, an
// Allan variance 3 Q^2 / tau^2), which stays a term of the noise model.
//
// Found when the record's distinct values are few (at most a quarter of the
// samples looked at) and every gap between neighbouring distinct values is
// a whole multiple of the smallest gap (to 1e-6 of it, and at least 99 % of
// the gaps exactly one or more LSBs).
//
// The rounding error is white, uniform (variance q^2 / 12) and independent
// of the signal when the signal moves by enough LSBs from sample to sample:
// for Gaussian noise of standard deviation sigma the departures fall as
// exp(-2 pi^2 sigma^2 / q^2) (Widrow's quantisation theorem; Widrow and
// Kollar, "Quantization Noise", Cambridge 2008, ch. 4 and 5), 0.7 % at
// q = 2 sigma and 11 % at q = 3 sigma. The rounding is taken as noise-like
// when q <= 2 sigma, sigma being the samples' own sample-to-sample spread
// (the rms of their first differences over sqrt(2), the rounding's q^2/12
// taken out): a slow drift or a random walk does not make a coarse word
// noise-like, and a sensor's output filter, which makes neighbours alike,
// makes the test stricter, as it should.
#pragma once

#include <cstdint>
#include <span>

namespace foglab::model {

struct OutputQuantisation {
  bool detected = false;
  double lsb_deg_h = 0.0;            ///< [deg/h] the step q
  std::int64_t distinct_values = 0;  ///< among the samples looked at
  std::int64_t samples_examined = 0;
  /// [deg/h/sqrt(Hz)] the white level of the rounding noise, q / sqrt(12 fs).
  double white_level_deg_h_sqrt_hz = 0.0;
  /// [deg/h] the standard deviation of the samples examined.
  double sample_sd_deg_h = 0.0;
  /// [deg/h] their sample-to-sample spread: the rms of the first
  /// differences over sqrt(2), with the rounding's q^2 / 12 taken out (the
  /// white part of the spread, before rounding).
  double step_sd_deg_h = 0.0;
  /// Whether the rounding is noise-like: q <= 2 step_sd_deg_h (above, the
  /// output sticks to its codes and the rounding is not white noise).
  bool noise_like = false;
  /// How far the rounded samples' white variance can depart from the
  /// sensor's plus q^2 / 12, as a share of the sensor's: 4 exp(-2 pi^2
  /// sd^2 / q^2) with sd = step_sd_deg_h. It is the covariance of the
  /// signal with its rounding error (Sheppard's correction for Gaussian
  /// noise, its first Fourier term: -2 sd^2 exp(..) cos(2 pi mu / q), twice
  /// in the variance), whose sign depends on where the mean mu sits on the
  /// grid: 0.9 % at q = 1.8 sd, 2.9 % at q = 2 sd.
  double white_variance_departure = 0.0;
};

/// The grid that sorted (ascending) values lie on: their distinct values,
/// those equal to 1e-9 of the largest magnitude merged (a unit conversion
/// leaves the last bits of a whole count of steps uneven), and, when there
/// are at least 3 and at least 99 % of the gaps between neighbours are
/// whole multiples of the smallest (to 1e-6 of it), that smallest gap, the
/// step; else a step of 0.
struct ValueGrid {
  std::int64_t distinct_values = 0;
  double step = 0.0;
};
ValueGrid value_grid(std::span<const double> sorted);

/// Looks at up to `max_samples` samples of `rate_deg_h` (the first ones)
/// sampled at `sample_rate_hz`.
OutputQuantisation find_output_quantisation(std::span<const double> rate_deg_h,
                                            double sample_rate_hz,
                                            std::size_t max_samples = 200000);

}  // namespace foglab::model
