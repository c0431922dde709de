// Rate -> angle integration with compensated mean removal (see allan.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/stats/allan.h"

namespace foglab::stats {

namespace {

void check_rate(double sample_rate_hz) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw UsageError(fmt::format("sample rate {} Hz: expected a positive number", sample_rate_hz));
  }
}

// Angle record: remove the straight line through the end points (a constant
// rate; every statistic is blind to it, and removing it keeps numbers small)
// and scale to tau0 = 1 units. `out` may alias `in`.
void angle_to_phase(std::span<const double> in, double sample_rate_hz, double* out) {
  const std::size_t n = in.size();
  if (n == 0) return;
  const double x0 = in[0];
  const double slope = n > 1 ? (in[n - 1] - x0) / static_cast<double>(n - 1) : 0.0;
#pragma omp parallel for schedule(static) if (n > kChunkSamples)
  for (std::size_t k = 0; k < n; ++k) {
    out[k] = ((in[k] - x0) - slope * static_cast<double>(k)) * sample_rate_hz;
  }
}

// Rate record: x_0 = 0, x_{k+1} = x_k + (y_k - mean). Chunks are integrated
// in parallel from offsets that are compensated sums, so rounding errors
// never travel further than one chunk. Returns the chunk offsets x at each
// chunk start and the final value x_n.
std::vector<double> chunk_offsets(std::span<const double> rate, double mean, double* last) {
  const std::vector<CompensatedSum> sums = chunk_sums(rate, mean);
  std::vector<double> offsets(sums.size());
  CompensatedSum running;
  for (std::size_t c = 0; c < sums.size(); ++c) {
    offsets[c] = running.value();
    running.add(sums[c]);
  }
  *last = running.value();
  return offsets;
}

}  // namespace

std::vector<double> detail::to_phase(std::span<const double> samples, double sample_rate_hz,
                                     InputKind input) {
  check_rate(sample_rate_hz);
  if (input == InputKind::phase) {
    std::vector<double> x = large_vector(samples.size());
    angle_to_phase(samples, sample_rate_hz, x.data());
    return x;
  }
  const std::size_t n = samples.size();
  const double mean = compensated_mean(samples);
  double last = 0.0;
  const std::vector<double> offsets = chunk_offsets(samples, mean, &last);
  std::vector<double> x = large_vector(n + 1);
  const std::size_t chunks = offsets.size();
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * kChunkSamples;
    const std::size_t end = std::min(n, begin + kChunkSamples);
    double acc = offsets[c];
    for (std::size_t k = begin; k < end; ++k) {
      x[k] = acc;
      acc += samples[k] - mean;
    }
  }
  x[n] = last;
  return x;
}

void detail::to_phase_in_place(std::vector<double>& samples, double sample_rate_hz,
                               InputKind input) {
  check_rate(sample_rate_hz);
  if (input == InputKind::phase) {
    angle_to_phase(samples, sample_rate_hz, samples.data());
    return;
  }
  const std::size_t n = samples.size();
  const double mean = compensated_mean(samples);
  double last = 0.0;
  const std::vector<double> offsets = chunk_offsets(samples, mean, &last);
  const std::size_t chunks = offsets.size();
  double* y = samples.data();
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * kChunkSamples;
    const std::size_t end = std::min(n, begin + kChunkSamples);
    double acc = offsets[c];
    for (std::size_t k = begin; k < end; ++k) {  // x_k replaces y_k
      const double rate = y[k];
      y[k] = acc;
      acc += rate - mean;
    }
  }
  samples.push_back(last);  // x_n (one reallocation at most; readers reserve n + 1)
}

}  // namespace foglab::stats
