#include "cli_common.h"

#include <fmt/format.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <mutex>
#include <regex>
#include <unordered_set>

#include "foglab/core/error.h"
#include "foglab/io/channels.h"
#include "foglab/io/sample.h"

namespace foglab::cli {

void add_input_options(CLI::App& command, InputOptions& options, bool file_optional) {
  auto* file = command.add_option(
      "FILE", options.path,
      file_optional ? "record: .mat, text (.csv/.tsv/.txt), .f32/.f64 or - for stdin; "
                      "omitted: the built-in sample"
                    : "record: .mat, text (.csv/.tsv/.txt), .f32/.f64 or - for stdin");
  if (!file_optional) file->required();
  add_reading_options(command, options);
}

void add_reading_options(CLI::App& command, InputOptions& options) {
  command.add_option("--channel", options.channel,
                     "variable (MAT) or column name/1-based index (text); default: the only "
                     "data channel, else Y1");
  command.add_option("--fs", options.sample_rate_hz,
                     "sample rate [Hz]; default: the file's f variable or time column");
  command.add_option("--format", options.format, "auto, mat, text, f32 or f64")
      ->capture_default_str();
  command
      .add_option("--units", options.units,
                  "unit of the samples: deg/h, deg/s, rad/s (gyroscope) or m/s^2, g, mg "
                  "(accelerometer); analyze also takes a list by sensor or channel: "
                  "gyro=deg/s,accel=g or ax=mg,gx=rad/s")
      ->capture_default_str()
      ->each([&options](const std::string&) { options.units_given = true; });
  command.add_option("--time", options.time_channel,
                     "time variable/column used for the sample rate (default t/time/time_s)");
  command.add_flag("--decimal-comma", options.decimal_comma,
                   "text: numbers written with a decimal comma (0,25); fields separated by "
                   "tabs, semicolons or blanks");
  command
      .add_option("--max-samples", options.max_samples,
                  "the most samples read from the record (default: what 1/16 of the free "
                  "memory holds); an endless stream stops there with an error")
      ->check(CLI::PositiveNumber);
}

std::size_t default_max_samples() {
  std::uint64_t bytes = 0;
  if (std::FILE* meminfo = std::fopen("/proc/meminfo", "r")) {
    char line[256];
    while (std::fgets(line, sizeof line, meminfo) != nullptr) {
      unsigned long long kib = 0;
      if (std::sscanf(line, "MemAvailable: %llu kB", &kib) == 1) bytes = kib * 1024;
    }
    std::fclose(meminfo);
  }
  if (bytes == 0) {
    bytes = static_cast<std::uint64_t>(::sysconf(_SC_AVPHYS_PAGES)) *
            static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  }
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    bytes = std::min<std::uint64_t>(bytes, limit.rlim_cur);
  }
  return static_cast<std::size_t>(std::max<std::uint64_t>(bytes / 16 / sizeof(double), 1000000));
}

std::string json_text(const nlohmann::json& document) {
  return document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

io::ReadOptions read_options(const InputOptions& options) {
  io::ReadOptions read;
  read.channel = options.channel;
  read.sample_rate_hz = options.sample_rate_hz;
  read.format = parse_format_option(options.format, options.path);
  read.unit = parse_units_option(options.units, options.path);
  read.time_channel = options.time_channel;
  read.max_magnitude = io::kMaxSampleMagnitude;  // 1e308 overflows the statistics
  read.decimal_comma = options.decimal_comma;
  read.max_samples = options.max_samples ? *options.max_samples : default_max_samples();
  return read;
}

stats::TauGrid parse_taus_option(const std::string& text, const std::string& path) {
  try {
    return stats::parse_tau_grid(text);
  } catch (const UsageError& e) {
    if (path.empty()) throw;
    throw UsageError(fmt::format("'{}': {}", path, e.what()));
  }
}

io::InputFormat parse_format_option(const std::string& text, const std::string& path) {
  try {
    return io::input_format_from_string(text);
  } catch (const UsageError& e) {
    throw UsageError(fmt::format("--format {} for '{}': {}", text, path, e.what()));
  }
}

RateUnit parse_units_option(const std::string& text, const std::string& path) {
  try {
    return rate_unit_from_string(text);
  } catch (const UsageError& e) {
    throw UsageError(fmt::format("--units {} for '{}': {}", text, path, e.what()));
  }
}

UnitSpec parse_unit_spec(const std::string& text, const std::string& path) {
  UnitSpec spec;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    start = comma + 1;
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos) {
      if (spec.all) {
        throw UsageError(fmt::format(
            "--units {} for '{}': one unit for every channel, or NAME=UNIT items (gyro=deg/s, "
            "accel=g, ax=mg), not two bare units",
            text, path));
      }
      spec.all = parse_units_option(item, path);
      continue;
    }
    const std::string name = item.substr(0, equals);
    const SampleUnit unit = parse_units_option(item.substr(equals + 1), path);
    const bool gyro = name == "gyro" || name == "gyroscope" || name == "gyroscopes";
    const bool accel = name == "accel" || name == "accelerometer" || name == "accelerometers";
    if (gyro || accel) {
      const Sensor sensor = gyro ? Sensor::gyroscope : Sensor::accelerometer;
      if (sensor_of(unit) != sensor) {
        throw UsageError(fmt::format(
            "--units {} for '{}': {} is a unit of {}, not of the {}'s {}", text, path,
            to_string(unit), sensor_of(unit) == Sensor::gyroscope ? "angular rate" : "acceleration",
            to_string(sensor), gyro ? "angular rate" : "acceleration"));
      }
      (gyro ? spec.gyroscope : spec.accelerometer) = unit;
    } else if (name.empty()) {
      throw UsageError(fmt::format("--units {} for '{}': '{}' names no channel", text, path, item));
    } else {
      spec.channels.emplace_back(name, unit);
    }
  }
  return spec;
}

