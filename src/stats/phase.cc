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

// Rate record: x_0 = 0, x_{k+1} = x_k + (y_k - mean) into out[0 .. n]; `out`
// may alias `rate` (each x_k is written after y_k is read). One parallel pass
// takes the compensated sums of y_k - shift over fixed pieces, with the
// first piece's mean as the shift, so a bias of 10^6 deg/h loses none of the
// noise's digits; the mean is shift + (their total) / n. The pieces are then
// integrated from offsets that are compensated sums, so rounding never
// travels further than one piece: in parallel, each thread first touching
// the part of `out` it writes, and four pieces side by side in one loop
// (four independent additions per step instead of one chain).
constexpr std::size_t kLanes = 4;
constexpr std::size_t kPiece = kChunkSamples / kLanes;

void integrate_rate(std::span<const double> rate, double* out) {
  const std::size_t n = rate.size();
  const std::size_t head = std::min(n, kPiece);
  const double shift =
      head > 0 ? chunk_sum(rate.first(head)).value() / static_cast<double>(head) : 0.0;
  const std::vector<CompensatedSum> sums = chunk_sums(rate, shift, kPiece);
  CompensatedSum total;
  for (const CompensatedSum& s : sums) total.add(s);
  const double excess = n > 0 ? total.value() / static_cast<double>(n) : 0.0;
  const std::size_t pieces = sums.size();
  std::vector<double> offsets(pieces);
  CompensatedSum running;
  for (std::size_t p = 0; p < pieces; ++p) {
    offsets[p] = running.value();
    running.add(sums[p]);
    running.add(-excess * static_cast<double>(std::min(n, (p + 1) * kPiece) - p * kPiece));
  }
  const double last = running.value();
  const double* y = rate.data();
  const std::size_t chunks = (pieces + kLanes - 1) / kLanes;
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t first = c * kLanes;
    if ((c + 1) * kLanes * kPiece <= n) {
      double acc[kLanes];
      for (std::size_t l = 0; l < kLanes; ++l) acc[l] = offsets[first + l];
      const std::size_t begin = first * kPiece;
      for (std::size_t t = 0; t < kPiece; ++t) {
        for (std::size_t l = 0; l < kLanes; ++l) {
          const std::size_t k = begin + l * kPiece + t;
          const double v = y[k];
          out[k] = acc[l];
          acc[l] += (v - shift) - excess;
        }
      }
      continue;
    }
    for (std::size_t p = first; p < std::min(pieces, first + kLanes); ++p) {  // the last chunk
      double acc = offsets[p];
      for (std::size_t k = p * kPiece; k < std::min(n, (p + 1) * kPiece); ++k) {
        const double v = y[k];
        out[k] = acc;
        acc += (v - shift) - excess;
      }
    }
  }
  out[n] = last;
}

}  // namespace

void detail::check_sample_rate(double sample_rate_hz) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw UsageError(fmt::format("sample rate {} Hz: expected a positive number", sample_rate_hz));
  }
}

std::size_t detail::phase_points(std::size_t samples, InputKind input) {
  return input == InputKind::rate ? samples + 1 : samples;
}

void detail::to_phase_into(std::span<const double> samples, double sample_rate_hz, InputKind input,
                           double* out) {
  check_sample_rate(sample_rate_hz);
  if (input == InputKind::phase) {
    angle_to_phase(samples, sample_rate_hz, out);
  } else {
    integrate_rate(samples, out);
  }
}

std::vector<double> detail::to_phase(std::span<const double> samples, double sample_rate_hz,
                                     InputKind input) {
  std::vector<double> x = large_vector(phase_points(samples.size(), input));
  to_phase_into(samples, sample_rate_hz, input, x.data());
  return x;
}

void detail::to_phase_in_place(std::vector<double>& samples, double sample_rate_hz,
                               InputKind input) {
  const std::size_t n = samples.size();
  if (input == InputKind::rate) samples.push_back(0.0);  // x_n (readers reserve n + 1)
  to_phase_into(std::span<const double>(samples.data(), n), sample_rate_hz, input, samples.data());
}

}  // namespace foglab::stats
