// foglab — read_series(): option checks, format dispatch, and what every
// format shares (finite samples, unit conversion, time-vector checks).
#include "foglab/io/reader.h"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/text.h"
#include "foglab/io/channels.h"
#include "foglab/io/rosbag.h"
#include "readers_internal.h"
#include "stamp_grid.h"

namespace foglab::io {
namespace internal {

bool has_extension(const std::string& path, std::string_view extension) {
  const std::string lower = ascii_lower(path);
  return lower.size() > extension.size() &&
         lower.compare(lower.size() - extension.size(), extension.size(), extension) == 0;
}

std::string quoted_path(const std::string& path) {
  return path == "-" ? std::string("standard input") : "'" + path + "'";
}

void throw_data_error(const std::string& path, std::string_view what) {
  throw DataError(fmt::format("{}: {}", quoted_path(path), what));
}

const char* const kIgnoreTimeHint =
    "; to analyse the samples as evenly spaced anyway, give the sample rate [Hz] in "
    "ReadOptions::sample_rate_hz (the time is then ignored)";

namespace {

// stat() + fopen() so that the message carries the system's own reason.
struct stat stat_readable(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    throw UsageError(fmt::format("cannot open '{}': {}", path, std::strerror(errno)));
  }
  if (S_ISDIR(info.st_mode)) {
    throw UsageError(fmt::format("cannot open '{}': {}", path, std::strerror(EISDIR)));
  }
  // A FIFO (or a device) is opened once, by the reader: an open and close
  // here would take the writer's data or leave it blocked.
  if (!S_ISREG(info.st_mode)) {
    if (::access(path.c_str(), R_OK) != 0) {
      throw UsageError(fmt::format("cannot open '{}': {}", path, std::strerror(errno)));
    }
    return info;
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    throw UsageError(fmt::format("cannot open '{}': {}", path, std::strerror(errno)));
  }
  std::fclose(file);
  return info;
}

}  // namespace

}  // namespace internal

bool is_stream(const std::string& path) {
  struct stat info {};
  return path == "-" ||
         (::stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode) && !S_ISDIR(info.st_mode));
}

