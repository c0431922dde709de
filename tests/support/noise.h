// Test support: reproducible Gaussian noise (and a plain ramp), the noise generated in parallel
// from a counter-based generator so that 10^9 samples take seconds and do not depend on the number
// of threads.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace foglab::test {

inline std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// Standard normal deviate number `index` of stream `seed` (Box-Muller).
inline double normal_at(std::uint64_t seed, std::uint64_t index) {
  const std::uint64_t a = splitmix64(seed * 0x100000001b3ULL + 2 * index);
  const std::uint64_t b = splitmix64(seed * 0x100000001b3ULL + 2 * index + 1);
  const double u1 = (static_cast<double>(a >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
  const double u2 = static_cast<double>(b >> 11) * 0x1.0p-53;         // [0, 1)
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

/// Fills `out` with sigma * N(0, 1) deviates of stream `seed`.
inline void fill_normal(std::span<double> out, std::uint64_t seed, double sigma) {
  const auto n = static_cast<std::int64_t>(out.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) out[i] = sigma * normal_at(seed, static_cast<std::uint64_t>(i));
}

inline std::vector<double> white(std::size_t count, std::uint64_t seed, double sigma) {
  std::vector<double> v(count);
  fill_normal(v, seed, sigma);
  return v;
}

/// `count` draws of N(mean, sd^2) from std::mt19937_64 seeded with `seed`:
/// noise made independently of foglab's own generators, in one thread.
inline std::vector<double> mt_normal(std::size_t count, std::uint64_t seed, double mean,
                                     double sd) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(mean, sd);
  std::vector<double> v(count);
  for (double& x : v) x = normal(engine);
  return v;
}

/// A random walk with steps sigma * N(0, 1).
inline std::vector<double> random_walk(std::size_t count, std::uint64_t seed, double step) {
  std::vector<double> v = white(count, seed, step);
  for (std::size_t i = 1; i < count; ++i) v[i] += v[i - 1];
  return v;
}

/// first, first + step, ... (n values): a deterministic series for readers and writers.
inline std::vector<double> ramp(std::size_t n, double first, double step) {
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = first + step * static_cast<double>(i);
  return out;
}

}  // namespace foglab::test
