// foglab — a narrow-band disturbance of the rate (a spectral line: mains
// pickup, a dither or structural resonance, a sinusoidal input) and what it
// does to the Allan variance.
//
// A line is kept as its excess over the noise floor in the frequency bins
// of a Welch PSD: each bin b at frequency f_b carries the variance v_b (both
// signs of f; the line's variance is their sum). A sinusoid of variance v at
// frequency f, sampled every tau0, has at tau = m tau0 the Allan variance
//
//   AVAR(tau) = 2 v sin^4(pi f tau) / (m sin(pi f tau0))^2
//
// (the m-average of a sampled sinusoid is its value at the block's centre
// times the Dirichlet kernel sin(pi f tau) / (m sin(pi f tau0)); two
// neighbouring averages differ by 2 sin(pi f tau) times that); a line is the
// sum over its bins. It vanishes where tau is a whole number of periods and
// decays as 1/tau^2 between bumps: the pattern of bumps near tau = 0.37/f,
// 1.4/f, ... that no IEEE Std 952 term follows.
#pragma once

#include <vector>

namespace foglab {

/// One harmonic of a periodic disturbance taken out of the record with its
/// line (SpectralLine::harmonics).
struct LineHarmonic {
  int number = 2;                ///< k: at k times the line's frequency_hz
  double amplitude_deg_h = 0.0;  ///< [deg/h] amplitude_deg_h cos(2 pi k f t + phase_rad)
  double phase_rad = 0.0;        ///< [rad]
};

struct SpectralLine {
  double frequency_hz = 0.0;             ///< [Hz] the power-weighted centre of its bins
  double width_hz = 0.0;                 ///< [Hz] from its lowest to its highest bin
  double variance = 0.0;                 ///< [(deg/h)^2] the sum of bin_variance
  double peak_ratio = 0.0;               ///< the highest bin's PSD over the noise floor there
  std::vector<double> bin_frequency_hz;  ///< [Hz]
  std::vector<double> bin_variance;      ///< [(deg/h)^2]
  /// Whether the noise fit's factor on the lines' variance, which the first
  /// taus decide (NoiseFitResult::line_variance_scale: a broad resonance's
  /// bins hold only part of it), applies: not to a slow line found in the
  /// long-segment PSD, a sinusoid whose bins hold all of its variance and
  /// whose Allan variance the first taus do not see, nor to a line
  /// removed_from_record.
  bool takes_variance_scale = true;
  /// A slow line that is one sinusoid, amplitude_deg_h cos(2 pi f t +
  /// phase_rad) with t [s] from the record's first sample and f its
  /// frequency_hz, taken out of the record before the Allan variance
  /// (model::remove_sinusoids()): the noise fit leaves its Allan variance
  /// out, for the record it sees has none.
  bool removed_from_record = false;
  double amplitude_deg_h = 0.0;  ///< [deg/h] when removed_from_record
  double phase_rad = 0.0;        ///< [rad] when removed_from_record
  /// A periodic disturbance that is not one sinusoid (a thermostat's square
  /// wave), removed_from_record as a sum of harmonics: those above the
  /// first, each also one of the bins (its bin_variance amplitude^2 / 2),
  /// so that `variance` is the whole disturbance's. Empty for a sinusoid.
  std::vector<LineHarmonic> harmonics;
};

/// The Dirichlet kernel sin(pi f m tau0) / (m sin(pi f tau0)): the gain of
/// the mean of m `samples` taken every `sample_interval_s` (tau0) [s] on a
/// sinusoid of `frequency_hz` (f) [Hz]. Not finite where f is a multiple
/// of the sample rate (such a line aliases to DC).
double dirichlet_kernel(double frequency_hz, double samples, double sample_interval_s);

/// The line's Allan variance [(deg/h)^2] at tau [s] for samples every
/// `sample_interval_s` (tau0) [s] (of the line as it is, removed from the
/// record or not).
double line_allan_variance(const SpectralLine& line, double tau_s, double sample_interval_s);

}  // namespace foglab
