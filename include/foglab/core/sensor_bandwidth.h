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
// T >> tau0, the continuous filter's. Other short filters (a moving average
// over a few samples, a second-order low-pass) give other first points and
// the same 1 / tau^2 decay; the two parameters phi and T follow them closely
// enough to keep N the white level (docs/validation.md).
#pragma once

namespace foglab {

struct SensorBandwidth {
  double filtered_fraction = 0.0;  ///< phi in [0, 1]: the part of N^2 that is filtered
  double time_constant_s = 0.0;    ///< [s] T of the first-order low-pass (0: none)

  /// Whether it changes anything (phi > 0 and T > 0).
  bool any() const { return filtered_fraction > 0.0 && time_constant_s > 0.0; }
};

/// The first-order cut-off 1 / (2 pi T) [Hz] (infinite for T = 0).
double cutoff_hz(const SensorBandwidth& bandwidth);

/// The lag-1 correlation exp(-tau0 / T) of the filtered part's samples.
double filtered_lag1(const SensorBandwidth& bandwidth, double sample_interval_s);

/// The factor on the white term's Allan variance N^2 / tau at tau [s] (an
/// integer multiple m of the sample interval tau0 [s]): 1 without a
/// bandwidth, below 1 at short tau, tending to 1 as tau grows.
double white_allan_factor(const SensorBandwidth& bandwidth, double tau_s, double sample_interval_s);

/// The lag-1 autocorrelation of the white noise's samples with this
/// bandwidth: phi rho (1 - rho) / (1 + rho - 2 phi rho) (0 without one).
double white_lag1_correlation(const SensorBandwidth& bandwidth, double sample_interval_s);

}  // namespace foglab
