// Rate -> angle integration with compensated mean removal (see allan.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/stats/allan.h"

namespace foglab::stats {

std::vector<double> to_phase(std::span<const double> samples, double sample_rate_hz,
                             InputKind input) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw UsageError(fmt::format("sample rate {} Hz: expected a positive number", sample_rate_hz));
  }
  const std::size_t n = samples.size();
  if (input == InputKind::phase) {
    std::vector<double> x(n);
    if (n == 0) return x;
    // Remove the straight line through the end points (a constant rate):
    // every statistic is blind to it, and removing it keeps the numbers small.
    const double x0 = samples[0];
    const double slope = n > 1 ? (samples[n - 1] - x0) / static_cast<double>(n - 1) : 0.0;
#pragma omp parallel for schedule(static) if (n > kChunkSamples)
    for (std::size_t k = 0; k < n; ++k) {
      x[k] = ((samples[k] - x0) - slope * static_cast<double>(k)) * sample_rate_hz;
    }
    return x;
  }

  // Rate: x_0 = 0, x_{k+1} = x_k + (y_k - mean). Chunks are integrated in
  // parallel from offsets that are themselves compensated sums, so rounding
  // errors never travel further than one chunk.
  const double mean = compensated_mean(samples);
  std::vector<double> x(n + 1);
  x[0] = 0.0;
  const std::size_t chunks = (n + kChunkSamples - 1) / kChunkSamples;
  std::vector<CompensatedSum> chunk_sums(chunks);
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * kChunkSamples;
    const std::size_t end = std::min(n, begin + kChunkSamples);
    CompensatedSum s;
    for (std::size_t k = begin; k < end; ++k) s.add(samples[k] - mean);
    chunk_sums[c] = s;
  }
  std::vector<double> offsets(chunks);
  CompensatedSum running;
  for (std::size_t c = 0; c < chunks; ++c) {
    offsets[c] = running.value();
    running.add(chunk_sums[c]);
  }
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * kChunkSamples;
    const std::size_t end = std::min(n, begin + kChunkSamples);
    double acc = offsets[c];
    for (std::size_t k = begin; k < end; ++k) {
      acc += samples[k] - mean;
      x[k + 1] = acc;
    }
  }
  return x;
}

}  // namespace foglab::stats