namespace {
/// "a gyroscope's", "an accelerometer's".
std::string sensor_owner(Sensor sensor) {
  return sensor == Sensor::gyroscope ? "a gyroscope's" : "an accelerometer's";
}
}  // namespace

SampleUnit channel_unit(const UnitSpec& spec, const std::string& channel, const std::string& path,
                        std::vector<std::string>& notes) {
  const std::optional<Sensor> named = io::sensor_by_name(channel);
  for (const auto& [name, unit] : spec.channels) {
    if (name != channel) continue;
    if (named && *named != sensor_of(unit)) {
      throw UsageError(fmt::format(
          "mixed units: '{}' channel {} is named as {}, but --units gives it {}, a unit of {}",
          path, channel, sensor_owner(*named), to_string(unit),
          sensor_of(unit) == Sensor::gyroscope ? "angular rate" : "acceleration"));
    }
    return unit;
  }
  if (named == Sensor::gyroscope && spec.gyroscope) return *spec.gyroscope;
  if (named == Sensor::accelerometer && spec.accelerometer) return *spec.accelerometer;
  if (spec.all && (!named || *named == sensor_of(*spec.all))) return *spec.all;
  if (spec.all) {
    throw UsageError(fmt::format(
        "mixed units: '{}' channel {} is named as {}, but --units {} is a unit of {}; give "
        "each sensor its unit (--units gyro=deg/s,accel=g)",
        path, channel, sensor_owner(*named), to_string(*spec.all),
        sensor_of(*spec.all) == Sensor::gyroscope ? "angular rate" : "acceleration"));
  }
  if (named == Sensor::accelerometer) {
    notes.push_back(fmt::format(
        "'{}' channel {} is an accelerometer's (by its name) and --units gives it no unit: "
        "read in m/s^2 (give accel=g or accel=mg otherwise)",
        path, channel));
    return SampleUnit::m_per_s2;
  }
  return SampleUnit::deg_per_hour;
}

void leave_missing_samples(io::Series& series, std::vector<double>* paired) {
  const io::MissingSamples left = io::drop_missing_samples(series, paired);
  if (left.samples > 0) {
    std::string ends;
    if (left.at_start > 0) {
      ends += fmt::format("; the record starts {} sample(s) later", left.at_start);
    }
    if (left.at_end > 0) ends += fmt::format("; it ends {} sample(s) earlier", left.at_end);
    note(fmt::format(
        "'{}': {} NaN or empty sample(s) in {} stretch(es){} are missing samples, left out{}",
        series.path, left.samples, left.stretches,
        paired != nullptr ? " (of the rate or its temperature)" : "", ends));
  }
  if (!series.gaps.empty()) {
    const std::int64_t missing = missing_samples(series.gaps);
    note(
        fmt::format("'{}': the record has {} gap(s), {} sample(s) ({:.6g} s) missing; the "
                    "statistics use the contiguous stretches between them (nothing is "
                    "interpolated)",
                    series.path, series.gaps.size(), missing,
                    static_cast<double>(missing) / series.sample_rate_hz));
  }
}

