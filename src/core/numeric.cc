#include "foglab/core/numeric.h"

#include <fmt/format.h>
#include <omp.h>
#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "foglab/core/error.h"
#include "simd_clones.h"

namespace foglab {

void advise_huge_pages(double* data, std::size_t count) {
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t end = begin + count * sizeof(double);
  const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = end & ~(kHugePage - 1);
  if (last > first) {
    // Advice only: failure just means ordinary pages.
    (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  }
#else
  (void)data;
  (void)count;
#endif
}

std::vector<double> large_vector(std::size_t size, double fill, std::size_t capacity) {
  std::vector<double> v;
  v.reserve(std::max(size, capacity));
  advise_huge_pages(v.data(), v.capacity());
  // The first touch in parallel: on the virtual machines we measure on, the
  // kernel's zeroing of fresh pages costs more than the statistics computed on
  // them, and each thread pays it for its own half. (C++20 creates the
  // doubles implicitly in the allocated storage; resize() then fills
  // resident pages.)
  double* data = v.data();
  const auto count = static_cast<std::int64_t>(size);
#pragma omp parallel for schedule(static) if (size > kChunkSamples)
  for (std::int64_t i = 0; i < count; ++i) data[i] = fill;
  v.resize(size, fill);
  return v;
}

int worker_threads() { return std::max(1, omp_get_max_threads()); }

FOGLAB_SIMD_CLONES CompensatedSum chunk_sum(std::span<const double> values, double shift) {
  constexpr std::size_t kLanes = 16;  // independent chains hide the latency
  double sum[kLanes] = {};
  double comp[kLanes] = {};
  const std::size_t n = values.size();
  const std::size_t body = n - n % kLanes;
  const double* p = values.data();
  for (std::size_t i = 0; i < body; i += kLanes) {
    for (std::size_t l = 0; l < kLanes; ++l) {  // Kahan, lane by lane
      const double y = (p[i + l] - shift) - comp[l];
      const double t = sum[l] + y;
      comp[l] = (t - sum[l]) - y;
      sum[l] = t;
    }
  }
  CompensatedSum total;
  for (std::size_t l = 0; l < kLanes; ++l) {
    total.add(sum[l]);
    total.add(-comp[l]);
  }
  for (std::size_t i = body; i < n; ++i) total.add(p[i] - shift);
  return total;
}

std::vector<CompensatedSum> chunk_sums(std::span<const double> values, double shift,
                                       std::size_t chunk) {
  if (chunk == 0) chunk = kChunkSamples;
  const std::size_t n = values.size();
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::vector<CompensatedSum> partial(chunks);
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * chunk;
    const std::size_t end = std::min(n, begin + chunk);
    partial[c] = chunk_sum(values.subspan(begin, end - begin), shift);
  }
  return partial;
}

double compensated_sum(std::span<const double> values) {
  CompensatedSum total;
  for (const auto& p : chunk_sums(values)) total.add(p);
  return total.value();
}

double compensated_mean(std::span<const double> values) {
  if (values.empty()) return 0.0;
  return compensated_sum(values) / static_cast<double>(values.size());
}

namespace {

// Whether every value of p[0 .. n) is finite: v - v is 0 for a finite value
// and NaN for an infinite or NaN one, so one sum tells, without branches.
FOGLAB_SIMD_CLONES bool all_finite(const double* p, std::size_t n) {
  double s = 0.0;
#pragma omp simd reduction(+ : s)
  for (std::size_t i = 0; i < n; ++i) s += p[i] - p[i];
  return s == 0.0;
}

}  // namespace

std::size_t first_non_finite(std::span<const double> values) {
  const std::size_t n = values.size();
  const std::size_t chunks = (n + kChunkSamples - 1) / kChunkSamples;
  std::vector<char> finite(chunks, 1);
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * kChunkSamples;
    finite[c] = all_finite(values.data() + begin, std::min(n, begin + kChunkSamples) - begin);
  }
  for (std::size_t c = 0; c < chunks; ++c) {
    if (finite[c]) continue;
    for (std::size_t i = c * kChunkSamples; i < n; ++i) {
      if (!std::isfinite(values[i])) return i;
    }
  }
  return n;
}

double median_in_place(std::span<double> values) {
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

RobustSpread robust_spread(std::span<const double> values) {
  std::vector<double> work(values.begin(), values.end());
  RobustSpread r;
  r.centre = median_in_place(work);
  for (std::size_t i = 0; i < work.size(); ++i) work[i] = std::fabs(values[i] - r.centre);
  r.spread = 1.4826 * median_in_place(work);
  return r;
}

void require_varying(std::span<const double> values, std::string_view unit) {
  if (values.size() < 2) return;  // too short: each analysis says so
  // The first sample that differs ends the search: on a real record, the second.
  const double first = values[0];
  if (std::all_of(values.begin() + 1, values.end(), [first](double v) { return v == first; })) {
    throw DataError(
        fmt::format("the record is constant: all {} samples equal {:g} {}, so there "
                    "is no noise to analyse",
                    values.size(), first, unit));
  }
}

}  // namespace foglab
