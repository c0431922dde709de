// foglab — bias steps (steps.h).
#include "foglab/model/steps.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <utility>

#include "foglab/core/error.h"
#include "foglab/core/gaps.h"
#include "foglab/core/numeric.h"

namespace foglab::model {
namespace {

struct Candidate {
  std::int64_t index = -1;
  double size = 0.0, z = 0.0;
  double spread = 0.0;  // D's robust spread at the window that found it
  std::int64_t window = 0;
};

// Means over [i, j) of the record from its prefix sums p, with a drift of
// `slope` per sample taken out (the record's own, from the median of D).
struct Means {
  const std::vector<double>& p;
  double slope = 0.0;
  double operator()(std::int64_t i, std::int64_t j) const {
    const double sum = p[static_cast<std::size_t>(j)] - p[static_cast<std::size_t>(i)];
    return sum / static_cast<double>(j - i) - slope * 0.5 * static_cast<double>(i + j - 1);
  }
};

// D at k: the mean of the w samples from k + missing less the mean of the w
// before k (missing 0 for a step, a gap's samples for a jump across it).
double difference(const Means& raw, std::int64_t k, std::int64_t w, std::int64_t missing = 0) {
  return raw(k + missing, k + missing + w) - raw(k - w, k);
}

// visit(D, k, s) for every `stride`-th k from the start of each of
// `stretches` (s its index) where both windows lie inside it, from prefix
// sums p. The one walker of the steps and of the jumps across gaps.
template <class Visit>
void for_each_difference(const std::vector<double>& p, std::int64_t w, std::int64_t missing,
                         std::int64_t stride, std::span<const Stretch> stretches, Visit visit) {
  const Means raw{p};
  for (std::size_t s = 0; s < stretches.size(); ++s) {
    for (std::int64_t k = stretches[s].begin + w; k + missing + w <= stretches[s].end;
         k += stride) {
      visit(difference(raw, k, w, missing), k, s);
    }
  }
}

// D(k), the differences of the means of the w samples after k and the w
// before, every w/8 samples with both windows inside one of `stretches`.
struct Differences {
  std::vector<double> values;
  std::vector<std::int64_t> at;
  std::vector<std::size_t> in;  // the stretch of each
};

Differences differences_at(const std::vector<double>& p, std::int64_t w,
                           std::span<const Stretch> stretches) {
  Differences d;
  for_each_difference(p, w, 0, std::max<std::int64_t>(1, w / 8), stretches,
                      [&](double value, std::int64_t k, std::size_t s) {
                        d.values.push_back(value);
                        d.at.push_back(k);
                        d.in.push_back(s);
                      });
  return d;
}

// Fewer D than this give no spread to judge by.
constexpr std::size_t kFewestDifferences = 16;
// A step's size over 2 h agrees with its size over h within this many sd
// of their difference (best_at(): for white noise one step in 3,000
// measured over a shorter window than it could be).
constexpr double kSizeAgreement = 4.0;
// A size this small against D's spread is what levelling left: nothing.
constexpr double kNothingLeft = 1e-9;

// The most significant step at window length w, from prefix sums p, with
// every window inside one of the contiguous `stretches`.
Candidate best_at(const std::vector<double>& p, std::int64_t w,
                  std::span<const Stretch> stretches) {
  const Means raw{p};
  const auto [values, at, in] = differences_at(p, w, stretches);
  Candidate c;
  if (values.size() < kFewestDifferences) return c;
  const auto [centre, spread] = robust_spread(values);
  if (!(spread > 0.0)) return c;
  std::size_t top = 0;
  for (std::size_t i = 1; i < values.size(); ++i) {
    if (std::fabs(values[i] - centre) > std::fabs(values[top] - centre)) top = i;
  }
  const double top_dev = std::fabs(values[top] - centre);
  const std::int64_t coarse = at[top];
  const Stretch& stretch = stretches[in[top]];
  // A steady drift makes every D its slope times W (the median, centre):
  // the change point and the size are found with that slope taken out, so
  // that a drift (a temperature ramp without its channel, a rate ramp)
  // neither moves the step nor enters its size.
  const Means level{p, centre / static_cast<double>(w)};
  // The sample: the single change point of the stretch W either side,
  // where |mean after - mean before| sqrt(l r / (l + r)) peaks (l, r the
  // samples on either side): it uses the whole stretch, so it lands within
  // (sd / size)^2 samples of the step, not within the triangle's width.
  const std::int64_t a = std::max(stretch.begin, coarse - w);
  const std::int64_t b = std::min(stretch.end, coarse + w);
  std::int64_t best = coarse;
  double best_stat = -1.0;
  for (std::int64_t k = a + 1; k < b; ++k) {
    const double l = static_cast<double>(k - a), r = static_cast<double>(b - k);
    const double stat = std::fabs(level(k, b) - level(a, k)) * std::sqrt(l * r / (l + r));
    if (stat > best_stat) best_stat = stat, best = k;
  }
  const double best_dev =
      std::fabs(difference(raw, std::clamp(best, stretch.begin + w, stretch.end - w), w) - centre);
  // Its size from up to 4 W either side (four times the samples of the
  // stretch that found it: half the scatter, where the noise is white),
  // unless another change lies nearer. The size is measured over h = W/8
  // either side, and h doubled while the size over 2 h agrees with the
  // size over h within kSizeAgreement sd of their difference (for white
  // noise spread sqrt(W / 2 h), from D's spread at W). A short pulse of the
  // bias (two steps closer than the window) had been measured across both
  // edges, a fraction of its height, and then found again at the same
  // sample with size 0.
  const auto size_within = [&](std::int64_t h) {
    const std::int64_t lo = std::max(stretch.begin, best - h);
    const std::int64_t hi = std::min(stretch.end, best + h);
    return level(best, hi) - level(lo, best);
  };
  std::int64_t h = std::max<std::int64_t>(1, w / 8);
  c.size = size_within(h);
  for (; h < 4 * w; h *= 2) {
    const double wider = size_within(2 * h);
    const double allowed = kSizeAgreement * spread *
                           std::sqrt(static_cast<double>(w) / (2.0 * static_cast<double>(h)));
    if (!(std::fabs(wider - c.size) <= allowed)) break;
    c.size = wider;
  }
  c.index = best;
  c.z = std::max(best_dev, top_dev) / spread;
  c.spread = spread;
  c.window = w;
  return c;
}

// The robust centre and spread of the difference of the means of w
// samples `missing` samples apart (the w after k + missing less the w
// before k), over every place inside `stretches` where nothing is missing:
// what a jump across a gap of that length would be without one, drift,
// flicker and random walk included. At most kMostDifferences places, evenly
// spread (a record with many gaps stays fast).
constexpr std::size_t kMostDifferences = 4096;

RobustSpread differences_over(const std::vector<double>& p, std::int64_t w, std::int64_t missing,
                              std::span<const Stretch> stretches) {
  std::int64_t places = 0;
  for (const Stretch& s : stretches)
    places += std::max<std::int64_t>(0, s.size() - 2 * w - missing + 1);
  const std::int64_t stride = std::max<std::int64_t>(
      std::max<std::int64_t>(1, w / 8), places / static_cast<std::int64_t>(kMostDifferences));
  std::vector<double> values;
  for_each_difference(p, w, missing, stride, stretches,
                      [&](double value, std::int64_t, std::size_t) { values.push_back(value); });
  if (values.size() < kFewestDifferences) return {kNaN, kNaN};
  return robust_spread(values);
}

// The bias's jump across each gap between `stretches` (GapJump), from
// prefix sums p of the record as the steps left it. At each window length
// w the jump is compared with the same difference taken as far apart
// inside the stretches (differences_over): its median is the drift over
// that time, its spread what the noise moves the bias by. The size, over
// up to 4 w either side, has the record's drift (a least-squares slope)
// taken out over the time between the windows' centres.
std::vector<GapJump> jumps_across(const std::vector<double>& p, std::span<const Gap> gaps,
                                  std::span<const Stretch> stretches, double threshold) {
  const Means raw{p};
  const auto n = static_cast<std::int64_t>(p.size()) - 1;
  // The drift per sample: the least-squares slope common to the stretches,
  // each with its own level (the steps are levelled by now). The median of
  // D over the longest window, as the steps take it, had moved a jump of 5
  // across a gap of 3 x 10^5 samples by 0.2 (white noise of sd 1, 2 x 10^5
  // samples); this slope's sd there is 8e-8 per sample, 0.02 over the gap.
  double sxy = 0.0, sxx = 0.0;
  for (const Stretch& st : stretches) {
    const double mid = 0.5 * static_cast<double>(st.begin + st.end - 1);
    const double level = raw(st.begin, st.end);
    for (std::int64_t k = st.begin; k < st.end; ++k) {
      const double t = static_cast<double>(k) - mid;
      const auto i = static_cast<std::size_t>(k);
      sxy += t * (p[i + 1] - p[i] - level);
      sxx += t * t;
    }
  }
  const double slope = sxx > 0.0 ? sxy / sxx : 0.0;
  std::map<std::pair<std::int64_t, std::int64_t>, RobustSpread> apart;  // by (w, missing)
  std::vector<GapJump> jumps;
  for (std::size_t g = 0; g < gaps.size(); ++g) {
    const Stretch& before = stretches[g];
    const Stretch& after = stretches[g + 1];
    const std::int64_t missing = gaps[g].missing_samples;
    GapJump best{after.begin, kNaN, 0, kNaN, false};
    for (std::int64_t w = 64; 64 * w <= n && before.size() >= w && after.size() >= w; w *= 2) {
      // gaps of a length (a bag's lost messages: thousands of 1 or 2) share it
      auto [at, fresh] = apart.try_emplace({w, missing});
      if (fresh) at->second = differences_over(p, w, missing, stretches);
      const auto [centre, spread] = at->second;
      // D across the gap, against D as far apart inside the stretches
      const double z =
          std::fabs(difference(raw, before.end, w, after.begin - before.end) - centre) / spread;
      // the most significant window; until one is judged, the longest
      const bool judged = std::isfinite(z) && spread > 0.0;
      const bool take = judged ? !(best.significance >= z) : !std::isfinite(best.significance);
      if (!take) continue;
      const std::int64_t lo = std::max(before.begin, before.end - 4 * w);
      const std::int64_t hi = std::min(after.end, after.begin + 4 * w);
      const double distance = 0.5 * static_cast<double>(hi - after.begin) +
                              static_cast<double>(missing) +
                              0.5 * static_cast<double>(before.end - lo);
      best.size_deg_h = raw(after.begin, hi) - raw(lo, before.end) - slope * distance;
      best.window_samples = w;
      best.significance = judged ? z : kNaN;
    }
    if (best.window_samples == 0) continue;
    best.significant = best.significance > threshold;
    jumps.push_back(best);
  }
  return jumps;
}

// A step levelled out of the record takes a shift out of its level; the
// jumps of a bounded process (a random telegraph bias) levelled in part
// leave the rest as a walk. The record's wander over long times, from
// prefix sums p: the differences of neighbouring means of `block` samples
// inside each of `stretches` (their mean square is an Allan variance at
// that length).
std::vector<double> long_differences(const std::vector<double>& p, std::int64_t block,
                                     std::span<const Stretch> stretches) {
  std::vector<double> d;
  for_each_difference(p, block, 0, block, stretches,
                      [&](double value, std::int64_t, std::size_t) { d.push_back(value); });
  return d;
}

// Whether levelling made the record wander more than chance allows:
// `before` and `after` its long differences unlevelled and levelled. With
// delta = before - after (the levelled steps' own differences) the growth
// of the sum of squares, sum(after^2) - sum(before^2) = -2 sum(after
// delta) - sum(delta^2), is negative for steps that were there, give or
// take 2 sqrt(v sum(delta^2)) where after's differences are noise of
// variance v (their mean square; before's where that is less: a bounded
// process levelled in part makes after's a walk). Beyond
// kWanderSignificance of that, the levelled record wanders with what was
// taken out. For steps that were there the growth is that scatter less
// sum(delta^2), so a false call (2.3 % at 2) can only come where the steps
// hardly move the long-term level, and leaving those in costs little: a
// 46-sample pulse 6.3 s into the ADIS16405 imu1 y record stands at 1.3 and
// stays two steps. A telegraph bias of +-0.5 deg/h (2 h, 100 s dwell) with
// 15 of its jumps levelled stood at 2.6.
constexpr double kWanderSignificance = 2.0;

bool wanders_more(std::span<const double> before, std::span<const double> after) {
  if (before.size() != after.size() || before.size() < 2) return false;
  double delta_squares = 0.0, cross = 0.0, v_after = 0.0, v_before = 0.0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const double delta = before[i] - after[i];
    delta_squares += delta * delta;
    cross += after[i] * delta;
    v_after += after[i] * after[i];
    v_before += before[i] * before[i];
  }
  const double v = std::min(v_after, v_before) / static_cast<double>(after.size());
  const double growth = -2.0 * cross - delta_squares;
  return delta_squares > 0.0 && growth > kWanderSignificance * 2.0 * std::sqrt(v * delta_squares);
}

// From this many steps on, the wander (above) is asked: one step alone is
// a glitch whatever its effect on the wander.
constexpr std::size_t kFewestForAProcess = 2;
// The wander is read at this share of the record (about 15 differences).
constexpr std::int64_t kWanderBlocks = 16;

// Whether the steps, their `sizes` in time order, go back and forth between
// two levels, as a telegraph bias does when every jump of it is found (and
// levelling them all leaves the record calm): at least four, and of the
// neighbouring pairs three quarters or more opposite in sign and within a
// quarter of their mean size of each other (a glitch's steps have no
// reason to undo the one before; a missed short pulse spoils one pair).
bool between_two_levels(std::span<const double> sizes) {
  constexpr std::size_t kFewest = 4;
  if (sizes.size() < kFewest) return false;
  std::size_t returns = 0;
  for (std::size_t i = 1; i < sizes.size(); ++i) {
    const double a = sizes[i - 1], b = sizes[i];
    returns += a * b < 0.0 && std::fabs(a + b) <= 0.25 * 0.5 * (std::fabs(a) + std::fabs(b));
  }
  return 4 * returns >= 3 * (sizes.size() - 1);
}

// Adds `sign` times each step's size to every sample from the step on (-1: levels them).
void shift_after_steps(std::span<double> y, const BiasSteps& steps, double sign) {
  for (std::size_t i = 0; i < steps.indices.size(); ++i) {
    const double by = sign * steps.sizes_deg_h[i];
    for (std::size_t k = static_cast<std::size_t>(steps.indices[i]); k < y.size(); ++k) y[k] += by;
  }
}

}  // namespace

