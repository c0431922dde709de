// foglab — stamps on their grid (stamp_grid.h says what for).
#include "stamp_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

namespace foglab::io::internal {
namespace {

// A uniform grid has two parameters: its step T and its phase. A stamp's position relative to
// the grid, frac((t - t0) / T), is its phase; jitter spreads the phases about the grid's, and a
// dropped or repeated message shifts a stamp by whole steps, which leaves its phase alone. So
// the step and the phase are found from phases (circular statistics: the angle of the mean of
// exp(2 pi i phase)), never by counting steps, and a stamp then lies in the slot
// round((t - t0) / T - phase). Rounding against the grid rather than against the previous
// stamp is what keeps jitter of up to +-40 % of a step from making a gap (a step between two
// jittered stamps can be 0.2 or 1.8 steps, which step counting would call a duplicate or a
// gap).
//   1. T starts as the median step. It is refined in stages: the phase of a block of B stamps
//      (their circular mean) moves from one block to the next by B times the step's relative
//      error (mod 1), so each stage takes blocks four times longer than the last (16 stamps
//      first), while B times the remaining error stays well below half a step. A block's
//      phase averages the jitter out of B stamps, and a dropped stamp leaves it alone: the
//      phase differences of single stamps L apart (this method's first form) are spread over
//      the whole cycle by +-40 % jitter on both, and the pairs with a dropped stamp between
//      them that pass for L apart biased them: with 1 % of the stamps lost and +-30 % jitter
//      the step came out 0.05 % off and the slots wrong.
//   2. The phase is the circular mean over a window of about 4000 messages around each
//      message (blocks of 256, unwrapped from block to block), which follows a slow drift of
//      the recording host's clock against the sensor's.
//   3. A message whose slot is not after the previous message's is dropped; slots skipped are
//      a gap. The rate is then the least-squares slope of stamp against slot.

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Angle, in cycles in (-0.5, 0.5], of a sum of unit vectors.
double cycles(double sum_cos, double sum_sin) { return std::atan2(sum_sin, sum_cos) / kTwoPi; }

// `x` minus the nearest integer: in [-0.5, 0.5].
double wrap(double x) { return x - std::round(x); }

// Step 1 above: the step [s] refined from `step_s` by the phases of blocks of stamps.
double refine_step_s(std::span<const std::int64_t> stamps_ns, double step_s) {
  constexpr std::size_t kMaxStamps = std::size_t{1} << 18;  // a stage's, spread over the record
  const std::size_t n = stamps_ns.size();
  // blocks up to 65,536 stamps: the step is then within about 1e-7 of its own, and step 2's
  // window follows what is left
  for (std::size_t block = 16; 2 * block <= std::min(n, kMaxStamps); block *= 4) {
    // pairs of neighbouring blocks, spread over the record
    const std::size_t pairs = std::min(n, kMaxStamps) / (2 * block);
    const std::size_t stride = (n - 2 * block) / pairs + 1;
    // A block's phase (circular mean) and mean position, in steps from the first stamp.
    auto block_at = [&](std::size_t first, double& mean_position) {
      double c = 0.0;
      double s = 0.0;
      double sum = 0.0;
      for (std::size_t k = first; k < first + block; ++k) {
        const double position = static_cast<double>(stamps_ns[k] - stamps_ns[0]) * 1e-9 / step_s;
        c += std::cos(kTwoPi * position);
        s += std::sin(kTwoPi * position);
        sum += position;
      }
      mean_position = sum / static_cast<double>(block);
      return cycles(c, s);
    };
    double c = 0.0;
    double s = 0.0;
    double span = 0.0;
    std::size_t used = 0;
    for (std::size_t first = 0; first + 2 * block <= n; first += stride) {
      double before = 0.0;
      double after = 0.0;
      const double difference = block_at(first + block, after) - block_at(first, before);
      // Not across a gap (a pause of an hour): there the phase difference is the step's error
      // times the slots between, too many to unwrap.
      if (after - before > 2.0 * static_cast<double>(block)) continue;
      c += std::cos(kTwoPi * difference);
      s += std::sin(kTwoPi * difference);
      span += after - before;
      ++used;
    }
    if (used == 0) break;
    // The blocks' phase difference is their distance in steps times step_s' relative error.
    step_s *= 1.0 + cycles(c, s) / (span / static_cast<double>(used));
  }
  return step_s;
}

// Step 2 above: the grid's phase along the record, and from it each message's slot (the first
// message's is 0), computed when asked for rather than stored (10^7 slots).
class GridSlots {
 public:
  GridSlots(std::span<const std::int64_t> stamps_ns, double step_s)
      : stamps_ns_(stamps_ns), step_s_(step_s) {
    const std::size_t n = stamps_ns.size();
    const std::size_t blocks = (n + kBlock - 1) / kBlock;
    std::vector<double> block_cos(blocks, 0.0);
    std::vector<double> block_sin(blocks, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      const double angle = kTwoPi * position(k);
      block_cos[k / kBlock] += std::cos(angle);
      block_sin[k / kBlock] += std::sin(angle);
    }
    // The windowed phase at each block, unwrapped from block to block.
    phase_.resize(blocks);
    double c = 0.0;
    double s = 0.0;
    for (std::size_t b = 0; b < std::min(blocks, kHalfWindowBlocks + 1); ++b) {
      c += block_cos[b];
      s += block_sin[b];
    }
    for (std::size_t b = 0; b < blocks; ++b) {
      if (b > 0) {
        if (b + kHalfWindowBlocks < blocks) {
          c += block_cos[b + kHalfWindowBlocks];
          s += block_sin[b + kHalfWindowBlocks];
        }
        if (b > kHalfWindowBlocks) {
          c -= block_cos[b - kHalfWindowBlocks - 1];
          s -= block_sin[b - kHalfWindowBlocks - 1];
        }
      }
      const double angle = cycles(c, s);
      phase_[b] = b == 0 ? angle : phase_[b - 1] + wrap(angle - phase_[b - 1]);
    }
    first_ = 0;
    first_ = slot(0);
  }