namespace internal {

void require_readable(const std::string& path) {
  if (path != "-") stat_readable(path);
}

std::optional<std::uint64_t> regular_file_size(const std::string& path) {
  if (path == "-") return std::nullopt;
  const struct stat info = stat_readable(path);
  if (!S_ISREG(info.st_mode)) return std::nullopt;
  return static_cast<std::uint64_t>(info.st_size);
}

std::string join_names(const std::vector<std::string>& names) { return list_names(names); }

std::string format_value(double value) { return fmt::format("{:.12g}", value); }

TimeAxisCheck::TimeAxisCheck(const std::string& path, std::string name, double resolution_s)
    : path_(path), name_(std::move(name)), resolution_s_(resolution_s) {
  head_s_.reserve(kHeadSteps + 1);
  head_lines_.reserve(kHeadSteps + 1);
}

std::string TimeAxisCheck::where(std::size_t index, std::size_t line) const {
  return line == 0 ? fmt::format("sample {} of '{}'", index + 1, name_)
                   : fmt::format("sample {} of '{}' (line {})", index + 1, name_, line);
}

void TimeAxisCheck::add(double time_s, std::size_t line, double resolution_s) {
  const std::size_t index = count_++;
  resolution_s_ = std::max(resolution_s_, resolution_s);
  if (!std::isfinite(time_s)) {
    throw_data_error(path_, fmt::format("time at {} is {}{}", where(index, line),
                                        format_value(time_s), kIgnoreTimeHint));
  }
  bool increasing = true;
  if (index == 0) {
    first_s_ = time_s;
  } else if (!(time_s > previous_s_)) {
    increasing = false;
    // counted once, when the reference is known (the first 64 steps are replayed)
    if (settled_ && faults_++ == 0) {
      first_fault_ = fmt::format(
          "time is not increasing at {}: {} s follows {} s (a repeated or "
          "decreasing time)",
          where(index, line), format_value(time_s), format_value(previous_s_));
    }
  }
  if (settled_) {
    // kept for a jittered axis while they fit in int64 nanoseconds (292 years)
    const double offset_ns = (time_s - first_s_) * 1e9;
    if (times_fit_ && std::fabs(offset_ns) < 9e18) {
      times_ns_.push_back(std::llround(offset_ns));
    } else {
      times_fit_ = false;
      times_ns_.clear();
    }
  }
  if (settled_ && index > 0 && increasing) {
    const double step = time_s - previous_s_;
    const double magnitude = std::max(std::fabs(first_s_), std::fabs(time_s));
    const double rounding_s = resolution_s_ < 0.5 * reference_s_ ? resolution_s_ : 0.0;
    const double tolerance_s =
        0.01 * reference_s_ + rounding_s + 8.0 * std::numeric_limits<double>::epsilon() * magnitude;
    if (step >= 1.5 * reference_s_) {
      const double steps = step / reference_s_;
      if (!(steps < 1e15)) {
        throw_data_error(
            path_, fmt::format("time jumps by {} s at {} ({} s -> {} s), {} sample "
                               "steps of {} s: not a gap in one record{}",
                               format_value(step), where(index, line), format_value(previous_s_),
                               format_value(time_s), format_value(steps),
                               format_value(reference_s_), kIgnoreTimeHint));
      }
      gaps_.push_back({static_cast<std::int64_t>(index), std::llround(steps) - 1});
    } else if (std::fabs(step - reference_s_) > tolerance_s) {
      ++irregular_steps_;
      if (faults_++ == 0) {
        first_fault_ = fmt::format(
            "time is not uniformly sampled at {}: step {} s ({} s -> {} s), expected {} s (an "
            "irregular step; a gap would be at least 1.5 steps)",
            where(index, line), format_value(step), format_value(previous_s_), format_value(time_s),
            format_value(reference_s_));
      }
    }
  } else if (!settled_) {
    head_s_.push_back(time_s);
    head_lines_.push_back(line);
  }
  previous_s_ = time_s;
  if (!settled_ && head_s_.size() == kHeadSteps + 1) settle_reference();
}

void TimeAxisCheck::settle_reference() {
  std::vector<double> steps;
  for (std::size_t i = 1; i < head_s_.size(); ++i) steps.push_back(head_s_[i] - head_s_[i - 1]);
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  reference_s_ = *middle;
  settled_ = true;
  // replay the buffered times through the step check
  const std::vector<double> head = std::move(head_s_);
  const std::vector<std::size_t> lines = std::move(head_lines_);
  head_s_.clear();
  head_lines_.clear();
  const std::size_t count = count_;
  count_ = 0;
  for (std::size_t i = 0; i < head.size(); ++i) add(head[i], lines[i]);
  count_ = count;
}

TimeAxis TimeAxisCheck::result() {
  if (count_ < 2) {
    throw_data_error(path_,
                     fmt::format("time column '{}' has {} sample(s); at least 2 are "
                                 "needed for a sample rate (or give ReadOptions::sample_rate_hz)",
                                 name_, count_));
  }
  if (!settled_) settle_reference();
  if (faults_ > 0) return jittered_axis();
  times_ns_ = {};
  TimeAxis axis;
  axis.rate_hz =
      static_cast<double>(static_cast<std::int64_t>(count_) - 1 + missing_samples(gaps_)) /
      (previous_s_ - first_s_);
  check_file_sample_rate(path_, axis.rate_hz, fmt::format("time column {}", name_));
  axis.gaps = gaps_;
  axis.start_s = first_s_;
  return axis;
}

// Irregular steps and times that do not increase: a few are each a fault in the times (the
// first is named); many are a logger's jitter when the times scatter about a uniform grid
// (stamp_grid.h) and few rows fall on the slot of the row before them.
TimeAxis TimeAxisCheck::jittered_axis() {
  constexpr std::size_t kFewestFaults = 16;
  constexpr double kLeastFaultFraction = 0.01;
  constexpr double kMostDroppedFraction = 0.01;
  const std::size_t steps = count_ - 1;
  const std::vector<std::int64_t> times_ns = std::move(times_ns_);
  times_ns_ = {};
  auto refuse = [&](const std::string& why) {
    throw_data_error(path_, fmt::format("{}{}{}{}", first_fault_,
                                        faults_ > 1 ? fmt::format(" and {} more irregular or "
                                                                  "decreasing step(s) of {}",
                                                                  faults_ - 1, steps)
                                                    : std::string(),
                                        why, kIgnoreTimeHint));
  };
  const bool many =
      faults_ >= kFewestFaults &&
      static_cast<double>(faults_) >= kLeastFaultFraction * static_cast<double>(steps);
  if (!many || !times_fit_) refuse("");
  const double median_s = median_step_s(times_ns);
  const StampGrid grid = fit_stamp_grid(times_ns, median_s);
  if (!(grid.step_s > 0.0) || grid.scatter_rms_steps > kMostScatterSteps) {
    refuse(
        fmt::format(", and the times do not scatter about a uniform grid either (rms {:.2f} "
                    "of a step about the grid that fits them best; up to {} is read as a "
                    "logger's jitter)",
                    grid.scatter_rms_steps, kMostScatterSteps));
  }
  if (static_cast<double>(grid.dropped.size()) >
      kMostDroppedFraction * static_cast<double>(count_)) {
    refuse(
        fmt::format(", and on the uniform grid they scatter about, {} of the {} rows fall on "
                    "the slot of the row before them or earlier (up to 1 % is read as a "
                    "logger's repeated rows)",
                    grid.dropped.size(), count_));
  }
  TimeAxis axis;
  axis.rate_hz = 1.0 / grid.step_s;
  check_file_sample_rate(path_, axis.rate_hz, fmt::format("time column {}", name_));
  axis.gaps = grid.gaps;
  axis.start_s = first_s_;
  axis.dropped = grid.dropped;
  axis.jitter = TimeJitter{
      irregular_steps_, steps, median_s, grid.jitter_rms_s, grid.jitter_max_s, grid.dropped.size()};
  return axis;
}

void apply_time_axis(Series& series, TimeAxis axis, const std::string& time_name,
                     bool rate_from_axis) {
  if (axis.dropped.size() > 0 && axis.dropped.back() >= series.values.size()) {
    throw std::logic_error("apply_time_axis: the time axis has more rows than the values");
  }
  const std::size_t rows = series.values.size();
  drop_entries(series.values, axis.dropped);
  if (rate_from_axis) {
    series.sample_rate_hz = axis.rate_hz;
    series.sample_rate_source = SampleRateSource::time_channel;
    series.sample_rate_channel = time_name;
  }
  series.gaps = std::move(axis.gaps);
  series.start_time_s = axis.start_s;
  series.time_jitter = axis.jitter;
  const std::int64_t missing = missing_samples(series.gaps);
  const auto present = static_cast<std::int64_t>(series.values.size());
  if (missing > present && static_cast<std::int64_t>(series.gaps.size()) > present / 16) {
    series.notes.emplace_back(
        Text::io_note_time_bursts, quoted_path(series.path), time_name, series.gaps.size(), present,
        missing, format_value(rate_from_axis ? 1.0 / axis.rate_hz : 1.0 / series.sample_rate_hz));
  }
  if (axis.jitter) {
    const TimeJitter& j = *axis.jitter;
    series.notes.emplace_back(Text::io_note_time_jitter, quoted_path(series.path), time_name,
                              j.irregular_steps, j.steps, format_value(j.median_step_s),
                              fmt::format("{:.3g}", j.rms_s), fmt::format("{:.3g}", j.max_s),
                              format_value(axis.rate_hz));
    if (j.rows_dropped > 0) {
      series.notes.emplace_back(Text::io_note_time_rows_dropped, j.rows_dropped, rows, time_name);
    }
  }
}

TimeAxis time_axis_of(const std::string& path, std::string_view name,
                      std::span<const double> time_s, double resolution_s) {
  TimeAxisCheck check(path, std::string(name), resolution_s);
  for (const double t : time_s) check.add(t);
  return check.result();
}

void check_file_sample_rate(const std::string& path, double rate_hz, std::string_view source) {
  if (!(rate_hz >= kMinSampleRateHz && rate_hz <= kMaxSampleRateHz)) {
    throw_data_error(
        path, fmt::format("sample rate from {} is {} Hz; expected a positive, "
                          "finite rate from {:g} to {:g} Hz",
                          source, format_value(rate_hz), kMinSampleRateHz, kMaxSampleRateHz));
  }
}

}  // namespace internal

