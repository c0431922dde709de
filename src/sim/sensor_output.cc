// foglab — the sensor's output chain (sensor_output.h).
#include "foglab/sim/sensor_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <utility>

#include "foglab/core/error.h"
#include "foglab/core/sensor_bandwidth.h"
#include "foglab/sim/generator.h"
#include "generator_internal.h"

namespace foglab::sim {
namespace {

// Process ids of the counter-based generator for the output chain (beside
// generator.cc's; never reuse or renumber).
constexpr std::uint64_t kSpike = 9;
constexpr std::uint64_t kSpikeSign = 10;
constexpr std::uint64_t kTimeJitter = 11;

// Whether sample `index` carries a spike: one draw of the counter-based
// generator under the spike process's key, below the per-sample probability
// (OutputChain and spike_times_s draw the same way).
bool spike_at(std::uint64_t key, std::int64_t index, double probability) {
  return probability > 0.0 &&
         detail::uniform_of(detail::word_at(key, static_cast<std::uint64_t>(index))) < probability;
}

double spike_probability(const SensorOutput& output, double sample_rate_hz) {
  return output.spike_rate_per_hour / (3600.0 * sample_rate_hz);
}

// The largest amplitude, step, spike or output step [deg/h] and filter
// time constant [s]: far beyond any sensor, and no sample can overflow.
constexpr double kMaxSize = 1e9;

void check(bool ok, std::string_view field, double value, std::string_view expected) {
  if (!ok) {
    throw UsageError(fmt::format("SensorOutput::{} = {}: expected {}", field, value, expected));
  }
}

}  // namespace

bool SensorOutput::any() const {
  return !sinusoids.empty() || !square_waves.empty() || !steps.empty() ||
         moving_average_samples > 1 || filter_time_constant_s > 0.0 ||
         butterworth_cutoff_hz > 0.0 || spike_rate_per_hour > 0.0 || lsb_deg_h > 0.0;
}

void validate(const SensorOutput& o, double sample_rate_hz) {
  for (const Sinusoid& s : o.sinusoids) {
    check(std::isfinite(s.frequency_hz) && s.frequency_hz > 0.0 &&
              s.frequency_hz < 0.5 * sample_rate_hz,
          "sinusoids[].frequency_hz", s.frequency_hz, "> 0 and below half the sample rate");
    check(s.amplitude_deg_h >= 0.0 && s.amplitude_deg_h <= kMaxSize, "sinusoids[].amplitude_deg_h",
          s.amplitude_deg_h, "in [0, 1e9]");
    check(std::isfinite(s.phase_rad), "sinusoids[].phase_rad", s.phase_rad, "a finite number");
  }
  for (const SquareWave& s : o.square_waves) {
    check(std::isfinite(s.frequency_hz) && s.frequency_hz > 0.0 &&
              s.frequency_hz < 0.5 * sample_rate_hz,
          "square_waves[].frequency_hz", s.frequency_hz, "> 0 and below half the sample rate");
    check(s.amplitude_deg_h >= 0.0 && s.amplitude_deg_h <= kMaxSize,
          "square_waves[].amplitude_deg_h", s.amplitude_deg_h, "in [0, 1e9]");
    check(std::isfinite(s.phase_rad), "square_waves[].phase_rad", s.phase_rad, "a finite number");
  }
  for (const BiasStep& s : o.steps) {
    check(std::isfinite(s.time_s) && s.time_s >= 0.0, "steps[].time_s", s.time_s,
          "a finite time >= 0");
    check(std::fabs(s.size_deg_h) <= kMaxSize, "steps[].size_deg_h", s.size_deg_h,
          "at most 1e9 in magnitude");
  }
  check(o.moving_average_samples >= 1 && o.moving_average_samples <= 100000,
        "moving_average_samples", o.moving_average_samples, "1 .. 100000");
  check(o.filter_time_constant_s >= 0.0 && o.filter_time_constant_s <= kMaxSize,
        "filter_time_constant_s", o.filter_time_constant_s, "in [0, 1e9]");
  check(std::isfinite(o.butterworth_cutoff_hz) && o.butterworth_cutoff_hz >= 0.0 &&
            o.butterworth_cutoff_hz < 0.5 * sample_rate_hz,
        "butterworth_cutoff_hz", o.butterworth_cutoff_hz,
        ">= 0 (0: none) and below half the sample rate");
  check(std::isfinite(o.spike_rate_per_hour) && o.spike_rate_per_hour >= 0.0, "spike_rate_per_hour",
        o.spike_rate_per_hour, "a finite number >= 0");
  check(o.spike_size_deg_h >= 0.0 && o.spike_size_deg_h <= kMaxSize, "spike_size_deg_h",
        o.spike_size_deg_h, "in [0, 1e9]");
  check(o.lsb_deg_h >= 0.0 && o.lsb_deg_h <= kMaxSize, "lsb_deg_h", o.lsb_deg_h, "in [0, 1e9]");
  check(o.time_jitter_s >= 0.0 && o.time_jitter_s < 0.4 / sample_rate_hz, "time_jitter_s",
        o.time_jitter_s,
        fmt::format("from 0 to below 0.4 sample steps ({:.6g} s)", 0.4 / sample_rate_hz));
  for (const Dropout& d : o.dropouts) {
    check(std::isfinite(d.start_s) && d.start_s >= 0.0, "dropouts[].start_s", d.start_s,
          "a finite time >= 0");
    check(std::isfinite(d.duration_s) && d.duration_s > 0.0, "dropouts[].duration_s", d.duration_s,
          "a finite duration > 0");
  }
}

namespace {

// The lost samples [first, end) of each dropout, sorted and merged, within
// a record of `samples` samples.
std::vector<std::pair<std::int64_t, std::int64_t>> lost_ranges(const SensorOutput& o, double fs,
                                                               std::int64_t samples) {
  std::vector<std::pair<std::int64_t, std::int64_t>> ranges;
  for (const Dropout& d : o.dropouts) {
    // sample k is lost when start <= k / fs < start + duration
    const auto first = static_cast<std::int64_t>(std::ceil(d.start_s * fs));
    const auto end = static_cast<std::int64_t>(std::ceil((d.start_s + d.duration_s) * fs));
    if (std::min(end, samples) > first) ranges.emplace_back(first, std::min(end, samples));
  }
  std::sort(ranges.begin(), ranges.end());
  std::vector<std::pair<std::int64_t, std::int64_t>> merged;
  for (const auto& r : ranges) {
    if (!merged.empty() && r.first <= merged.back().second) {
      merged.back().second = std::max(merged.back().second, r.second);
    } else {
      merged.push_back(r);
    }
  }
  return merged;
}

}  // namespace

std::vector<Gap> dropout_gaps(const SensorOutput& output, double sample_rate_hz,
                              std::int64_t samples) {
  std::vector<Gap> gaps;
  std::int64_t lost_before = 0;
  for (const auto& [first, end] : lost_ranges(output, sample_rate_hz, samples)) {
    if (first > 0 && end < samples) gaps.push_back({first - lost_before, end - first});
    lost_before += end - first;
  }
  return gaps;
}

std::vector<Gap> remove_dropouts(Recording& rec, const SensorOutput& output) {
  const auto samples = static_cast<std::int64_t>(rec.rate_deg_h.size());
  const auto ranges = lost_ranges(output, rec.sample_rate_hz, samples);
  if (ranges.empty()) return {};
  std::vector<bool> lost(static_cast<std::size_t>(samples), false);
  for (const auto& [first, end] : ranges) {
    std::fill(lost.begin() + first, lost.begin() + end, true);
  }
  auto keep = [&](std::vector<double>& column) {
    if (column.size() != lost.size()) return;
    std::size_t out = 0;
    for (std::size_t k = 0; k < column.size(); ++k) {
      if (!lost[k]) column[out++] = column[k];
    }
    column.resize(out);
  };
  keep(rec.time_s);
  keep(rec.rate_deg_h);
  keep(rec.temperature_c);
  if (rec.rate_deg_h.empty()) {
    throw UsageError("SensorOutput::dropouts lose every sample of the record");
  }
  return dropout_gaps(output, rec.sample_rate_hz, samples);
}

void jitter_times(std::span<double> time_s, std::int64_t first_index, const SensorOutput& output,
                  double sample_rate_hz, std::uint64_t seed, std::uint64_t stream) {
  validate(output, sample_rate_hz);
  if (output.time_jitter_s <= 0.0) return;
  const std::uint64_t key = detail::process_key(seed, stream, kTimeJitter);
  const double scale_s = output.time_jitter_s;
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    const auto index = static_cast<std::uint64_t>(first_index + static_cast<std::int64_t>(i));
    time_s[i] += (2.0 * detail::uniform_of(detail::word_at(key, index)) - 1.0) * scale_s;
  }
}