io::Series load_input(const InputOptions& options, bool keep_nan_rows) {
  if (options.path.empty()) {
    io::Series sample = io::builtin_sample();
    note(fmt::format("no FILE given: using the built-in sample ({} samples at {} Hz, {} h)",
                     sample.values.size(), sample.sample_rate_hz,
                     io::BuiltinSample::kDurationS / 3600.0));
    return sample;
  }
  progress(fmt::format("reading '{}'", options.path));
  io::ReadOptions read = read_options(options);
  read.nan_is_missing = true;
  io::Series series = io::read_series(options.path, read);
  for (const Message& m : series.notes) note(m.text());
  if (!keep_nan_rows) leave_missing_samples(series, nullptr);
  if (options.channel.empty() && series.available_channels.size() > 1) {
    note(fmt::format("'{}' has channels {}; using '{}' (choose with --channel)", options.path,
                     io::list_names(series.available_channels), series.channel));
  }
  return series;
}

nlohmann::json number(double value) {
  if (!std::isfinite(value)) return nullptr;
  return value;
}

nlohmann::json numbers(const std::vector<double>& values) {
  nlohmann::json array = nlohmann::json::array();
  for (const double v : values) array.push_back(number(v));
  return array;
}

nlohmann::json noise_model_json(const NoiseModel& m) {
  nlohmann::json j = nlohmann::json::object();
  for (const NoiseParameter& p : kNoiseParameters) j[std::string(p.name)] = m.*p.value;
  return j;
}

nlohmann::json noise_units_json() {
  nlohmann::json j = nlohmann::json::object();
  for (const NoiseParameter& p : kNoiseParameters) j[std::string(p.name)] = p.unit;
  return j;
}

nlohmann::json model_json(const sim::ErrorModel& m) {
  nlohmann::json j = noise_model_json(m.noise);
  j["bias"] = m.bias;
  j["input_rate"] = m.input_rate;
  j["temp_coefs"] = m.temp_coefs;
  return j;
}

nlohmann::json model_units_json() {
  nlohmann::json j = {{"bias", "deg/h"},
                      {"input_rate", "deg/h"},
                      {"temp_coefs", "deg/h/degC^k, k = 1, 2, ... about temperature.reference_c"}};
  j.update(noise_units_json());
  return j;
}

std::string sample_rate_source_text(const io::Series& series) {
  switch (series.sample_rate_source) {
    case io::SampleRateSource::option:
      return "option --fs";
    case io::SampleRateSource::variable_f:
      return "variable f";
    case io::SampleRateSource::time_channel:
      return "time column " + series.sample_rate_channel;
    case io::SampleRateSource::builtin:
      return "built-in";
  }
  return "";
}

nlohmann::json gaps_json(const io::Series& series) {
  const double fs = series.sample_rate_hz;
  nlohmann::json list = nlohmann::json::array();
  const std::vector<GapSpan> spans = gap_spans_s(series.gaps, fs);
  for (std::size_t g = 0; g < spans.size(); ++g) {
    list.push_back({{"before_sample", series.gaps[g].before_sample},
                    {"missing_samples", series.gaps[g].missing_samples},
                    {"start_s", spans[g].start_s},
                    {"end_s", spans[g].end_s}});
  }
  const std::int64_t missing = missing_samples(series.gaps);
  return {{"count", series.gaps.size()},
          {"missing_samples", missing},
          {"missing_value_rows", series.nan_left_out.samples},
          {"missing_s", static_cast<double>(missing) / fs},
          {"first_sample_time_s", series.start_time_s},
          {"treatment", series.gaps.empty() ? "none"
                                            : "contiguous stretches: Allan terms and Welch "
                                              "segments spanning a gap are left out; nothing is "
                                              "interpolated"},
          {"list", list}};
}

nlohmann::json input_json(const io::Series& series) {
  nlohmann::json jitter = nullptr;
  if (series.time_jitter) {
    const io::TimeJitter& j = *series.time_jitter;
    jitter = {{"irregular_steps", j.irregular_steps},
              {"steps", j.steps},
              {"median_step_s", j.median_step_s},
              {"rms_s", j.rms_s},
              {"max_s", j.max_s},
              {"rows_dropped", j.rows_dropped}};
  }
  return {{"path", series.path},
          {"channel", series.channel},
          {"sample_rate_hz", series.sample_rate_hz},
          {"sample_rate_source", sample_rate_source_text(series)},
          {"samples", series.values.size()},
          {"gaps", gaps_json(series)},
          {"time_jitter", jitter}};
}