namespace {

using internal::has_extension;
using internal::quoted_path;
using internal::throw_data_error;

// The format a file is read as: the option, else by extension.
InputFormat resolve_format(const std::string& path, InputFormat format) {
  if (format != InputFormat::automatic) return format;
  if (path == "-") return InputFormat::text;
  if (has_extension(path, ".mat")) return InputFormat::mat;
  if (has_extension(path, ".f32")) return InputFormat::f32;
  if (has_extension(path, ".f64")) return InputFormat::f64;
  return InputFormat::text;
}

void check_format_source(const std::string& path, InputFormat format) {
  if (path == "-" && format == InputFormat::mat) {
    throw UsageError("MAT files cannot be read from standard input: give a file name");
  }
  internal::require_readable(path);
  if (format == InputFormat::mat && is_stream(path)) {
    throw UsageError(
        fmt::format("'{}' is not a regular file (a FIFO or a device): a MAT file "
                    "is read by seeking in it; save it to a file",
                    path));
  }
}

std::string describe_non_finite(double value) {
  if (std::isnan(value)) return "NaN";
  return value > 0 ? "+Inf" : "-Inf";
}

// A channel whose largest sample (in deg/h, m/s^2 or degC) is below this in
// magnitude but not 0 is refused: the statistics square the samples (the
// kurtosis takes fourth powers), and below about 1e-154 a square underflows
// to 0, so the Allan deviation of such a record came out 0 or denormal and
// was called noiseless. No sensor's output is that small in these units; a
// wrong unit or scale is.
constexpr double kMinLargestMagnitude = 1e-30;

// Checks every sample and converts it to deg/h (m/s^2 for an acceleration
// unit). In parallel, chunk by chunk: a chunk whose every converted sample is
// finite and within the limit (which may be infinite) is converted
// at once; a chunk that is not is walked sample by sample for the message.
void finish_values(Series& series, RateUnit unit, double max_magnitude, bool nan_is_missing) {
  if (series.values.empty()) {
    throw_data_error(series.path, fmt::format("channel '{}' has no samples", series.channel));
  }
  const double factor = to_internal_unit(unit);
  const SampleUnit target = internal_unit(sensor_of(unit));
  const std::size_t n = series.values.size();
  const std::size_t chunks = (n + kChunkSamples - 1) / kChunkSamples;
  std::vector<char> converted(chunks, 0);
  std::vector<double> largest(chunks, 0.0);
  double* values = series.values.data();
#pragma omp parallel for schedule(static) if (chunks > 1)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t begin = c * kChunkSamples, end = std::min(n, begin + kChunkSamples);
    bool within = true;
    double chunk_largest = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      const double in_unit = values[i] * factor;  // in - in: 0 if finite, else NaN
      within &= in_unit - in_unit == 0.0 && std::fabs(in_unit) <= max_magnitude;
      chunk_largest = std::max(chunk_largest, std::fabs(in_unit));
    }
    largest[c] = chunk_largest;
    if (!within) continue;
    if (factor != 1.0) {  // deg/h in: checked, nothing to write
      for (std::size_t i = begin; i < end; ++i) values[i] *= factor;
    }
    converted[c] = 1;
  }
  for (std::size_t c = 0; c < chunks; ++c) {
    if (converted[c]) continue;
    for (std::size_t i = c * kChunkSamples; i < std::min(n, (c + 1) * kChunkSamples); ++i) {
      const double value = values[i];
      if (nan_is_missing && std::isnan(value)) continue;  // a missing sample, left as NaN
      if (!std::isfinite(value)) {
        throw_data_error(series.path, fmt::format("sample {} of '{}' is {}", i + 1, series.channel,
                                                  describe_non_finite(value)));
      }
      const double in_unit = value * factor;
      if (!std::isfinite(in_unit)) {
        throw_data_error(series.path,
                         fmt::format("sample {} of '{}' ({} {}) overflows when converted to {}",
                                     i + 1, series.channel, internal::format_value(value),
                                     to_string(unit), to_string(target)));
      }
      if (std::fabs(in_unit) > max_magnitude) {
        throw_data_error(
            series.path,
            fmt::format("sample {} of '{}' is {}{}: too large (more than {:g} in magnitude, far "
                        "beyond any sensor's output or temperature, and the statistics would "
                        "overflow); check the channel, its unit and the file",
                        i + 1, series.channel, internal::format_value(value),
                        unit == target ? std::string() : fmt::format(" {}", to_string(unit)),
                        max_magnitude));
      }
      values[i] = in_unit;
    }
  }
  const double record_largest = *std::max_element(largest.begin(), largest.end());
  if (record_largest > 0.0 && record_largest < kMinLargestMagnitude) {
    throw_data_error(
        series.path,
        fmt::format("channel '{}' has no sample larger than {} {} in magnitude: too small for "
                    "the statistics, whose squares would underflow (no sensor's output is that "
                    "small); check the channel, its unit and the file",
                    series.channel, internal::format_value(record_largest), to_string(target)));
  }
}

}  // namespace

