// foglab — generating a synthetic static-gyro recording.
//
// Reproducibility: every random number is a pure function of (seed, process,
// sample index) — a counter-based generator — so the same seed gives
// bit-identical samples whatever the number of threads, and any stretch of
// the record can be generated on its own. The Markov processes (random walk,
// Gauss-Markov, the flicker bank) carry their state across blocks, so memory
// does not grow with the record.
//
// Flicker noise: a calibrated bank of first-order Gauss-Markov processes with
// correlation times spread log-uniformly beyond the record's tau range (see
// docs/theory/flicker.md for the choice, the calibration and the valid range).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "foglab/sim/error_model.h"

namespace foglab::sim {

struct GeneratorOptions {
  double sample_rate_hz = 10.0;  ///< [Hz] > 0
  double duration_s = 3600.0;    ///< [s] > 0; samples = round(duration_s * sample_rate_hz)
  std::uint64_t seed = 1;        ///< same seed, same bits
  /// Stream selector: different variants with one seed give independent
  /// noise (lab2-data uses the gyro and run number here).
  std::uint64_t stream = 0;
};

/// One stretch of a recording handed to a sink.
struct Block {
  std::int64_t first_index = 0;              ///< index of the first sample in the record
  std::span<const double> time_s;            ///< [s] t_k = k / fs
  std::span<const double> rate_deg_h;        ///< [deg/h]
  std::span<const double> temperature_c;     ///< [degC]
};

/// A whole recording in memory.
struct Recording {
  double sample_rate_hz = 0.0;
  std::vector<double> time_s;         ///< [s]
  std::vector<double> rate_deg_h;     ///< [deg/h]
  std::vector<double> temperature_c;  ///< [degC]
};

/// Generates the recording block by block, in order, calling `sink` for each
/// (blocks of at most 2^20 samples; the sink may write them out). Uses all
/// worker threads inside each block. The sink runs on a helper thread while
/// the next block is generated (so writing overlaps generating); its calls
/// never overlap one another, come in order, and the block's spans stay valid
/// until the call returns. An exception from the sink stops the generation
/// and is rethrown to the caller. Throws UsageError for invalid options
/// or model parameters (negative intensities, gm_sigma > 0 with gm_tc <= 0).
void generate(const ErrorModel& model, const TemperatureProfile& temperature,
              const GeneratorOptions& options, const std::function<void(const Block&)>& sink);

/// The same, collected in memory.
Recording generate(const ErrorModel& model, const TemperatureProfile& temperature,
                   const GeneratorOptions& options);

}  // namespace foglab::sim
