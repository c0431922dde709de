#include "foglab/stats/allan_drift.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/stats/allan.h"

namespace foglab::stats {
namespace {

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

// The gaps inside samples [begin, end), counted from `begin`.
std::vector<Gap> gaps_within(std::span<const Gap> gaps, std::int64_t begin, std::int64_t end) {
  std::vector<Gap> inside;
  for (const Gap& g : gaps) {
    if (g.before_sample > begin && g.before_sample < end) {
      inside.push_back({g.before_sample - begin, g.missing_samples});
    }
  }
  return inside;
}

}  // namespace

bool AllanDrift::any() const { return std::ranges::find(drifting, true) != drifting.end(); }

AllanDriftCalls AllanDrift::calls() const {
  AllanDriftCalls c;
  c.z_low = c.ratio_low = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    const double z = std::abs(trend_z[i]);
    c.largest_z = std::max(c.largest_z, z);
    if (!drifting[i]) continue;
    c.tau_s.push_back(tau_s[i]);
    c.z_low = std::min(c.z_low, z), c.z_high = std::max(c.z_high, z);
    c.ratio_low = std::min(c.ratio_low, last_to_first[i]);
    c.ratio_high = std::max(c.ratio_high, last_to_first[i]);
  }
  if (c.tau_s.empty()) c.z_low = c.ratio_low = 0.0;
  return c;
}

AllanDrift allan_drift(std::span<const double> rate, double tau0_s, std::span<const Gap> gaps,
                       const AllanDriftOptions& options) {
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

  // Block b holds samples [b * block, its end); the last takes the rest.
  const auto block_end = [&](int b) { return b + 1 == options.blocks ? samples : (b + 1) * block; };
  // Each block's OADEV at the factors ms (allan_deviation(): its gaps'
  // stretches pooled, each factor where its longest stretch allows it);
  // deviation[b][k] and terms[b][k] (0: not there).
  AllanOptions allan;
  allan.grid.kind = TauGridKind::octave;
  allan.grid.min_clusters = options.min_clusters;
  allan.confidence = false;
  const double fs = 1.0 / tau0_s;
  std::vector<std::vector<double>> deviation(static_cast<std::size_t>(options.blocks),
                                             std::vector<double>(ms.size(), 0.0));
  std::vector<std::vector<std::int64_t>> terms(static_cast<std::size_t>(options.blocks),
                                               std::vector<std::int64_t>(ms.size(), 0));
#pragma omp parallel for schedule(dynamic, 1)
  for (int b = 0; b < options.blocks; ++b) {
    const std::int64_t begin = b * block;
    const std::int64_t end = block_end(b);
    const std::vector<Gap> inside = gaps_within(gaps, begin, end);
    const std::vector<Stretch> stretches = contiguous_stretches(end - begin, inside);
    if (max_factor(AllanKind::oadev, longest_stretch(stretches) + 1) < 1) continue;
    const AllanResult a = allan_deviation(
        rate.subspan(static_cast<std::size_t>(begin), static_cast<std::size_t>(end - begin)), fs,
        InputKind::rate, allan, inside);
    for (std::size_t i = 0; i < a.m.size(); ++i) {
      const auto k = static_cast<std::size_t>(std::ranges::find(ms, a.m[i]) - ms.begin());
      if (k == ms.size()) continue;
      deviation[b][k] = a.dev[i];
      terms[b][k] = a.n[i];
    }
  }

  for (std::size_t k = 0; k < ms.size(); ++k) {
    // A block the gaps leave with fewer than a quarter of its terms is
    // left out of this tau's test.
    std::vector<double> v;
    std::vector<double> adev(terms.size(), kNaN);
    for (std::size_t b = 0; b < terms.size(); ++b) {
      if (4 * terms[b][k] >= block) {
        v.push_back(deviation[b][k] * deviation[b][k]);
        adev[b] = deviation[b][k];
      }
    }
    if (v.size() < 16) continue;
    const std::size_t eighth = v.size() / 8;
    const double first = std::accumulate(v.begin(), v.begin() + eighth, 0.0);
    const double last = std::accumulate(v.end() - eighth, v.end(), 0.0);
    const double z = mann_kendall_z(v);
    r.tau_s.push_back(static_cast<double>(ms[k]) * tau0_s);
    r.trend_z.push_back(z);
    r.last_to_first.push_back(first > 0 ? last / first : kNaN);
    r.drifting.push_back(std::abs(z) >= options.z_threshold);
    r.blocks_used.push_back(static_cast<int>(v.size()));
    r.block_adev.push_back(std::move(adev));
  }
  if (r.tau_s.empty()) {
    r.blocks = 0;
    return r;
  }
  for (int b = 0; b < options.blocks; ++b) {
    const std::int64_t begin = b * block;
    const std::int64_t end = block_end(b);
    r.block_time_s.push_back(elapsed_s(begin + (end - begin) / 2, gaps, fs));
  }
  return r;
}

}  // namespace foglab::stats
