// foglab — a sensor's output bandwidth as it shows in the Allan variance.
//
// Gyro electronics filter their output before it is sampled (an analog
// anti-alias filter, a digital low-pass, a decimation filter), so
// neighbouring samples of the white rate noise are correlated and the Allan
// deviation of the first few taus falls more slowly than N / sqrt(tau). The
// filter keeps the white level N (its gain at low frequency is 1); it only
// takes variance away at short tau.
//
// foglab's model of it: a fraction phi of the white noise passes a
// first-order low-pass of time constant T (cut-off 1 / (2 pi T)) and the
// output is sampled every tau0. The sampled filtered part is a first-order
// autoregressive sequence with lag-1 correlation rho = exp(-tau0 / T); its
// Allan variance at tau = m tau0, with the white level N^2 kept, is exactly
//
//   AVAR(tau) = N^2 / tau * (1 - phi * rho (1 - rho^m) (3 - rho^m) / (m (1 - rho^2)))
//
// (the variance of an m-average of the sequence less the covariance of two
// neighbouring ones, from its autocovariance r_k = r_0 rho^k). For large m
// the correction is 3 phi rho / (m (1 - rho^2)) = 1.5 phi T / tau when
// T >> tau0, the continuous filter's.
//
// A moving average over k samples (a boxcar decimation filter) is the other
// kind: its samples are correlated over k - 1 lags exactly, r_j = (k - |j|)
// / k^2 of the white level per sample, and its Allan variance follows from
// those sums (the variance of an m-average less the covariance of two
// neighbouring ones), also exactly.
//
// A second-order Butterworth low-pass at a cut-off f_c (digital, by the
// bilinear transform with pre-warping, butterworth_coefficients()) is the
// third: the anti-alias or output filter of much gyro electronics. Its
// samples' autocorrelation a_j is the impulse response's own (summed until
// it is below 1e-16 of the first term), and the same sums as the moving
// average's give its Allan variance exactly, in O(R) for a reach of R
// lags. (The first-order filter and the moving average
// had followed a second-order one only roughly: N 7-19 % high on a
// Butterworth at 10-40 Hz sampled at 100 Hz.)
//
// The filter acts on the output's flicker noise too; flicker_allan_factor()
// gives what it does to the flicker plateau.
//
// The fourth kind is any filter, known only beyond its memory. A real
// sensor's output filter can be a cascade (an anti-alias filter, then a
// decimation filter) that none of the three follows over the first taus.
// For a filter whose samples are correlated over fewer than m lags, with
// autocorrelation r_j, the variance of an m-average is (m sum r_j -
// sum |j| r_j) / m^2 and two neighbouring m-averages share sum_(j>0) j r_j
// / m^2, so its Allan variance is exactly
//
//   AVAR(tau) = N^2 / tau * (1 - c tau0 / tau),  c = 1.5 sum |j| r_j / sum r_j
//
// whatever the filter's shape (c = (k^2 - 1) / (2 k) for a moving average
// over k samples, 3 rho / (1 - rho^2) for the first-order filter, whose
// memory ends within rho^m). The fit uses it from 3 c samples on, once the
// first taus are left out (model/noise_fit.cc, noise_fit_bandwidth.cc; a
// moving average's memory ends at 2 c). Inside 2 c samples, and for the
// cut-off and the power response, the first-order low-pass with the same
// c stands in for the unknown shape.
#pragma once

#include <array>

namespace foglab {

struct SensorBandwidth {
  double filtered_fraction = 0.0;  ///< phi in [0, 1]: the part of N^2 that is filtered
  double time_constant_s = 0.0;    ///< [s] T of the first-order low-pass (0: none)
  /// k > 1: the filter is a moving average over k samples instead (T unused).
  int moving_average_samples = 1;
  /// > 0: the filter is a second-order Butterworth low-pass at this cut-off
  /// [Hz] instead (T and k unused).
  double butterworth_cutoff_hz = 0.0;
  /// > 0: a filter known only beyond its memory instead, by c [samples]
  /// of its factor 1 - phi c tau0 / tau on the white Allan variance (only
  /// the product phi c shows; the fit takes phi = 1; T, k and f_c unused).
  double memory_constant_samples = 0.0;

