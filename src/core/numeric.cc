#include "foglab/core/numeric.h"

#include <fmt/format.h>
#include <omp.h>
#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "foglab/core/error.h"

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
  v.resize(size, fill);
  return v;
}

int worker_threads() { return std::max(1, omp_get_max_threads()); }

CompensatedSum chunk_sum(std::span<const double> values, double shift) {
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

std::vector<CompensatedSum> chunk_sums(std::span<const double> values, double shift) {
  const std::size_t n = values.size();
  const std::size_t chunks = (n + kChunkSamples - 1) / kChunkSamples;
  std::vector<CompensatedSum> partial(chunks);
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * kChunkSamples;
    const std::size_t end = std::min(n, begin + kChunkSamples);
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
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  if (*low == *high) {
    throw DataError(
        fmt::format("the record is constant: all {} samples equal {:g} {}, so there "
                    "is no noise to analyse",
                    values.size(), *low, unit));
  }
}

}  // namespace foglab
