#include "foglab/core/numeric.h"

#include <omp.h>

#include <algorithm>
#include <vector>

namespace foglab {

int worker_threads() { return std::max(1, omp_get_max_threads()); }

double compensated_sum(std::span<const double> values) {
  const std::size_t n = values.size();
  const std::size_t chunks = (n + kChunkSamples - 1) / kChunkSamples;
  std::vector<CompensatedSum> partial(chunks);
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * kChunkSamples;
    const std::size_t end = std::min(n, begin + kChunkSamples);
    CompensatedSum s;
    for (std::size_t i = begin; i < end; ++i) s.add(values[i]);
    partial[c] = s;
  }
  CompensatedSum total;
  for (const auto& p : partial) total.add(p);
  return total.value();
}

double compensated_mean(std::span<const double> values) {
  if (values.empty()) return 0.0;
  return compensated_sum(values) / static_cast<double>(values.size());
}

}  // namespace foglab
