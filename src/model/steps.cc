// foglab — bias steps (steps.h).
#include "foglab/model/steps.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "foglab/core/numeric.h"

namespace foglab::model {
namespace {

struct Candidate {
  std::int64_t index = -1;
  double size = 0.0, z = 0.0;
  std::int64_t window = 0;
};

// The most significant step at window length w, from prefix sums p.
Candidate best_at(const std::vector<double>& p, std::int64_t w) {
  const auto n = static_cast<std::int64_t>(p.size()) - 1;
  auto d = [&](std::int64_t k) {
    return (p[static_cast<std::size_t>(k + w)] - p[static_cast<std::size_t>(k)] -
            (p[static_cast<std::size_t>(k)] - p[static_cast<std::size_t>(k - w)])) /
           static_cast<double>(w);
  };
  const std::int64_t stride = std::max<std::int64_t>(1, w / 8);
  std::vector<double> values;
  for (std::int64_t k = w; k + w <= n; k += stride) values.push_back(d(k));
  Candidate c;
  if (values.size() < 16) return c;
  const auto [centre, spread] = robust_spread(values);
  if (!(spread > 0.0)) return c;
  std::size_t top = 0;
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (std::fabs(values[i] - centre) > std::fabs(values[top] - centre)) top = i;
  }
  const double top_dev = std::fabs(values[top] - centre);
  const std::int64_t coarse = w + static_cast<std::int64_t>(top) * stride;
  // The sample: the single change point of the stretch W either side,
  // where |mean after - mean before| sqrt(l r / (l + r)) peaks (l, r the
  // samples on either side): it uses the whole stretch, so it lands within
  // (sd / size)^2 samples of the step, not within the triangle's width.
  const std::int64_t a = std::max<std::int64_t>(0, coarse - w);
  const std::int64_t b = std::min(n, coarse + w);
  std::int64_t best = coarse;
  double best_stat = -1.0;
  const double sum = p[static_cast<std::size_t>(b)] - p[static_cast<std::size_t>(a)];
  for (std::int64_t k = a + 1; k < b; ++k) {
    const double l = static_cast<double>(k - a), r = static_cast<double>(b - k);
    const double left = (p[static_cast<std::size_t>(k)] - p[static_cast<std::size_t>(a)]) / l;
    const double right = (sum - left * l) / r;
    const double stat = std::fabs(right - left) * std::sqrt(l * r / (l + r));
    if (stat > best_stat) best_stat = stat, best = k;
  }
  const double best_dev = std::fabs(d(std::clamp(best, w, n - w)) - centre);
  // Its size from up to 4 W either side (four times the samples of the
  // stretch that found it: half the scatter, where the noise is white).
  const std::int64_t lo = std::max<std::int64_t>(0, best - 4 * w);
  const std::int64_t hi = std::min(n, best + 4 * w);
  const double best_size = (p[static_cast<std::size_t>(hi)] - p[static_cast<std::size_t>(best)]) /
                  static_cast<double>(hi - best) -
              (p[static_cast<std::size_t>(best)] - p[static_cast<std::size_t>(lo)]) /
                  static_cast<double>(best - lo);
  c.index = best;
  c.size = best_size;
  c.z = std::max(best_dev, top_dev) / spread;
  c.window = w;
  return c;
}

}  // namespace

BiasSteps find_steps(std::span<double> y, const StepOptions& options, double lsb_deg_h) {
  BiasSteps steps;
  const auto n = static_cast<std::int64_t>(y.size());
  double mean = 0.0;
  for (double v : y) {
    if (!std::isfinite(v)) return steps;  // the readers refuse these; nothing to do
    mean += v;
  }
  mean /= static_cast<double>(std::max<std::int64_t>(1, n));
  // Prefix sums of y - mean (one array beside the record; the steps are
  // levelled in y itself and put back when they are only to be reported).
  std::vector<double> p(y.size() + 1);
  for (int round = 0; round < options.max_steps; ++round) {
    p[0] = 0.0;
    for (std::size_t k = 0; k < y.size(); ++k) p[k + 1] = p[k] + (y[k] - mean);
    Candidate best;
    for (std::int64_t w = 64; 64 * w <= n; w *= 2) {
      const Candidate c = best_at(p, w);
      if (c.index >= 0 && c.z > best.z) best = c;
    }
    if (best.index < 0 || !(best.z > options.threshold)) break;
    if (!(std::fabs(best.size) > 0.0) || std::fabs(best.size) < lsb_deg_h) break;
    for (std::int64_t k = best.index; k < n; ++k) y[static_cast<std::size_t>(k)] -= best.size;
    steps.indices.push_back(best.index);
    steps.sizes_deg_h.push_back(best.size);
    steps.window_samples.push_back(best.window);
    steps.significance.push_back(best.z);
  }
  if (!options.remove) {
    for (std::size_t i = 0; i < steps.indices.size(); ++i) {
      for (std::int64_t k = steps.indices[i]; k < n; ++k) {
        y[static_cast<std::size_t>(k)] += steps.sizes_deg_h[i];
      }
    }
  }
  // Time order.
  std::vector<std::size_t> order(steps.indices.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return steps.indices[a] < steps.indices[b]; });
  BiasSteps sorted;
  for (std::size_t i : order) {
    sorted.indices.push_back(steps.indices[i]);
    sorted.sizes_deg_h.push_back(steps.sizes_deg_h[i]);
    sorted.window_samples.push_back(steps.window_samples[i]);
    sorted.significance.push_back(steps.significance[i]);
  }
  sorted.removed = options.remove && !sorted.indices.empty();
  return sorted;
}

}  // namespace foglab::model