void mark_dropouts_nan(std::span<double> values, std::int64_t first_index, std::int64_t samples,
                       const SensorOutput& output, double sample_rate_hz) {
  const auto end_index = first_index + static_cast<std::int64_t>(values.size());
  for (const auto& [first, end] : lost_ranges(output, sample_rate_hz, samples)) {
    const std::int64_t from = std::max(first, first_index), to = std::min(end, end_index);
    for (std::int64_t k = from; k < to; ++k) {
      values[static_cast<std::size_t>(k - first_index)] = std::numeric_limits<double>::quiet_NaN();
    }
  }
}

double output_filter_gain(const SensorOutput& output, double frequency_hz, double sample_rate_hz) {
  const double w = 2.0 * std::numbers::pi * frequency_hz / sample_rate_hz;
  double gain = 1.0;
  const int k = output.moving_average_samples;
  if (k > 1 && std::sin(0.5 * w) != 0.0) {
    gain *= std::fabs(std::sin(0.5 * w * k) / (k * std::sin(0.5 * w)));
  }
  if (output.filter_time_constant_s > 0.0) {
    const double rho = std::exp(-1.0 / (sample_rate_hz * output.filter_time_constant_s));
    const double re = 1.0 - rho * std::cos(w), im = rho * std::sin(w);
    gain *= (1.0 - rho) / std::sqrt(re * re + im * im);
  }
  if (output.butterworth_cutoff_hz > 0.0) {
    const std::array<double, 5> c =
        butterworth_coefficients(output.butterworth_cutoff_hz, 1.0 / sample_rate_hz);
    const std::complex<double> z1 = std::polar(1.0, -w), z2 = z1 * z1;
    gain *= std::abs((c[0] + c[1] * z1 + c[2] * z2) / (1.0 + c[3] * z1 + c[4] * z2));
  }
  return gain;
}

