// foglab — the truth of a real sensor's output chain: what happens to the
// rate after the error model (sim/error_model.h), as gyro electronics and
// their surroundings do it. Each effect is exact and seeded like the rest of
// the generator; the answer key (generate --truth) records every one.
//
// In order, per sample k (tau0 = 1/fs, t_k = k tau0):
//   1. disturbances added to the model's rate: sinusoids A sin(2 pi f t + p)
//      (mains pickup, dither, a resonance), square waves A sgn(sin(2 pi f t
//      + p)) (sgn 0 = +1: a heater switched on and off, whose current's
//      field a FOG's coil feels) and bias steps (a jump of s deg/h from time
//      t on: a power glitch, a mode change);
//   2. the sensor's bandwidth: a moving average over the last k samples
//      and/or a first-order low-pass y_k = rho y_(k-1) + (1 - rho) x_k with
//      rho = exp(-tau0 / T) (unit gain at DC; on white noise exactly the
//      process of core/sensor_bandwidth.h with the whole of it filtered),
//      and/or a second-order Butterworth low-pass at a cut-off f_c (the
//      bilinear transform with pre-warping: K = tan(pi f_c / fs),
//      H(z) = K^2 (1 + z^-1)^2 / ((1 + sqrt2 K + K^2) + 2 (K^2 - 1) z^-1 +
//      (1 - sqrt2 K + K^2) z^-2); unit gain at DC, -3 dB at f_c), as the
//      anti-aliasing or output filter of gyro electronics; each started at
//      its first input as if it had been there forever;
//   3. spikes: isolated outliers of +-size at a mean rate per hour, at
//      samples drawn independently (a bit error, a vibration knock);
//   4. the output word: each sample rounded to a whole number of LSBs;
//   5. dropouts: stretches of samples the logger loses. They are not part of
//      the chain (the record is generated whole, so the other effects do not
//      depend on them); remove_dropouts() takes them out of a recording,
//      whose time column then shows the gaps (core/gaps.h);
//   6. the logger's time stamps: each time written is t_k + u_k, u_k
//      uniform on [-j, j] seconds (a host that stamps each sample when it
//      arrives; rms j / sqrt(3)); the samples stay on the sensor's grid.
//      jitter_times() applies it to a recording's time column.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "foglab/core/gaps.h"

namespace foglab::sim {

struct Recording;

struct Sinusoid {
  double frequency_hz = 0.0;     ///< [Hz] > 0
  double amplitude_deg_h = 0.0;  ///< [deg/h] peak (rms = amplitude / sqrt(2))
  double phase_rad = 0.0;
};

/// A periodic disturbance that is not a sinusoid: harmonics at the odd
/// multiples k f of amplitude 4 A / (pi k).
struct SquareWave {
  double frequency_hz = 0.0;     ///< [Hz] > 0
  double amplitude_deg_h = 0.0;  ///< [deg/h] half the peak-to-peak (rms = amplitude)
  double phase_rad = 0.0;
};

struct BiasStep {
  double time_s = 0.0;      ///< [s] from here on
  double size_deg_h = 0.0;  ///< [deg/h]
};

struct Dropout {
  double start_s = 0.0;     ///< [s] the samples at start_s <= t_k < start_s + duration_s are lost
  double duration_s = 0.0;  ///< [s] > 0
};

struct SensorOutput {
  std::vector<Sinusoid> sinusoids;
  std::vector<SquareWave> square_waves;
  std::vector<BiasStep> steps;
  int moving_average_samples = 1;       ///< k >= 1 (1: none)
  double filter_time_constant_s = 0.0;  ///< [s] T of the first-order low-pass (0: none)
  double butterworth_cutoff_hz = 0.0;   ///< [Hz] f_c of the second-order low-pass (0: none)
  double spike_rate_per_hour = 0.0;     ///< mean number of spikes per hour
  double spike_size_deg_h = 0.0;        ///< [deg/h] each spike's magnitude (random sign)
  double lsb_deg_h = 0.0;               ///< [deg/h] output step (0: not rounded)
  std::vector<Dropout> dropouts;        ///< lost stretches (step 5, not in any())
  /// [s] j of step 6: 0 (exact times) to below 0.4 tau0 (not in any())
  double time_jitter_s = 0.0;