std::string_view to_string(InputFormat format) {
  switch (format) {
    case InputFormat::automatic:
      return "auto";
    case InputFormat::mat:
      return "mat";
    case InputFormat::text:
      return "text";
    case InputFormat::f32:
      return "f32";
    case InputFormat::f64:
      return "f64";
  }
  return "?";
}

std::string_view to_string(SampleRateSource source) {
  switch (source) {
    case SampleRateSource::option:
      return "option";
    case SampleRateSource::variable_f:
      return "variable_f";
    case SampleRateSource::time_channel:
      return "time_channel";
    case SampleRateSource::builtin:
      return "builtin";
  }
  return "?";
}

InputFormat input_format_from_string(std::string_view text) {
  const std::string t = ascii_lower(text);
  if (t == "auto" || t == "automatic") return InputFormat::automatic;
  if (t == "mat") return InputFormat::mat;
  if (t == "text" || t == "csv" || t == "tsv" || t == "txt") return InputFormat::text;
  if (t == "f32" || t == "float32") return InputFormat::f32;
  if (t == "f64" || t == "float64") return InputFormat::f64;
  throw UsageError(
      fmt::format("unknown input format '{}': expected auto, mat, text (csv, tsv), "
                  "f32 (float32) or f64 (float64)",
                  text));
}