std::vector<double> spike_times_s(const SensorOutput& output, double sample_rate_hz,
                                  std::uint64_t seed, std::uint64_t stream, std::int64_t samples) {
  std::vector<double> times;
  const double p = spike_probability(output, sample_rate_hz);
  const std::uint64_t key = detail::process_key(seed, stream, kSpike);
  const auto lost = lost_ranges(output, sample_rate_hz, samples);  // sorted, disjoint
  auto next_lost = lost.begin();
  for (std::int64_t k = 0; p > 0.0 && k < samples; ++k) {
    while (next_lost != lost.end() && next_lost->second <= k) ++next_lost;
    const bool dropped = next_lost != lost.end() && next_lost->first <= k;
    if (spike_at(key, k, p) && !dropped) times.push_back(static_cast<double>(k) / sample_rate_hz);
  }
  return times;
}

OutputChain::OutputChain(const SensorOutput& output, double sample_rate_hz, std::uint64_t seed,
                         std::uint64_t stream)
    : output_(output),
      fs_(sample_rate_hz),
      key_spike_(detail::process_key(seed, stream, kSpike)),
      key_sign_(detail::process_key(seed, stream, kSpikeSign)) {
  validate(output_, sample_rate_hz);
  if (output_.filter_time_constant_s > 0.0) {
    rho_ = std::exp(-1.0 / (sample_rate_hz * output_.filter_time_constant_s));
  }
  if (output_.butterworth_cutoff_hz > 0.0) {
    biquad_ = butterworth_coefficients(output_.butterworth_cutoff_hz, 1.0 / sample_rate_hz);
  }
  window_.assign(static_cast<std::size_t>(output_.moving_average_samples - 1), 0.0);
}

void OutputChain::apply(std::int64_t first, double* rate, std::size_t count) {
  const double p_spike = spike_probability(output_, fs_);
  for (std::size_t k = 0; k < count; ++k) {
    const std::int64_t index = first + static_cast<std::int64_t>(k);
    const double t = static_cast<double>(index) / fs_;
    double x = rate[k];
    // 1. Disturbances.
    for (const Sinusoid& s : output_.sinusoids) {
      x += s.amplitude_deg_h * std::sin(2.0 * std::numbers::pi * s.frequency_hz * t + s.phase_rad);
    }
    for (const SquareWave& s : output_.square_waves) {
      const double sine = std::sin(2.0 * std::numbers::pi * s.frequency_hz * t + s.phase_rad);
      x += sine >= 0.0 ? s.amplitude_deg_h : -s.amplitude_deg_h;
    }
    for (const BiasStep& s : output_.steps) {
      if (t >= s.time_s) x += s.size_deg_h;
    }
    // 2. Bandwidth: the moving average (the first samples average what
    // there is so far), then the first-order low-pass (started at its input).
    if (!window_.empty()) {
      const std::size_t have =
          std::min<std::size_t>(window_.size(), static_cast<std::size_t>(index));
      const double sum = window_sum_ + x;
      const double mean = sum / static_cast<double>(have + 1);
      window_sum_ += x - (have == window_.size() ? window_[next_] : 0.0);
      window_[next_] = x;
      next_ = (next_ + 1) % window_.size();
      x = mean;
    }
    if (rho_ > 0.0) {
      filtered_ = started_ ? rho_ * filtered_ + (1.0 - rho_) * x : x;
      started_ = true;
      x = filtered_;
    }
    if (biquad_[0] > 0.0) {
      const auto& [b0, b1, b2, a1, a2] = biquad_;
      if (!biquad_started_) {  // the steady state of a constant input x
        z1_ = x * (1.0 - b0);
        z2_ = x * (b2 - a2);
        biquad_started_ = true;
      }
      const double y = b0 * x + z1_;
      z1_ = b1 * x - a1 * y + z2_;
      z2_ = b2 * x - a2 * y;
      x = y;
    }
    // 3. Spikes.
    if (spike_at(key_spike_, index, p_spike)) {
      const bool up =
          detail::uniform_of(detail::word_at(key_sign_, static_cast<std::uint64_t>(index))) < 0.5;
      x += up ? output_.spike_size_deg_h : -output_.spike_size_deg_h;
      spikes_.push_back(index);
    }
    // 4. The output word.
    if (output_.lsb_deg_h > 0.0) x = std::round(x / output_.lsb_deg_h) * output_.lsb_deg_h;
    rate[k] = x;
  }
}

}  // namespace foglab::sim