  bool moving_average() const { return moving_average_samples > 1; }
  bool butterworth() const { return butterworth_cutoff_hz > 0.0; }
  bool beyond_memory() const { return memory_constant_samples > 0.0; }
  /// Whether it changes anything.
  bool any() const {
    return filtered_fraction > 0.0 &&
           (moving_average() || butterworth() || beyond_memory() || time_constant_s > 0.0);
  }
};

/// The first-order low-pass on the whole output whose factor beyond its
/// memory is 1 - c tau0 / tau: lag-1 correlation rho with
/// 3 rho / (1 - rho^2) = c, time constant -tau0 / ln(rho). The stand-in for
/// a filter known only by c (SensorBandwidth::memory_constant_samples).
SensorBandwidth first_order_with_memory(double memory_constant_samples, double sample_interval_s);

/// The second-order Butterworth low-pass at `cutoff_hz` for samples every
/// `sample_interval_s`, by the bilinear transform with pre-warping:
/// K = tan(pi f_c tau0), H(z) = K^2 (1 + z^-1)^2 / ((1 + sqrt2 K + K^2) +
/// 2 (K^2 - 1) z^-1 + (1 - sqrt2 K + K^2) z^-2) (unit gain at DC, -3 dB at
/// f_c). Returns {b0, b1, b2, a1, a2} of y_k = b0 x_k + b1 x_(k-1) +
/// b2 x_(k-2) - a1 y_(k-1) - a2 y_(k-2). Needs 0 < f_c tau0 < 1/2.
std::array<double, 5> butterworth_coefficients(double cutoff_hz, double sample_interval_s);

/// The cut-off [Hz]: 1 / (2 pi T) of the first-order low-pass, the
/// Butterworth's f_c, or where the moving average's response falls to
/// 1/sqrt(2) (0.443 fs / k for large k), the first-order stand-in's for a
/// filter known beyond its memory; infinite without a filter. `sample_interval_s` serves the
/// moving average.
double cutoff_hz(const SensorBandwidth& bandwidth, double sample_interval_s = 0.0);

/// The lag-1 correlation of the filtered part's samples: exp(-tau0 / T),
/// (k - 1) / k for the moving average, a_1 / a_0 for the Butterworth, the
/// first-order stand-in's rho for a filter known beyond its memory.
double filtered_lag1(const SensorBandwidth& bandwidth, double sample_interval_s);

/// The factor on the white term's Allan variance N^2 / tau at tau [s] (an
/// integer multiple m of the sample interval tau0 [s]): 1 without a
/// bandwidth, below 1 at short tau, tending to 1 as tau grows. For a filter
/// known beyond its memory 1 - phi c / m from m = 2 c, the first-order
/// stand-in's below.
double white_allan_factor(const SensorBandwidth& bandwidth, double tau_s, double sample_interval_s);

/// The factor on the flicker term's Allan variance (its plateau
/// 2 ln 2 B^2 / pi) at tau [s] = m tau0 when the filter acts on the output's
/// flicker noise as well (the same fraction phi): below 1 at short tau,
/// tending to 1 as (filter length / m)^2. Exact for flicker noise whose
/// samples are interval averages of a 1/f process: its semivariogram
/// between averages j samples apart is L(j+1) - 2 L(j) + L(j-1), L(a) =
/// a^2 ln|a| (up to scale), and the Allan kernel's quadratic form over it,
/// weighted by the filter's autocorrelation, follows as a fourth difference
/// of L at step m. For a filter known beyond its memory, the first-order
/// stand-in's (the kinds differ by O((c / m)^2) in it).
double flicker_allan_factor(const SensorBandwidth& bandwidth, double tau_s,
                            double sample_interval_s);

/// The bandwidth's power response at f [Hz] for samples every
/// `sample_interval_s`: (1 - phi) + phi |H(f)|^2, with H the sampled
/// filter's response normalised to 1 at DC — the first-order filter's
/// (1 - rho)^2 / (1 - 2 rho cos(2 pi f tau0) + rho^2) (rho = exp(-tau0 / T),
/// the autoregressive sequence above), the moving average's
/// sin^2(pi f k tau0) / (k sin(pi f tau0))^2, the Butterworth's |H(e^(i 2 pi f tau0))|^2,
/// the first-order stand-in's for a filter known beyond its memory.
/// 1 without a bandwidth. The PSD of the sensor's white (and flicker) noise
/// is its level times this.
double power_response(const SensorBandwidth& bandwidth, double frequency_hz,
                      double sample_interval_s);

/// The lag-1 autocorrelation of the white noise's samples with this
/// bandwidth (0 without one); for the first-order filter
/// phi rho (1 - rho) / (1 + rho - 2 phi rho); NaN for a filter known
/// beyond its memory (its shape inside the memory is not known).
double white_lag1_correlation(const SensorBandwidth& bandwidth, double sample_interval_s);

}  // namespace foglab