Series read_series(const std::string& path, const ReadOptions& options) {
  if (!(options.max_magnitude > 0.0)) {
    throw UsageError(fmt::format("invalid largest sample magnitude {} for {}: expected > 0",
                                 internal::format_value(options.max_magnitude), quoted_path(path)));
  }
  if (options.sample_rate_hz && !(*options.sample_rate_hz >= kMinSampleRateHz &&
                                  *options.sample_rate_hz <= kMaxSampleRateHz)) {
    throw UsageError(fmt::format(
        "invalid sample rate ReadOptions::sample_rate_hz {} for {}: expected a positive, "
        "finite rate from {:g} to {:g} Hz",
        internal::format_value(*options.sample_rate_hz), quoted_path(path), kMinSampleRateHz,
        kMaxSampleRateHz));
  }
  const InputFormat format = resolve_format(path, options.format);
  if (options.format == InputFormat::automatic && has_bag_extension(path)) {
    throw UsageError(
        fmt::format("{} is a ROS bag (.bag): `foglab analyze` reads its sensor_msgs/Imu channels; "
                    "this reads MAT, text and raw files",
                    quoted_path(path)));
  }
  check_format_source(path, format);

  Series series;
  switch (format) {
    case InputFormat::mat:
      series = internal::read_mat(path, options);
      break;
    case InputFormat::f32:
    case InputFormat::f64:
      series = internal::read_raw(path, options, format);
      break;
    case InputFormat::automatic:
    case InputFormat::text:
      series = internal::read_text(path, options);
      break;
  }
  series.path = path;
  if (options.sample_rate_hz) {
    series.sample_rate_hz = *options.sample_rate_hz;
    series.sample_rate_source = SampleRateSource::option;
  }
  finish_values(series, options.unit, options.max_magnitude, options.nan_is_missing);
  return series;
}

