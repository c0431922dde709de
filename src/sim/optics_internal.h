// foglab — helpers shared by the optics model (optics.cc) and lab 1's
// procedure (lab1.cc). Not installed.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <numeric>
#include <vector>

namespace foglab::sim::detail {

/// The mean of the last `count` values (all of them when there are fewer);
/// NaN for none.
inline double mean_of_last(const std::vector<double>& v, std::size_t count) {
  const std::size_t k = std::min(v.size(), count);
  if (k == 0) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(v.end() - static_cast<std::ptrdiff_t>(k), v.end(), 0.0) /
         static_cast<double>(k);
}

}  // namespace foglab::sim::detail
