// foglab — spikes (spikes.h).
#include "foglab/model/spikes.h"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>

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

// The noise's tail (spikes.h): the outlier centres between 4 and 8 robust
// standard deviations `sd`, whether Gaussian noise explains those beyond 5,
// and, when not, the size its power law exceeds with probability 0.05.
struct Tail {
  std::int64_t shoulder = 0;  // centres in (5, 8] sd
  double expected = 0.0;      // Gaussian noise's count there
  bool heavy = false;
  double alpha = 0.0;
  double beyond_deg_h = 0.0;  // spikes only beyond this
};

Tail noise_tail(std::span<const double> y, double sd) {
  constexpr double kLow = 4.0, kShoulder = kGaussianBulkEnd, kHigh = 8.0;
  constexpr double kLeastShoulder = 25.0, kTimesGaussian = 10.0, kTailChance = 0.05;
  Tail t;
  const std::size_t n = y.size();
  std::vector<double> band;  // |h| / sd of the centres in (kLow, kHigh]
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double a = std::fabs(h_at(y, k)) / sd;
    if (!(a > kLow && a <= kHigh)) continue;
    if ((k >= 2 && std::fabs(h_at(y, k - 1)) / sd > a) ||
        (k + 2 < n && std::fabs(h_at(y, k + 1)) / sd > a)) {
      continue;  // the neighbour of a larger outlier, not a centre
    }
    band.push_back(a);
    t.shoulder += a > kShoulder;
  }
  // Two-sided Gaussian tail mass between 5 and 8 sd.
  const double gauss = std::erfc(kShoulder / std::sqrt(2.0)) - std::erfc(kHigh / std::sqrt(2.0));
  t.expected = gauss * static_cast<double>(n - 2);
  const auto shoulder = static_cast<double>(t.shoulder);
  t.heavy = shoulder >= kLeastShoulder && shoulder >= kTimesGaussian * t.expected;
  if (!t.heavy) return t;
  // The truncated Pareto law on (kLow, kHigh]: the score in alpha is
  // m/alpha - sum log(x/kLow) - m r log(kHigh/kLow) / (1 - r), r = (kLow/kHigh)^alpha,
  // falling in alpha; its root is the maximum likelihood.
  double logs = 0.0;
  for (double a : band) logs += std::log(a / kLow);
  const auto m = static_cast<double>(band.size());
  const double span = std::log(kHigh / kLow);
  auto score = [&](double alpha) {
    const double r = std::exp(-alpha * span);
    return m / alpha - logs - m * r * span / (1.0 - r);
  };
  double lo = 0.05, hi = 200.0;
  if (score(hi) > 0.0) {
    t.alpha = hi;  // as steep as Gaussian noise: nothing to extend
  } else if (score(lo) < 0.0) {
    t.alpha = lo;
  } else {
    boost::math::tools::eps_tolerance<double> tolerance(30);
    std::uintmax_t iterations = 100;
    const auto [a, b] = boost::math::tools::toms748_solve(score, lo, hi, tolerance, iterations);
    t.alpha = 0.5 * (a + b);
  }
  // The law's count beyond kLow, then the size it exceeds kTailChance times.
  const double beyond_low = m / (1.0 - std::exp(-t.alpha * span));
  t.beyond_deg_h = kLow * sd * std::pow(beyond_low / kTailChance, 1.0 / t.alpha);
  return t;
}

// The excess kurtosis of y_(k+1) - y_k (at least 0). For white noise of
// excess kurtosis g the difference of two samples has g / 2; the other
// processes barely move the first differences.
double difference_excess_kurtosis(std::span<const double> y) {
  double m2 = 0.0, m4 = 0.0, count = 0.0;
  for (std::size_t k = 1; k < y.size(); ++k) {
    const double d = y[k] - y[k - 1];
    if (!std::isfinite(d)) continue;
    m2 += d * d;
    m4 += d * d * d * d;
    count += 1.0;
  }
  if (!(m2 > 0.0)) return 0.0;
  m2 /= count;
  m4 /= count;
  return std::max(0.0, m4 / (m2 * m2) - 3.0);
}

}  // namespace

Spikes find_spikes(std::span<double> y, const SpikeOptions& options, double lsb_deg_h) {
  Spikes s;
  const std::size_t n = y.size();
  if (n < 16) return s;
  s.robust_sd_deg_h = robust_sd(y);
  if (!(s.robust_sd_deg_h > 0.0)) return s;
  constexpr double kLeastSteps = 4.0;  // output steps a spike departs by at least
  const Tail tail = noise_tail(y, s.robust_sd_deg_h);
  s.shoulder_count = tail.shoulder;
  s.shoulder_expected = tail.expected;
  s.heavy_tailed = tail.heavy;
  s.tail_index = tail.alpha;
  s.threshold_deg_h = std::max({options.threshold * s.robust_sd_deg_h,
                                kLeastSteps * std::max(0.0, lsb_deg_h), tail.beyond_deg_h});
  if (s.heavy_tailed) s.excess_kurtosis = difference_excess_kurtosis(y) * 2.0;
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
