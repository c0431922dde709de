// foglab — spikes (spikes.h).
#include "foglab/model/spikes.h"

#include <algorithm>
#include <cmath>

#include "foglab/core/numeric.h"

namespace foglab::model {
namespace {

double h_at(std::span<const double> y, std::size_t k) { return y[k] - 0.5 * (y[k - 1] + y[k + 1]); }

// The robust scale of h over (up to a million of) the record's samples.
double robust_sd(std::span<const double> y) {
  const std::size_t n = y.size();
  const std::size_t stride = std::max<std::size_t>(1, (n - 2) / 1000000);
  std::vector<double> h;
  h.reserve((n - 2) / stride + 1);
  for (std::size_t k = 1; k + 1 < n; k += stride) {
    const double v = h_at(y, k);
    if (std::isfinite(v)) h.push_back(v);
  }
  if (h.size() < 8) return 0.0;
  const double spread = robust_spread(h).spread;
  if (spread > 0.0) return spread;
  // A coarse output word: most h are 0 and so is their MAD. The root mean
  // square of h stands in (a few spikes raise it, so it errs towards
  // finding fewer).
  double ss = 0.0, bulk = 0.0;
  for (double v : h) {
    ss += v * v;
    bulk += 1.0;
  }
  return std::sqrt(ss / bulk);
}

}  // namespace

Spikes find_spikes(std::span<double> y, const SpikeOptions& options, double lsb_deg_h) {
  Spikes s;
  const std::size_t n = y.size();
  if (n < 16) return s;
  s.robust_sd_deg_h = robust_sd(y);
  if (!(s.robust_sd_deg_h > 0.0)) return s;
  constexpr double kLeastSteps = 4.0;  // output steps a spike departs by at least
  s.threshold_deg_h =
      std::max(options.threshold * s.robust_sd_deg_h, kLeastSteps * std::max(0.0, lsb_deg_h));
  std::vector<std::size_t> found;
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double h = h_at(y, k);
    if (!(std::fabs(h) > s.threshold_deg_h)) continue;
    // Isolated: each neighbour departs from its own neighbours by what the
    // spike does to it (-h/2), to within half the threshold; a step (h/2
    // at one sample, -h/2 before it and 0 after) or a longer excursion
    // does not.
    const double tolerance = 0.5 * s.threshold_deg_h;
    const bool left = k >= 2 && std::fabs(h_at(y, k - 1) + 0.5 * h) > tolerance;
    const bool right = k + 2 < n && std::fabs(h_at(y, k + 1) + 0.5 * h) > tolerance;
    if (left || right) continue;
    found.push_back(k);
    if (s.indices.size() < options.max_reported) {
      s.indices.push_back(static_cast<std::int64_t>(k));
      s.sizes_deg_h.push_back(h);
    }
  }
  s.count = static_cast<std::int64_t>(found.size());
  if (options.remove) {
    for (std::size_t k : found) y[k] = 0.5 * (y[k - 1] + y[k + 1]);
    s.removed = !found.empty();
  }
  return s;
}

}  // namespace foglab::model
