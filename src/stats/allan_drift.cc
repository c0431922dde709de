#include "foglab/stats/allan_drift.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "foglab/core/error.h"

namespace foglab::stats {
namespace {

// The Allan variance's terms of one contiguous piece, x[0 .. n), at m
// samples: the sum of the squared differences of neighbouring m-sample
// sums and their count (overlapping, as allan.h computes the OADEV).
struct Terms {
  double sum = 0.0;
  std::int64_t count = 0;
};

// `phase` is the piece's running sum, phase[0] = 0 and phase.size() = n + 1.
Terms piece_terms(const std::vector<double>& phase, std::int64_t m) {
  const auto n = static_cast<std::int64_t>(phase.size()) - 1;
  Terms t;
  if (n < 2 * m) return t;
  const double* p = phase.data();
  double s = 0.0;
#pragma omp simd reduction(+ : s)
  for (std::int64_t i = 0; i <= n - 2 * m; ++i) {
    const double d = p[i + 2 * m] - 2.0 * p[i + m] + p[i];
    s += d * d;
  }
  t.sum = s / (static_cast<double>(m) * static_cast<double>(m));
  t.count = n - 2 * m + 1;
  return t;
}

// Mann–Kendall z of `v` in its order (continuity-corrected; no ties are
// expected of continuous values).
double mann_kendall_z(std::span<const double> v) {
  const auto n = static_cast<double>(v.size());
  double s = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (std::size_t j = i + 1; j < v.size(); ++j) {
      s += (v[j] > v[i]) - (v[j] < v[i]);
    }
  }
  const double variance = n * (n - 1.0) * (2.0 * n + 5.0) / 18.0;
  if (s == 0.0) return 0.0;
  return (s - std::copysign(1.0, s)) / std::sqrt(variance);
}

}  // namespace

bool AllanDrift::any() const { return std::ranges::find(drifting, true) != drifting.end(); }

AllanDrift allan_drift(std::span<const double> rate, double tau0_s,
                       std::span<const Stretch> stretches, const AllanDriftOptions& options) {
  if (!(tau0_s > 0) || options.blocks < 16 || options.min_clusters < 1) {
    throw UsageError("allan_drift: tau0 must be positive, blocks >= 16 and min_clusters >= 1");
  }
  AllanDrift r;
  r.z_threshold = options.z_threshold;
  const auto samples = static_cast<std::int64_t>(rate.size());
  const std::int64_t block = samples / options.blocks;
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; block >= options.min_clusters * m; m *= 2) ms.push_back(m);
  if (ms.empty()) return r;
  r.blocks = options.blocks;

  // terms[b][k]: block b's terms at ms[k], its pieces pooled.
  std::vector<std::vector<Terms>> terms(static_cast<std::size_t>(options.blocks),
                                        std::vector<Terms>(ms.size()));
#pragma omp parallel for schedule(dynamic, 1)
  for (int b = 0; b < options.blocks; ++b) {
    const std::int64_t begin = b * block;
    const std::int64_t end = b + 1 == options.blocks ? samples : begin + block;
    std::vector<double> phase;
    for (const Stretch& s : stretches) {
      const std::int64_t from = std::max(begin, s.begin), to = std::min(end, s.end);
      if (to - from < 2) continue;
      // The piece's running sum about its own mean, for precision.
      const double mean = std::accumulate(rate.begin() + from, rate.begin() + to, 0.0) /
                          static_cast<double>(to - from);
      phase.assign(1, 0.0);
      for (std::int64_t i = from; i < to; ++i) phase.push_back(phase.back() + (rate[i] - mean));
      for (std::size_t k = 0; k < ms.size(); ++k) {
        const Terms t = piece_terms(phase, ms[k]);
        terms[b][k].sum += t.sum;
        terms[b][k].count += t.count;
      }
    }
  }

  for (std::size_t k = 0; k < ms.size(); ++k) {
    // A block the gaps leave with fewer than a quarter of its terms is
    // left out of this tau's test.
    std::vector<double> v;
    for (const std::vector<Terms>& t : terms) {
      if (4 * t[k].count >= block) v.push_back(t[k].sum / (2.0 * static_cast<double>(t[k].count)));
    }
    if (v.size() < 16) continue;
    const std::size_t eighth = v.size() / 8;
    const double first = std::accumulate(v.begin(), v.begin() + eighth, 0.0);
    const double last = std::accumulate(v.end() - eighth, v.end(), 0.0);
    const double z = mann_kendall_z(v);
    r.tau_s.push_back(static_cast<double>(ms[k]) * tau0_s);
    r.trend_z.push_back(z);
    r.last_to_first.push_back(first > 0 ? last / first : std::nan(""));
    r.drifting.push_back(std::abs(z) >= options.z_threshold);
    r.blocks_used.push_back(static_cast<int>(v.size()));
  }
  if (r.tau_s.empty()) r.blocks = 0;
  return r;
}

}  // namespace foglab::stats