namespace {

// The library's API names in its messages and the flags that set them.
struct FlagOfField {
  const char* field;  // as the library's messages write it (a regex)
  const char* flag;   // the replacement
};
constexpr FlagOfField kFlagsOfFields[] = {
    {R"(BagReadOptions::sample_rate_hz)", "--fs"},
    {R"(ReadOptions::sample_rate_hz)", "--fs"},
    {R"(ReadOptions::channel)", "--channel"},
    {R"(ReadOptions::time_channel)", "--time"},
    {R"(ReadOptions::unit)", "--units"},
    {R"(ReadOptions::format)", "--format"},
    {R"(ReadOptions::decimal_comma)", "--decimal-comma"},
    {R"(ReadOptions::max_samples)", "--max-samples"},
    {R"(TauGrid::min_clusters)", "--min-clusters"},
    {R"(TauGrid::taus_s)", "--taus"},
    {R"re(parse_tau_grid\("([^"]*)"\))re", "--taus '$1'"},
    {R"(SensorOutput::sinusoids\[\]\.\w+)", "--sine"},
    {R"(SensorOutput::square_waves\[\]\.\w+)", "--square"},
    {R"(SensorOutput::steps\[\]\.\w+)", "--step"},
    {R"(SensorOutput::moving_average_samples)", "--moving-average"},
    {R"(SensorOutput::filter_time_constant_s)", "--filter-tc"},
    {R"(SensorOutput::butterworth_cutoff_hz)", "--butterworth"},
    {R"(SensorOutput::spike_(rate_per_hour|size_deg_h))", "--spikes"},
    {R"(SensorOutput::lsb_deg_h)", "--lsb"},
    {R"(SensorOutput::time_jitter_s)", "--stamp-jitter"},
};

}  // namespace

std::string in_cli_terms(std::string message) {
  static const std::vector<std::pair<std::regex, std::string>> rules = [] {
    std::vector<std::pair<std::regex, std::string>> r;
    for (const FlagOfField& f : kFlagsOfFields) r.emplace_back(std::regex(f.field), f.flag);
    return r;
  }();
  for (const auto& [field, flag] : rules) message = std::regex_replace(message, field, flag);
  return message;
}

sim::Lab2Options lab2_options(std::uint64_t seed, const std::optional<double>& hours) {
  sim::Lab2Options options;
  options.seed = seed;
  if (hours) {
    if (!(*hours > 0.0) || !std::isfinite(*hours)) {
      throw UsageError(fmt::format("--hours must be > 0, got {}", *hours));
    }
    options.duration_s = *hours * 3600.0;
  }
  return options;
}

namespace {
// One line at a time on stderr: the channels of an IMU are analysed in
// parallel, and each says what it found.
std::mutex stderr_lines;
}  // namespace

namespace {
thread_local std::vector<std::string>* collected_notes = nullptr;
}  // namespace

CollectNotes::CollectNotes(std::vector<std::string>& into) : previous_(collected_notes) {
  collected_notes = &into;
}

CollectNotes::~CollectNotes() { collected_notes = previous_; }

void note(const std::string& text) {
  if (collected_notes != nullptr) {
    collected_notes->push_back(in_cli_terms(text));
    return;
  }
  const std::string line = "foglab: note: " + in_cli_terms(text) + "\n";
  const std::lock_guard<std::mutex> lock(stderr_lines);
  // once: the channels of one file, read in parallel, each say what the file's time axis says
  static std::unordered_set<std::string> printed;
  if (!printed.insert(line).second) return;
  std::cerr << line;
}

void progress(const std::string& step) {
  static const bool terminal = isatty(STDERR_FILENO) != 0;
  if (!terminal || collected_notes != nullptr) return;
  const std::lock_guard<std::mutex> lock(stderr_lines);
  std::cerr << "foglab: " << step << " ...\n";
}

void add_title_options(CLI::App* cmd, TitleOptions& t) {
  cmd->add_option("--student", t.student,
                  "the report's title block: the student's name (the manual's title page)");
  cmd->add_option("--group", t.group, "the report's title block: the student's group");
  cmd->add_option("--date", t.date, "the report's title block: the date (default: today)");
}

report::TitleBlock title_block(const TitleOptions& t, int lab, std::optional<int> variant) {
  std::string date = t.date;
  if (date.empty()) {
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    localtime_r(&now, &local);
    char text[16];
    if (std::strftime(text, sizeof text, "%Y-%m-%d", &local) > 0) date = text;
  }
  return {lab, variant, t.student, t.group, date};
}

}  // namespace foglab::cli