  // The slot of message k, from the first stamp's; `offset_steps`, when given, receives the
  // stamp's distance from that slot [steps].
  std::int64_t slot(std::size_t k, double* offset_steps = nullptr) const {
    // The phase between block centres by linear interpolation.
    const double at = (static_cast<double>(k) + 0.5) / kBlock - 0.5;
    double p = phase_.front();
    if (at >= static_cast<double>(phase_.size() - 1)) {
      p = phase_.back();
    } else if (at > 0.0) {
      const auto b = static_cast<std::size_t>(at);
      const double f = at - static_cast<double>(b);
      p = phase_[b] + f * (phase_[b + 1] - phase_[b]);
    }
    const double place = position(k) - p;
    if (offset_steps != nullptr) *offset_steps = place - std::round(place);
    return std::llround(place) - first_;
  }

 private:
  static constexpr std::size_t kBlock = 256;
  static constexpr std::size_t kHalfWindowBlocks = 8;
  // Message k's stamp in steps from the first.
  double position(std::size_t k) const {
    return static_cast<double>(stamps_ns_[k] - stamps_ns_.front()) * 1e-9 / step_s_;
  }
  std::span<const std::int64_t> stamps_ns_;
  double step_s_;
  std::vector<double> phase_;
  std::int64_t first_ = 0;
};

}  // namespace

// The median of the positive steps between consecutive stamps [s], exact, without a copy of
// all of them (10^7 steps: a second of page faults on a virtual machine): a strided sample
// brackets the median, one pass counts the steps below the bracket and keeps those inside it,
// and the median is the right one of those. Should the bracket miss it (a sample that does not
// represent the record), every step is copied.
double median_step_s(std::span<const std::int64_t> stamps_ns) {
  const std::size_t n = stamps_ns.size();
  auto step = [&](std::size_t k) { return stamps_ns[k] - stamps_ns[k - 1]; };
  auto select = [](std::vector<std::int64_t>& v, std::size_t rank) {
    const auto at = v.begin() + static_cast<std::ptrdiff_t>(rank);
    std::nth_element(v.begin(), at, v.end());
    return static_cast<double>(*at) * 1e-9;
  };
  std::size_t positive = 0;
  for (std::size_t k = 1; k < n; ++k) positive += step(k) > 0 ? 1 : 0;
  if (positive == 0) return 0.0;
  const std::size_t rank = (positive - 1) / 2;  // of the median, among the positive steps

  constexpr std::size_t kSample = std::size_t{1} << 16;
  if (positive > 16 * kSample) {
    std::vector<std::int64_t> sample;
    sample.reserve(kSample + 1);
    const std::size_t stride = (n - 1) / kSample;
    for (std::size_t k = 1; k < n; k += stride) {
      if (step(k) > 0) sample.push_back(step(k));
    }
    std::sort(sample.begin(), sample.end());
    // A bracket of +-2 % of the sample about its median: wide against the sample's error in
    // rank (about 0.2 % of the steps for 65,536 samples).
    const std::size_t margin = sample.size() / 50;
    const std::int64_t low = sample[sample.size() / 2 - margin];
    const std::int64_t high = sample[sample.size() / 2 + margin];
    std::size_t below = 0;
    std::vector<std::int64_t> inside;
    inside.reserve(positive / 10);
    for (std::size_t k = 1; k < n; ++k) {
      const std::int64_t d = step(k);
      if (d <= 0) continue;
      if (d < low) {
        ++below;
      } else if (d <= high) {
        inside.push_back(d);
      }
    }
    if (rank >= below && rank - below < inside.size()) return select(inside, rank - below);
  }
  std::vector<std::int64_t> steps;
  steps.reserve(positive);
  for (std::size_t k = 1; k < n; ++k) {
    if (step(k) > 0) steps.push_back(step(k));
  }
  return select(steps, rank);
}

StampGrid fit_stamp_grid(std::span<const std::int64_t> stamps_ns, double median_s) {
  StampGrid fit;
  const std::size_t n = stamps_ns.size();
  if (n < 2 || !(median_s > 0.0)) return fit;

  // The grid, then the stamps kept on it and their gaps (step 3 above).
  const GridSlots grid(stamps_ns, refine_step_s(stamps_ns, median_s));
  std::int64_t last_slot = 0;
  std::size_t kept = 1;
  double scatter = 0.0;
  grid.slot(0, &scatter);
  double sum_squares = scatter * scatter;
  std::int64_t last_stamp = stamps_ns[0];
  for (std::size_t k = 1; k < n; ++k) {
    double offset = 0.0;
    const std::int64_t slot = grid.slot(k, &offset);
    sum_squares += offset * offset;
    const std::int64_t skipped = slot - last_slot - 1;
    if (skipped < 0 || stamps_ns[k] <= last_stamp) {
      fit.dropped.push_back(k);
      continue;
    }
    if (skipped > 0) fit.gaps.push_back(Gap{static_cast<std::int64_t>(kept), skipped});
    ++kept;
    last_slot = slot;
    last_stamp = stamps_ns[k];
  }
  fit.scatter_rms_steps = std::sqrt(sum_squares / static_cast<double>(n));

  // Least squares of stamp (from the first, [s]) against slot, in two passes for accuracy;
  // the slot of the i-th sample kept is i plus the samples missing before it.
  auto for_each_sample = [&](auto&& f) {
    std::size_t d = 0;
    std::size_t g = 0;
    std::int64_t i = 0;
    std::int64_t missing = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (d < fit.dropped.size() && fit.dropped[d] == k) {
        ++d;
        continue;
      }
      while (g < fit.gaps.size() && fit.gaps[g].before_sample == i) {
        missing += fit.gaps[g++].missing_samples;
      }
      f(static_cast<double>(i + missing), static_cast<double>(stamps_ns[k] - stamps_ns[0]) * 1e-9);
      ++i;
    }
  };
  double mean_slot = 0.0;
  double mean_s = 0.0;
  for_each_sample([&](double slot, double t_s) {
    mean_slot += slot;
    mean_s += t_s;
  });
  mean_slot /= static_cast<double>(kept);
  mean_s /= static_cast<double>(kept);
  double sxx = 0.0;
  double sxy = 0.0;
  for_each_sample([&](double slot, double t_s) {
    sxx += (slot - mean_slot) * (slot - mean_slot);
    sxy += (slot - mean_slot) * (t_s - mean_s);
  });
  const double step_s = sxx > 0.0 ? sxy / sxx : 0.0;
  if (!(step_s > 0.0)) return fit;
  fit.step_s = step_s;
  double residual_squares = 0.0;
  for_each_sample([&](double slot, double t_s) {
    const double residual = t_s - mean_s - step_s * (slot - mean_slot);
    residual_squares += residual * residual;
    fit.jitter_max_s = std::max(fit.jitter_max_s, std::abs(residual));
  });
  fit.jitter_rms_s = std::sqrt(residual_squares / static_cast<double>(kept));
  return fit;
}

void drop_entries(std::vector<double>& values, const std::vector<std::size_t>& dropped) {
  if (dropped.empty()) return;
  std::size_t d = 0;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (d < dropped.size() && dropped[d] == k) {
      ++d;
      continue;
    }
    values[kept++] = values[k];
  }
  values.resize(kept);
}

}  // namespace foglab::io::internal