  /// Whether any effect of steps 1-4 is on.
  bool any() const;
};

/// Throws UsageError naming the field for a negative or non-finite value,
/// k < 1 or a sinusoid (square wave) at or above the Nyquist frequency.
void validate(const SensorOutput& output, double sample_rate_hz);

/// The magnitude of the bandwidth filters' response at frequency f [Hz]
/// (a sinusoid there comes out this much smaller): the moving average's
/// |sin(pi f k / fs) / (k sin(pi f / fs))| times the low-pass's
/// (1 - rho) / |1 - rho e^(-i 2 pi f / fs)| times the Butterworth's |H|.
double output_filter_gain(const SensorOutput& output, double frequency_hz, double sample_rate_hz);

/// The times [s] of the spikes the chain puts into a record of `samples`
/// samples (the same draws as OutputChain's), but those in the samples
/// the dropouts lose: a spike dropped with its sample is not in the file.
std::vector<double> spike_times_s(const SensorOutput& output, double sample_rate_hz,
                                  std::uint64_t seed, std::uint64_t stream, std::int64_t samples);

/// The gaps the dropouts leave in a record of `samples` samples at
/// `sample_rate_hz` (overlapping dropouts merge; one that loses the first or
/// the last sample shortens the record instead, and is not a gap).
std::vector<Gap> dropout_gaps(const SensorOutput& output, double sample_rate_hz,
                              std::int64_t samples);

/// Removes the dropouts' samples from every column of `recording`; returns
/// the gaps (as dropout_gaps(), indices among the samples kept). Throws
/// UsageError when no sample would be left.
std::vector<Gap> remove_dropouts(Recording& recording, const SensorOutput& output);

/// Step 6: adds the logger's jitter to `time_s`, which holds the times of samples
/// first_index, first_index + 1, ... (before any dropout is removed); the draws are a pure
/// function of seed, stream and sample index, like the chain's.
void jitter_times(std::span<double> time_s, std::int64_t first_index, const SensorOutput& output,
                  double sample_rate_hz, std::uint64_t seed, std::uint64_t stream);

/// Marks the dropouts' samples NaN instead of removing them, as a logger
/// that writes NaN for a lost sample does: `values` holds samples
/// first_index, first_index + 1, ... of a record of `samples` samples.
void mark_dropouts_nan(std::span<double> values, std::int64_t first_index, std::int64_t samples,
                       const SensorOutput& output, double sample_rate_hz);

/// The chain of one record, applied block by block in order: it carries the
/// filters' state from one block to the next. Spikes come from the same
/// counter-based generator as the rest (a pure function of seed, stream and
/// sample index).
class OutputChain {
 public:
  OutputChain(const SensorOutput& output, double sample_rate_hz, std::uint64_t seed,
              std::uint64_t stream);
  /// Applies the chain to the rates of samples first .. first + count - 1.
  void apply(std::int64_t first, double* rate_deg_h, std::size_t count);
  /// The sample indices where spikes were put so far.
  const std::vector<std::int64_t>& spike_indices() const { return spikes_; }

 private:
  SensorOutput output_;
  double fs_;
  std::uint64_t key_spike_, key_sign_;
  double rho_ = 0.0, filtered_ = 0.0;
  bool started_ = false;
  std::array<double, 5> biquad_{};  // b0, b1, b2, a1, a2 (none: b0 = 0)
  double z1_ = 0.0, z2_ = 0.0;      // its transposed direct form II state
  bool biquad_started_ = false;
  std::vector<double> window_;  // the last k - 1 inputs of the moving average
  std::size_t next_ = 0;
  double window_sum_ = 0.0;
  std::vector<std::int64_t> spikes_;
};

}  // namespace foglab::sim
