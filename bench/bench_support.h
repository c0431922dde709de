// Benchmark support: a reproducible white-noise rate record, filled in parallel.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

namespace foglab::bench {

inline double normal_at(std::uint64_t index) {
  auto mix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  const double u1 = (static_cast<double>(mix(2 * index) >> 11) + 1.0) * 0x1.0p-53;
  const double u2 = static_cast<double>(mix(2 * index + 1) >> 11) * 0x1.0p-53;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

/// White rate noise, 0.1 deg/h/sqrt(Hz) at 100 Hz, on a 10 deg/h bias.
inline std::vector<double> gyro_record(std::size_t count) {
  std::vector<double> y(count);
  const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) y[i] = 10.0 + 1.0 * normal_at(static_cast<std::uint64_t>(i));
  return y;
}

/// One parallel read of the whole array (a sum): the unit of the streaming
/// bounds the Allan benchmarks set their stages against.
inline double read_once(const std::vector<double>& x) {
  double sum = 0.0;
  const auto n = static_cast<std::int64_t>(x.size());
#pragma omp parallel for reduction(+ : sum) schedule(static)
  for (std::int64_t i = 0; i < n; ++i) sum += x[i];
  return sum;
}

}  // namespace foglab::bench