MissingSamples drop_missing_samples(Series& series, std::vector<double>* paired) {
  std::vector<double>& values = series.values;
  const std::size_t n = values.size();
  if (paired != nullptr && paired->size() != n) {
    throw std::invalid_argument("drop_missing_samples: the paired channel's length differs");
  }
  auto missing = [&](std::size_t i) {
    return std::isnan(values[i]) || (paired != nullptr && std::isnan((*paired)[i]));
  };
  MissingSamples dropped;
  std::size_t first_missing = 0;
  while (first_missing < n && !missing(first_missing)) ++first_missing;
  if (first_missing == n) return dropped;

  // Row i lies at i + (samples the time axis skips before it) on the
  // record's grid; a kept row more than one step after the one before is a
  // gap, whether the time axis or left-out rows made it.
  std::vector<Gap> gaps;
  std::size_t g = 0;
  std::int64_t skipped = 0;
  std::int64_t first_kept = -1, previous = -1;
  std::size_t kept = 0;
  bool in_run = false;
  for (std::size_t i = 0; i < n; ++i) {
    while (g < series.gaps.size() && series.gaps[g].before_sample == static_cast<std::int64_t>(i)) {
      skipped += series.gaps[g++].missing_samples;
    }
    if (missing(i)) {
      ++dropped.samples;
      dropped.stretches += in_run ? 0 : 1;
      in_run = true;
      continue;
    }
    in_run = false;
    const std::int64_t at = static_cast<std::int64_t>(i) + skipped;
    if (first_kept < 0) {
      first_kept = at;
      dropped.at_start = dropped.samples;
    } else if (at - previous > 1) {
      gaps.push_back({static_cast<std::int64_t>(kept), at - previous - 1});
    }
    values[kept] = values[i];
    if (paired != nullptr) (*paired)[kept] = (*paired)[i];
    ++kept;
    previous = at;
  }
  if (kept == 0) {
    throw_data_error(series.path,
                     fmt::format("channel '{}'{} has no sample left: all {} are NaN (missing)",
                                 series.channel, paired != nullptr ? " with its pair" : "", n));
  }
  std::size_t last_kept = n - 1;
  while (missing(last_kept)) --last_kept;
  dropped.at_end = static_cast<std::int64_t>(n - 1 - last_kept);
  values.resize(kept);
  // the capacity stays: the Allan integration grows the record by one in place
  if (paired != nullptr) paired->resize(kept);
  series.gaps = std::move(gaps);
  series.start_time_s += static_cast<double>(first_kept) / series.sample_rate_hz;
  series.nan_left_out = dropped;
  return dropped;
}

std::vector<std::string> list_channels(const std::string& path, InputFormat format) {
  const InputFormat resolved = resolve_format(path, format);
  check_format_source(path, resolved);
  switch (resolved) {
    case InputFormat::mat:
      return internal::list_mat_channels(path);
    case InputFormat::f32:
    case InputFormat::f64:
      return {"1"};
    case InputFormat::automatic:
    case InputFormat::text:
      return internal::list_text_channels(path);
  }
  return {};
}

std::vector<std::string> list_variables(const std::string& path, InputFormat format) {
  const InputFormat resolved = resolve_format(path, format);
  if (resolved == InputFormat::mat) {
    check_format_source(path, resolved);
    return internal::list_mat_variables(path);
  }
  return list_channels(path, resolved);  // text columns and raw files: every name is a channel
}

}  // namespace foglab::io
