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
  /// [deg/h] the standard deviation of the samples examined (q / sd above
  /// about 1 means the rounding is not noise-like: the output sticks).
  double sample_sd_deg_h = 0.0;
};

/// Looks at up to `max_samples` samples of `rate_deg_h` (the first ones)
/// sampled at `sample_rate_hz`.
OutputQuantisation find_output_quantisation(std::span<const double> rate_deg_h,
                                            double sample_rate_hz,
                                            std::size_t max_samples = 200000);

}  // namespace foglab::model