void level_steps(std::span<double> rate_deg_h, const BiasSteps& steps) {
  shift_after_steps(rate_deg_h, steps, -1.0);
}

BiasSteps find_steps(std::span<double> y, const StepOptions& options, double lsb_deg_h,
                     std::span<const Gap> gaps, std::span<const double> baseline_deg_h) {
  BiasSteps steps;
  const auto n = static_cast<std::int64_t>(y.size());
  if (!baseline_deg_h.empty() && baseline_deg_h.size() != y.size()) {
    throw UsageError(fmt::format("bias steps: {} rate samples but {} of the baseline", y.size(),
                                 baseline_deg_h.size()));
  }
  check_gaps(gaps, n, "bias steps");
  auto base = [&](std::size_t k) { return baseline_deg_h.empty() ? 0.0 : baseline_deg_h[k]; };
  double mean = 0.0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    if (!std::isfinite(y[k]) || !std::isfinite(base(k))) return steps;  // the readers refuse these
    mean += y[k] - base(k);
  }
  mean /= static_cast<double>(std::max<std::int64_t>(1, n));
  const std::vector<Stretch> stretches = contiguous_stretches(n, gaps);
  // Prefix sums of y - baseline - mean (one array beside the record; the
  // steps are levelled in y itself and put back when they are only to be
  // reported).
  std::vector<double> p(y.size() + 1);
  const auto fill_prefix_sums = [&] {
    p[0] = 0.0;
    auto v = [&](std::size_t k) { return y[k] - base(k) - mean; };
    // An outlier's departure from its neighbours' mean, h; its neighbours
    // depart by about -h/2 and are left (pulling them in would put back
    // what was taken from it).
    auto h = [&](std::size_t k) { return v(k) - 0.5 * (v(k - 1) + v(k + 1)); };
    const double clip = options.outlier_clip_deg_h;
    for (std::size_t k = 0; k < y.size(); ++k) {
      double value = v(k);
      if (clip > 0.0 && k > 0 && k + 1 < y.size()) {
        const double hk = h(k);
        const bool centre = (k < 2 || std::fabs(h(k - 1)) <= std::fabs(hk)) &&
                            (k + 2 >= y.size() || std::fabs(h(k + 1)) <= std::fabs(hk));
        if (std::fabs(hk) > clip && centre) value -= std::copysign(std::fabs(hk) - clip, hk);
      }
      p[k + 1] = p[k] + value;
    }
  };
  using AsNoise = BiasSteps::AsNoise;
  AsNoise as_noise = AsNoise::none;
  const std::int64_t block = std::max<std::int64_t>(1, n / kWanderBlocks);
  std::vector<double> unlevelled;  // its long differences
  for (int round = 0;; ++round) {
    fill_prefix_sums();
    if (round == 0) unlevelled = long_differences(p, block, stretches);
    Candidate best;
    for (std::int64_t w = 64; 64 * w <= n; w *= 2) {
      const Candidate c = best_at(p, w, stretches);
      if (c.index >= 0 && c.z > best.z) best = c;
    }
    if (best.index < 0 || !(best.z > options.threshold)) break;
    if (!(std::fabs(best.size) > kNothingLeft * best.spread) || std::fabs(best.size) < lsb_deg_h)
      break;
    if (round == options.max_steps) {
      as_noise = AsNoise::beyond_limit;
      break;
    }
    for (std::int64_t k = best.index; k < n; ++k) y[static_cast<std::size_t>(k)] -= best.size;
    steps.indices.push_back(best.index);
    steps.sizes_deg_h.push_back(best.size);
    steps.window_samples.push_back(best.window);
    steps.significance.push_back(best.z);
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
  const auto put_back = [&] { shift_after_steps(y, sorted, +1.0); };
  // More jumps than max_steps, levelling that makes the record wander
  // more, or jumps back and forth between two levels: the bias jumps as a
  // process (a random telegraph or popcorn noise), not at a few glitches;
  // levelling some of them would leave a record that is neither, so none
  // is levelled and the statistics see the process.
  if (as_noise == AsNoise::none && sorted.indices.size() >= kFewestForAProcess) {
    fill_prefix_sums();
    if (wanders_more(unlevelled, long_differences(p, block, stretches))) {
      as_noise = AsNoise::wander;
    } else if (between_two_levels(sorted.sizes_deg_h)) {
      as_noise = AsNoise::two_levels;
    }
  }
  const bool left_in = as_noise != AsNoise::none;
  if (left_in) put_back();
  if (!gaps.empty()) {  // on the record as the statistics see it (levelled unless as noise)
    fill_prefix_sums();
    sorted.across_gaps = jumps_across(p, gaps, stretches, options.threshold);
  }
  if (!options.remove && !left_in) put_back();
  sorted.removed = options.remove && !left_in && !sorted.indices.empty();
  sorted.left_as_noise_because = as_noise;
  return sorted;
}

}  // namespace foglab::model
