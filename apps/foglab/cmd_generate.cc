// foglab generate — one synthetic static-gyro run with known truth.
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>

#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/io/channels.h"
#include "foglab/io/rosbag.h"
#include "foglab/io/writer.h"
#include "foglab/report/imu.h"
#include "foglab/sim/fleet.h"
#include "foglab/sim/generator.h"
#include "foglab/sim/lab2_variants.h"
#include "foglab/sim/presets.h"

namespace foglab::cli {
namespace {

struct GenerateCommand {
  std::string preset;
  std::optional<double> N, B, K, R, Q, gm_sigma, gm_tc, bias, input_rate;
  std::string temp_coefs;
  std::optional<double> sample_rate_hz;
  std::optional<double> hours;
  std::uint64_t seed = 1;
  std::uint64_t stream = 0;
  std::string temperature = "const";
  std::optional<double> temp_lsb;  // [degC] the temperature sensor's step
  std::string out;
  std::string truth;
  // The sensor's output chain (sim/sensor_output.h).
  std::optional<double> filter_tc;
  std::optional<double> butterworth_hz;
  int moving_average = 1;
  std::vector<std::string> sines, squares, steps;
  std::string spikes;
  std::optional<double> lsb;
  std::vector<std::string> drops;
  std::string drop_mark;  // "time", "nan"; empty: time, nan for a raw file
  // A 6-axis IMU (--imu): the mems-imu model, the gyroscope options above
  // for its three gyroscopes, these for its accelerometers [m/s^2 units].
  bool imu = false;
  std::optional<double> accel_N, accel_B, accel_K;
  std::optional<double> stamp_jitter_s;
  // A fleet (--fleet, sim/fleet.h).
  std::optional<int> fleet;
  double fleet_spread = 0.1;
  bool fleet_spread_given = false;
  std::size_t fleet_outliers = 0;
  double outlier_factor = 5.0;
  bool outlier_factor_given = false;
};

// `text` split at `separator` into numbers, naming the option and what was
// expected; between min_count and max_count of them.
std::vector<double> numbers_of(const std::string& option, const std::string& text,
                               char separator, std::size_t min_count, std::size_t max_count,
                               const std::string& expected) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t at = text.find(separator, start);
    const std::string item =
        text.substr(start, at == std::string::npos ? std::string::npos : at - start);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v)) {
      throw UsageError(
          fmt::format("{} '{}': '{}' is not a number (expected {})", option, text, item, expected));
    }
    out.push_back(v);
    if (at == std::string::npos) break;
    start = at + 1;
  }
  if (out.size() < min_count || out.size() > max_count) {
    throw UsageError(fmt::format("{} '{}': expected {}", option, text, expected));
  }
  return out;
}

sim::SensorOutput sensor_output_of(const GenerateCommand& c) {
  sim::SensorOutput o;
  for (const std::string& text : c.sines) {
    const auto v = numbers_of("--sine", text, ':', 2, 3, "F:A or F:A:PHASE (Hz, deg/h peak, rad)");
    o.sinusoids.push_back({v[0], v[1], v.size() > 2 ? v[2] : 0.0});
  }
  for (const std::string& text : c.squares) {
    const auto v = numbers_of("--square", text, ':', 2, 3,
                              "F:A or F:A:PHASE (Hz, deg/h half peak-to-peak, rad)");
    o.square_waves.push_back({v[0], v[1], v.size() > 2 ? v[2] : 0.0});
  }
  for (const std::string& text : c.steps) {
    const auto v = numbers_of("--step", text, ':', 2, 2, "T:S (time in s, size in deg/h)");
    o.steps.push_back({v[0], v[1]});
  }
  if (!c.spikes.empty()) {
    const auto v = numbers_of("--spikes", c.spikes, ':', 2, 2, "RATE:SIZE (per hour, deg/h)");
    o.spike_rate_per_hour = v[0];
    o.spike_size_deg_h = v[1];
  }
  o.moving_average_samples = c.moving_average;
  if (c.filter_tc) o.filter_time_constant_s = *c.filter_tc;
  if (c.butterworth_hz) o.butterworth_cutoff_hz = *c.butterworth_hz;
  if (c.lsb) o.lsb_deg_h = *c.lsb;
  if (c.stamp_jitter_s) o.time_jitter_s = *c.stamp_jitter_s;
  for (const std::string& text : c.drops) {
    const auto v = numbers_of("--drop", text, ':', 2, 2, "T:D (start and duration in s)");
    o.dropouts.push_back({v[0], v[1]});
  }
  return o;
}

// The dropouts and the gaps they leave (indices among the samples written).
nlohmann::json dropouts_json(const sim::SensorOutput& o, const sim::GeneratorOptions& g,
                             std::int64_t samples) {
  nlohmann::json list = nlohmann::json::array();
  for (const sim::Dropout& d : o.dropouts) {
    list.push_back({{"start_s", d.start_s}, {"duration_s", d.duration_s}});
  }
  nlohmann::json gaps = nlohmann::json::array();
  for (const Gap& gap : sim::dropout_gaps(o, g.sample_rate_hz, samples)) {
    gaps.push_back(
        {{"before_sample", gap.before_sample}, {"missing_samples", gap.missing_samples}});
  }
  return {{"asked", list}, {"gaps", gaps}};
}

nlohmann::json sensor_output_json(const sim::SensorOutput& o, const sim::GeneratorOptions& g,
                                  std::int64_t samples) {
  nlohmann::json sines = nlohmann::json::array(), steps = nlohmann::json::array();
  for (const sim::Sinusoid& s : o.sinusoids) {
    const double gain = sim::output_filter_gain(o, s.frequency_hz, g.sample_rate_hz);
    sines.push_back({{"frequency_hz", s.frequency_hz},
                     {"amplitude_deg_h", s.amplitude_deg_h},
                     {"rms_deg_h", s.amplitude_deg_h / std::sqrt(2.0)},
                     {"filter_gain", gain},
                     {"rms_in_output_deg_h", gain * s.amplitude_deg_h / std::sqrt(2.0)},
                     {"phase_rad", s.phase_rad}});
  }
  nlohmann::json squares = nlohmann::json::array();
  for (const sim::SquareWave& s : o.square_waves) {
    squares.push_back({{"frequency_hz", s.frequency_hz},
                       {"amplitude_deg_h", s.amplitude_deg_h},
                       {"rms_deg_h", s.amplitude_deg_h},
                       {"phase_rad", s.phase_rad}});
  }
  for (const sim::BiasStep& s : o.steps) {
    steps.push_back({{"time_s", s.time_s}, {"size_deg_h", s.size_deg_h}});
  }
  const double tc = o.filter_time_constant_s;
  return {{"sinusoids", sines},
          {"square_waves", squares},
          {"steps", steps},
          {"moving_average_samples", o.moving_average_samples},
          {"filter_time_constant_s", tc},
          {"filter_cutoff_hz",
           tc > 0 ? nlohmann::json(1.0 / (2.0 * std::numbers::pi * tc)) : nlohmann::json(nullptr)},
          {"filter_lag1", tc > 0 ? std::exp(-1.0 / (g.sample_rate_hz * tc)) : 0.0},
          {"butterworth_cutoff_hz", o.butterworth_cutoff_hz > 0
                                        ? nlohmann::json(o.butterworth_cutoff_hz)
                                        : nlohmann::json(nullptr)},
          {"spike_rate_per_hour", o.spike_rate_per_hour},
          {"spike_size_deg_h", o.spike_size_deg_h},
          {"spike_times_s", sim::spike_times_s(o, g.sample_rate_hz, g.seed, g.stream, samples)},
          {"lsb_deg_h", o.lsb_deg_h},
          {"time_jitter_s", o.time_jitter_s},
          {"time_jitter_rms_s", o.time_jitter_s / std::sqrt(3.0)},
          {"dropouts", dropouts_json(o, g, samples)}};
}

enum class OutFormat { mat, csv, f32, f64 };

OutFormat format_of(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".mat") return OutFormat::mat;
  if (ext == ".csv") return OutFormat::csv;
  if (ext == ".f32") return OutFormat::f32;
  if (ext == ".f64") return OutFormat::f64;
  throw UsageError(
      fmt::format("--out '{}': unknown output type '{}'; use .mat, .csv, .f32 or .f64", path, ext));
}

std::string_view to_string(OutFormat f) {
  switch (f) {
    case OutFormat::mat:
      return "mat";
    case OutFormat::csv:
      return "csv";
    case OutFormat::f32:
      return "f32";
    case OutFormat::f64:
      return "f64";
  }
  return "";
}

// --temperature with the sensor's step (--temp-lsb).
sim::TemperatureProfile temperature_of(const GenerateCommand& c) {
  sim::TemperatureProfile t = sim::parse_temperature(c.temperature);
  if (c.temp_lsb) t.lsb_c = *c.temp_lsb;
  return t;
}

std::vector<double> parse_coefs(const std::string& text) {
  if (text.empty()) return {};
  return numbers_of("--temp-coef", text, ',', 1, std::numeric_limits<std::size_t>::max(),
                    "c1,c2,... in deg/h/degC^k");
}

nlohmann::json units_json() {
  nlohmann::json units = model_units_json();
  units["rate"] = "deg/h";
  units["temperature"] = "degC";
  units["time"] = "s";
  return units;
}

/// Refuses an --out or --truth that would overwrite the --temperature file
/// (or another output).
void check_generate_paths(const GenerateCommand& c) {
  const RunPath inputs[] = {
      {"--temperature", c.temperature.starts_with("file:") ? c.temperature.substr(5) : ""}};
  const RunPath outputs[] = {{"--out", c.out}, {"--truth", c.truth}};
  check_outputs(inputs, outputs);
}

/// The gyroscope's model options (--N .. --gm-tc, --bias, --input-rate,
/// --temp-coef) over `model`'s values.
void apply_gyroscope_options(const GenerateCommand& c, sim::ErrorModel& model) {
  auto apply = [](const std::optional<double>& v, double& field) {
    if (v) field = *v;
  };
  apply(c.N, model.noise.N);
  apply(c.B, model.noise.B);
  apply(c.K, model.noise.K);
  apply(c.R, model.noise.R);
  apply(c.Q, model.noise.Q);
  apply(c.gm_sigma, model.noise.gm_sigma);
  apply(c.gm_tc, model.noise.gm_tc);
  apply(c.bias, model.bias);
  apply(c.input_rate, model.input_rate);
  if (!c.temp_coefs.empty()) model.temp_coefs = parse_coefs(c.temp_coefs);
}

/// --fs (else `default_rate_hz`: a preset's or the IMU model's), --hours,
/// --seed and --stream, checked; `samples` is the record's length.
sim::GeneratorOptions generator_options(const GenerateCommand& c,
                                        const std::optional<double>& default_rate_hz,
                                        std::int64_t& samples) {
  sim::GeneratorOptions options;
  if (c.sample_rate_hz) {
    options.sample_rate_hz = *c.sample_rate_hz;
  } else if (default_rate_hz) {
    options.sample_rate_hz = *default_rate_hz;
  } else {
    throw UsageError("--fs is required (the sample rate in Hz) unless a --preset gives one");
  }
  if (!(options.sample_rate_hz >= kMinSampleRateHz && options.sample_rate_hz <= kMaxSampleRateHz)) {
    throw UsageError(fmt::format("--fs must be from {:g} to {:g} Hz, got {}", kMinSampleRateHz,
                                 kMaxSampleRateHz, options.sample_rate_hz));
  }
  if (!c.hours) throw UsageError("--hours is required (the duration in hours)");
  if (!(*c.hours > 0.0 && *c.hours <= 1e6)) {
    throw UsageError(
        fmt::format("--hours must be in (0, 1e6] (a century is 876600 h), got {}", *c.hours));
  }
  options.duration_s = *c.hours * 3600.0;
  options.seed = c.seed;
  options.stream = c.stream;
  samples = static_cast<std::int64_t>(std::llround(options.duration_s * options.sample_rate_hz));
  if (samples < 1) {
    throw UsageError(fmt::format("--fs {} Hz for --hours {} gives no samples",
                                 options.sample_rate_hz, *c.hours));
  }
  return options;
}

/// `generate --imu`: six axes, one file (CSV, MAT or a ROS bag), the truth
/// of each axis.
void run_imu(const GenerateCommand& c) {
  check_generate_paths(c);
  if (!c.preset.empty()) {
    throw UsageError(fmt::format(
        "--preset {} with --imu: the presets are single gyroscopes; --imu starts from the "
        "mems-imu model (set its gyroscopes with --N/--B/--K, its accelerometers with "
        "--accel-N/--accel-B/--accel-K)",
        c.preset));
  }
  if (c.filter_tc || c.butterworth_hz || c.moving_average != 1 || !c.sines.empty() ||
      !c.squares.empty() || !c.steps.empty() || !c.spikes.empty() || c.lsb) {
    throw UsageError(
        "--imu takes --drop of the sensor-output options; the filter, sine, square, step, spike "
        "and LSB options are a single gyroscope's (deg/h) and are not applied to an IMU");
  }
  if (!c.drop_mark.empty()) {
    throw UsageError(
        "--drop-mark is a single gyroscope's file's; an IMU's dropped samples are rows left "
        "out (.csv, .mat) or messages missing (.bag)");
  }
  sim::ImuModel imu = sim::mems_imu_model();
  const sim::SensorOutput output = sensor_output_of(c);
  for (std::size_t a = 0; a < 6; ++a) {
    sim::ErrorModel& axis = imu.axes[a];
    if (a < 3) {
      apply_gyroscope_options(c, axis);
    } else {
      if (c.accel_N) axis.noise.N = *c.accel_N;
      if (c.accel_B) axis.noise.B = *c.accel_B;
      if (c.accel_K) axis.noise.K = *c.accel_K;
    }
    axis.output.dropouts = output.dropouts;
  }
  std::int64_t samples = 0;
  const sim::GeneratorOptions options = generator_options(c, imu.sample_rate_hz, samples);
  const std::string ext = std::filesystem::path(c.out).extension().string();
  if (ext != ".csv" && ext != ".mat" && ext != ".bag") {
    throw UsageError(fmt::format(
        "--out '{}' with --imu: write a .csv, .mat or .bag (ROS 1) file, not '{}'", c.out, ext));
  }
  sim::validate(output, options.sample_rate_hz);
  const double jitter_s = output.time_jitter_s;
  const sim::TemperatureProfile temperature = temperature_of(c);
  progress(fmt::format("generating 6 x {} samples ({} h at {} Hz)", samples, *c.hours,
                       options.sample_rate_hz));

  // Each axis its own stream: independent noise, the same seed.
  std::array<std::vector<double>, 6> axes;
  sim::Recording first;
  for (std::size_t a = 0; a < 6; ++a) {
    sim::GeneratorOptions o = options;
    o.stream = c.stream * 8 + a;
    sim::Recording rec = sim::generate(imu.axes[a], temperature, o);
    if (a == 0) sim::jitter_times(rec.time_s, 0, output, o.sample_rate_hz, o.seed, o.stream);
    sim::remove_dropouts(rec, imu.axes[a].output);
    axes[a] = std::move(rec.rate_deg_h);
    if (a == 0) first = std::move(rec);
  }

  std::vector<std::string> variables;
  if (ext == ".bag") {
    io::ImuBagContent bag;
    bag.topic = "/imu";
    bag.frame_id = "imu_link";
    // ROS time: the recording starts at 1.7e9 s (November 2023); the stamps
    // carry the sensor's clock plus the jitter asked for (sim::jitter_times).
    constexpr double kStartS = 1.7e9;
    bag.stamps_s.reserve(first.time_s.size());
    for (const double t : first.time_s) bag.stamps_s.push_back(kStartS + t);
    for (std::size_t a = 0; a < 3; ++a) {
      bag.angular_velocity_rad_s[a] = std::move(axes[a]);
      for (double& v : bag.angular_velocity_rad_s[a])
        v /= to_deg_per_hour(RateUnit::rad_per_second);
      bag.linear_acceleration_m_s2[a] = std::move(axes[3 + a]);
    }
    io::write_imu_bag(c.out, bag);
    variables = {"/imu: sensor_msgs/Imu"};
  } else {
    std::vector<io::NamedVector> vars;
    const double f = first.sample_rate_hz;
    if (ext == ".mat") vars.push_back({"f", {&f, 1}});
    vars.push_back({"t", first.time_s});
    for (std::size_t a = 0; a < 6; ++a) vars.push_back({std::string(io::kImuChannels[a]), axes[a]});
    vars.push_back({ext == ".mat" ? "T" : "temperature", first.temperature_c});
    if (ext == ".mat") {
      io::write_mat(c.out, vars);
    } else {
      const std::vector<std::string> comments = {
          fmt::format("foglab {} generate --imu: t [s], gyro_x..z [deg/h], accel_x..z [m/s^2], "
                      "temperature [degC]; {} Hz, seed {}, stream {}",
                      version(), f, options.seed, c.stream)};
      io::write_csv(c.out, vars, comments);
    }
    for (const io::NamedVector& v : vars) variables.push_back(v.name);
  }

  if (!c.truth.empty()) {
    nlohmann::json axes_json = nlohmann::json::object();
    std::array<double, 4> kalibr{};  // mean squares: gyro N, K; accel N, K
    for (std::size_t a = 0; a < 6; ++a) {
      const bool gyro = a < 3;
      const NoiseModel& n = imu.axes[a].noise;
      const double factor = report::kalibr_factor(gyro ? Sensor::gyroscope : Sensor::accelerometer);
      kalibr[gyro ? 0 : 2] += n.N * factor * n.N * factor / 3.0;
      kalibr[gyro ? 1 : 3] += n.K * factor * n.K * factor / 3.0;
      nlohmann::json j = model_json(imu.axes[a]);
      j["sensor"] = gyro ? "gyroscope" : "accelerometer";
      j["unit"] = gyro ? "deg/h" : "m/s^2";
      const AdevMinimum bi =
          adev_minimum(n, 1.0 / options.sample_rate_hz,
                       std::max(1.0 / options.sample_rate_hz, options.duration_s / 10.0));
      j["bias_instability"] = bi.adev_deg_h;
      j["bias_instability_tau_s"] = bi.tau_s;
      axes_json[std::string(io::kImuChannels[a])] = j;
    }
    const nlohmann::json truth = {
        {"generator", "foglab generate --imu"},
        {"foglab_version", std::string(version())},
        {"imu", imu.name},
        {"description", imu.description},
        {"axes", axes_json},
        {"kalibr",
         {{"gyroscope_noise_density", std::sqrt(kalibr[0])},
          {"gyroscope_random_walk", std::sqrt(kalibr[1])},
          {"accelerometer_noise_density", std::sqrt(kalibr[2])},
          {"accelerometer_random_walk", std::sqrt(kalibr[3])},
          {"update_rate", options.sample_rate_hz},
          {"of", "root mean square over each sensor's axes, continuous-time, Kalibr's units"}}},
        {"units",
         {{"gyroscope", "N deg/h/sqrt(Hz), B deg/h, K deg/h/sqrt(s), bias deg/h"},
          {"accelerometer", "N m/s^2/sqrt(Hz), B m/s^2, K m/s^2/sqrt(s), bias m/s^2"},
          {"kalibr", "rad/s/sqrt(Hz), rad/s^2/sqrt(Hz), m/s^2/sqrt(Hz), m/s^3/sqrt(Hz), Hz"}}},
        {"sample_rate_hz", options.sample_rate_hz},
        {"duration_s", options.duration_s},
        {"samples", samples},
        {"seed", options.seed},
        {"stream", c.stream},
        {"axis_streams", "stream x 8 + axis (0..5, in the order of the axes)"},
        {"stamp_jitter_s", jitter_s},
        {"dropouts", dropouts_json(output, options, samples)},
        {"output", {{"path", c.out}, {"variables", variables}}}};
    write_text_file(c.truth, json_text(truth));
  }
  if (c.truth != "-") {
    std::cout << fmt::format(
        "wrote '{}': a 6-axis IMU ({}), {} samples per axis at {} Hz ({} h), seed {}, stream {}\n",
        c.out, imu.name, first.time_s.size(), options.sample_rate_hz, *c.hours, options.seed,
        c.stream);
  }
}

/// The recording of `model` written to `out` with the seed and `stream`:
/// its truth document, and the sentence that says what was written.
struct Written {
  nlohmann::json truth;
  std::string summary;
};

Written write_recording(const GenerateCommand& c, const sim::ErrorModel& model,
                        const sim::GeneratorOptions& generator, std::int64_t samples,
                        const std::string& out, const std::string& shown_out) {
  const sim::GeneratorOptions& options = generator;
  const OutFormat format = format_of(out);
  const sim::TemperatureProfile temperature = temperature_of(c);
  const double t_ref = temperature.reference_c(options.duration_s);

  std::vector<std::string> variables;
  const bool raw = format == OutFormat::f32 || format == OutFormat::f64;
  if (raw && model.output.time_jitter_s > 0.0) {
    throw UsageError(
        fmt::format("--stamp-jitter: '{}' is a raw file, which has no time column; "
                    "write a .mat or .csv file",
                    shown_out));
  }
  if (raw && c.drop_mark == "time" && !model.output.dropouts.empty()) {
    throw UsageError(
        fmt::format("--drop-mark time: '{}' is a raw file, which has no time column to show "
                    "the gaps; write a .mat or .csv file, or mark the lost samples NaN "
                    "(--drop-mark nan, the default for a raw file)",
                    shown_out));
  }
  if (raw) {
    // streamed block by block: constant memory whatever the length
    io::RawFileWriter writer(out, format == OutFormat::f32 ? io::RawType::f32 : io::RawType::f64);
    std::vector<double> marked;
    sim::generate(model, temperature, options, [&](const sim::Block& block) {
      if (model.output.dropouts.empty()) {
        writer.append(block.rate_deg_h);
        return;
      }
      marked.assign(block.rate_deg_h.begin(), block.rate_deg_h.end());
      sim::mark_dropouts_nan(marked, block.first_index, samples, model.output,
                             options.sample_rate_hz);
      writer.append(marked);
    });
    writer.commit();
    variables = {"rate"};
  } else {
    sim::Recording rec = sim::generate(model, temperature, options);
    sim::jitter_times(rec.time_s, 0, model.output, options.sample_rate_hz, options.seed,
                      options.stream);
    if (c.drop_mark == "nan") {
      // the lost rows stay, rate and temperature NaN (the time goes on)
      const auto total = static_cast<std::int64_t>(rec.rate_deg_h.size());
      sim::mark_dropouts_nan(rec.rate_deg_h, 0, total, model.output, rec.sample_rate_hz);
      sim::mark_dropouts_nan(rec.temperature_c, 0, total, model.output, rec.sample_rate_hz);
    } else {
      sim::remove_dropouts(rec, model.output);
    }
    if (format == OutFormat::mat) {
      const double f = rec.sample_rate_hz;
      const std::vector<io::NamedVector> vars = {
          {"f", {&f, 1}}, {"t", rec.time_s}, {"Y1", rec.rate_deg_h}, {"T1", rec.temperature_c}};
      io::write_mat(out, vars);
      variables = {"f", "t", "Y1", "T1"};
    } else {
      const std::vector<io::NamedVector> cols = {
          {"t", rec.time_s}, {"rate", rec.rate_deg_h}, {"temperature", rec.temperature_c}};
      const std::vector<std::string> comments = {
          fmt::format("foglab {} generate: t [s], rate [deg/h], temperature [degC]; {} Hz, "
                      "seed {}, stream {}",
                      version(), rec.sample_rate_hz, options.seed, options.stream)};
      io::write_csv(out, cols, comments);
      variables = {"t", "rate", "temperature"};
    }
  }

  const AdevMinimum bi =
      adev_minimum(model.noise, 1.0 / options.sample_rate_hz,
                   std::max(1.0 / options.sample_rate_hz, options.duration_s / 10.0));
  const double arw = arw_deg_sqrt_h(model.noise.N);
  const ClassVerdict verdict = classify(bi.adev_deg_h, arw);
  nlohmann::json temp = {{"spec", c.temperature},
                         {"kind", std::string(sim::to_string(temperature.kind))},
                         {"start_c", temperature.start_c},
                         {"span_c", temperature.span_c},
                         {"jitter_c", temperature.jitter_c},
                         {"lsb_c", temperature.lsb_c},
                         {"reference_c", t_ref}};
  Written w;
  w.truth = {
      {"generator", "foglab generate"},
      {"foglab_version", std::string(version())},
      {"preset", c.preset.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.preset)},
      {"model", model_json(model)},
      {"sensor_output", sensor_output_json(model.output, options, samples)},
      {"units", units_json()},
      {"arw_deg_per_sqrt_h", arw},
      {"temperature", temp},
      {"sample_rate_hz", options.sample_rate_hz},
      {"duration_s", options.duration_s},
      {"samples", samples},
      {"seed", options.seed},
      {"stream", options.stream},
      {"output",
       {{"path", shown_out}, {"format", std::string(to_string(format))}, {"variables", variables}}},
      {"theory",
       {{"bias_instability_deg_h", bi.adev_deg_h},
        {"bias_instability_tau_s", bi.tau_s},
        {"bias_instability_at_range_edge", bi.at_range_edge},
        {"usable_tau_s", {1.0 / options.sample_rate_hz, options.duration_s / 10.0}},
        {"accuracy_class", std::string(to_string(verdict.accuracy_class))},
        {"class_decided_by", std::string(to_string(verdict.decided_by))}}}};
  // how the file shows the dropped samples: rows left out (the time column
  // shows the gap) or rows kept with NaN samples
  w.truth["sensor_output"]["dropouts"]["mark"] = raw || c.drop_mark == "nan" ? "nan" : "time";
  w.summary = fmt::format(
      "wrote '{}': {} samples at {} Hz ({} h), seed {}, stream {}; model ADEV minimum "
      "{:.4g} deg/h at {:.4g} s, ARW {:.4g} deg/sqrt(h), class {}",
      shown_out, samples, options.sample_rate_hz, *c.hours, options.seed, options.stream,
      bi.adev_deg_h, bi.tau_s, arw, to_string(verdict.accuracy_class));
  return w;
}

/// `generate --fleet`: a folder of units scattered about the model (sim/fleet.h),
/// DIR/NAME_001.EXT ..., and DIR/fleet_truth.json.
void run_fleet(const GenerateCommand& c, const sim::ErrorModel& nominal,
               const sim::GeneratorOptions& options, std::int64_t samples) {
  if (!c.truth.empty()) {
    throw UsageError(
        "--truth: a fleet's truth is written beside its units (fleet_truth.json in --out's "
        "folder)");
  }
  const std::filesystem::path pattern(c.out);
  if (pattern.stem().empty() || !pattern.has_parent_path()) {
    throw UsageError(fmt::format(
        "--out '{}': with --fleet, --out is FOLDER/NAME.EXT (e.g. fleet/unit.mat): the folder "
        "to write, the units' name and their type",
        c.out));
  }
  (void)format_of(c.out);
  sim::FleetSpec spec;
  spec.units = static_cast<std::size_t>(*c.fleet);
  spec.spread_log10 = c.fleet_spread;
  spec.outliers = c.fleet_outliers;
  spec.outlier_factor = c.outlier_factor;
  spec.seed = c.seed;
  const std::vector<sim::FleetMember> fleet = sim::draw_fleet(nominal, spec);

  OutputFolder folder("--out", pattern.parent_path().string());
  const int digits = std::max(3, static_cast<int>(std::to_string(fleet.size()).size()));
  nlohmann::json units = nlohmann::json::array();
  nlohmann::json outliers = nlohmann::json::array();
  for (std::size_t k = 0; k < fleet.size(); ++k) {
    const std::string name = fmt::format("{}_{:0{}}", pattern.stem().string(), k + 1, digits);
    const std::string file = name + pattern.extension().string();
    progress(fmt::format("[{}/{}] generating {}", k + 1, fleet.size(), file));
    sim::GeneratorOptions unit_options = options;
    unit_options.stream = c.stream + k;
    Written w = write_recording(c, fleet[k].model, unit_options, samples, folder.file(file),
                                folder.final_file(file));
    const nlohmann::json outlier = fleet[k].outlier_parameter.empty()
                                       ? nlohmann::json(nullptr)
                                       : nlohmann::json(fleet[k].outlier_parameter);
    if (!fleet[k].outlier_parameter.empty()) {
      outliers.push_back({{"unit", name}, {"parameter", fleet[k].outlier_parameter}});
    }
    w.truth["unit"] = name;
    w.truth["outlier_parameter"] = outlier;
    units.push_back(std::move(w.truth));
  }
  const nlohmann::json truth = {
      {"generator", "foglab generate --fleet"},
      {"foglab_version", std::string(version())},
      {"preset", c.preset.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.preset)},
      {"nominal_model", model_json(nominal)},
      {"units_count", fleet.size()},
      {"spread_log10", spec.spread_log10},
      {"outlier_factor", spec.outlier_factor},
      {"seed", spec.seed},
      {"about",
       "each unit's N, B, K, R, Q, gm_sigma are the nominal ones times independent factors "
       "10^(spread_log10 z), z standard normal: the fleet's median of each is the nominal value "
       "and its log10 has standard deviation spread_log10; an outlier has one of N, B, K "
       "multiplied further by outlier_factor"},
      {"outliers", outliers},
      {"units", units}};
  write_text_file(folder.file("fleet_truth.json"), json_text(truth));
  folder.commit();
  std::cout << fmt::format(
      "wrote {} units to '{}' ({} samples each at {} Hz, {} h; spread {} in log10, {} "
      "outlier(s) x{}) and their truth, fleet_truth.json\n",
      fleet.size(), pattern.parent_path().string(), samples, options.sample_rate_hz, *c.hours,
      spec.spread_log10, spec.outliers, spec.outlier_factor);
}

void run(const GenerateCommand& c) {
  if (c.imu) {
    if (c.fleet) throw UsageError("--fleet and --imu: a fleet is of single gyroscopes");
    run_imu(c);
    return;
  }
  if (c.accel_N || c.accel_B || c.accel_K) {
    throw UsageError("--accel-N, --accel-B and --accel-K need --imu");
  }
  if (!c.fleet && (c.fleet_outliers != 0 || c.fleet_spread_given || c.outlier_factor_given)) {
    throw UsageError("--spread, --outliers and --outlier-factor need --fleet");
  }
  check_generate_paths(c);
  sim::ErrorModel model;
  std::optional<double> preset_rate;
  if (!c.preset.empty()) {
    const sim::Preset& p = sim::find_preset(c.preset);
    model = p.model;
    preset_rate = p.sample_rate_hz;
  }
  apply_gyroscope_options(c, model);
  model.output = sensor_output_of(c);

  std::int64_t samples = 0;
  const sim::GeneratorOptions options = generator_options(c, preset_rate, samples);
  if (c.fleet) {
    run_fleet(c, model, options, samples);
    return;
  }
  progress(fmt::format("generating {} samples ({} h at {} Hz)", samples, *c.hours,
                       options.sample_rate_hz));
  const Written w = write_recording(c, model, options, samples, c.out, c.out);
  if (!c.truth.empty()) write_text_file(c.truth, json_text(w.truth));
  if (c.truth != "-") std::cout << w.summary << "\n";
}

}  // namespace

std::function<void()> register_generate(CLI::App& app) {
  auto c = std::make_shared<GenerateCommand>();
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "synthetic static-gyro recording with known truth (MAT f,t,Y1,T1; CSV t,rate,temperature; "
      "raw .f32/.f64 rate)");
  cmd->add_option("--preset", c->preset,
                  "start from a preset (kvh-dsp-3000, class-navigation, ...); explicit model "
                  "options override its values");
  cmd->add_option("--N", c->N, "white rate noise N [deg/h/sqrt(Hz)] (ARW = N/60 deg/sqrt(h))");
  cmd->add_option("--B", c->B, "flicker coefficient B [deg/h] (ADEV floor 0.664 B)");
  cmd->add_option("--K", c->K, "rate random walk K [deg/h/sqrt(s)]");
  cmd->add_option("--R", c->R, "rate ramp R [deg/h/s]");
  cmd->add_option("--Q", c->Q, "angle quantisation Q [deg/h*s]");
  cmd->add_option("--gm-sigma", c->gm_sigma, "Gauss-Markov sigma [deg/h]");
  cmd->add_option("--gm-tc", c->gm_tc, "Gauss-Markov correlation time [s]");
  cmd->add_option("--bias", c->bias, "constant bias [deg/h]");
  cmd->add_option("--temp-coef", c->temp_coefs,
                  "temperature coefficients c1,c2,... [deg/h/degC^k] about the mean temperature");
  cmd->add_option("--input-rate", c->input_rate, "constant input rate [deg/h]");
  cmd->add_option("--fs", c->sample_rate_hz, "sample rate [Hz] (default: the preset's)");
  cmd->add_option("--hours", c->hours, "duration [h]")->required();
  cmd->add_option("--seed", c->seed, "random seed (same seed, same bits)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--stream", c->stream, "independent stream number for one seed")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--temperature", c->temperature,
                  "const, const:25, ramp:10, ramp:10@20 or file:PATH")
      ->capture_default_str();
  cmd->add_option("--temp-lsb", c->temp_lsb,
                  "temperature sensor's step [degC]: the recorded temperature is rounded to it "
                  "(the rate follows the temperature itself)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", c->out, "output: FILE.mat, FILE.csv, FILE.f32 or FILE.f64")->required();
  cmd->add_option("--truth", c->truth, "write the truth as JSON ('-' for stdout)");
  cmd->add_option("--filter-tc", c->filter_tc,
                  "sensor bandwidth: first-order low-pass time constant on the output [s]");
  cmd->add_option("--butterworth", c->butterworth_hz,
                  "sensor bandwidth: second-order Butterworth low-pass cut-off on the output [Hz]");
  cmd->add_option("--moving-average", c->moving_average,
                  "sensor bandwidth: moving average over this many samples")
      ->capture_default_str();
  cmd->add_option("--sine", c->sines,
                  "sinusoidal disturbance F:A[:PHASE] (Hz, deg/h peak, rad); repeatable");
  cmd->add_option("--square", c->squares,
                  "square-wave disturbance F:A[:PHASE] (Hz, deg/h half peak-to-peak, rad: "
                  "A sgn(sin(2 pi F t + PHASE)), a heater switched on and off); repeatable");
  cmd->add_option("--step", c->steps, "bias step T:S (from time s on, size deg/h); repeatable");
  cmd->add_option("--spikes", c->spikes, "spikes RATE:SIZE (mean per hour, deg/h each)");
  cmd->add_option("--lsb", c->lsb, "output word: round each sample to this step [deg/h]");
  cmd->add_option("--drop", c->drops,
                  "dropped samples T:D (from time s on, for D s; the time column shows the gap, "
                  "or see --drop-mark); repeatable");
  cmd->add_option("--drop-mark", c->drop_mark,
                  "how the file shows a dropped sample: time (its row left out, the time column "
                  "shows the gap; .mat and .csv) or nan (its row kept with a NaN rate and "
                  "temperature; the default for .f32/.f64)")
      ->check(CLI::IsMember({"time", "nan"}));
  cmd->add_flag("--imu", c->imu,
                "a 6-axis IMU (mems-imu model, 400 Hz): gyro_x..z [deg/h] and accel_x..z "
                "[m/s^2] to .csv, .mat or a ROS 1 .bag (sensor_msgs/Imu on /imu, rad/s and "
                "m/s^2); the gyroscope options set its three gyroscopes");
  cmd->add_option("--accel-N", c->accel_N,
                  "--imu: accelerometer white noise N [m/s^2/sqrt(Hz)] (VRW = 60 N m/s/sqrt(h))");
  cmd->add_option("--accel-B", c->accel_B,
                  "--imu: accelerometer flicker coefficient B [m/s^2] (ADEV floor 0.664 B)");
  cmd->add_option("--accel-K", c->accel_K,
                  "--imu: accelerometer bias random walk K [m/s^2/sqrt(s)] (= m/s^3/sqrt(Hz))");
  cmd->add_option("--stamp-jitter", c->stamp_jitter_s,
                  "the logger's clock: each time written (the time column, a bag's stamps) "
                  "moves by a uniform draw of +- this many s, under 0.4 sample steps; the "
                  "samples stay on the sensor's grid");
  cmd->add_option("--fleet", c->fleet,
                  "a fleet of this many units scattered about the model, one file each: --out "
                  "FOLDER/NAME.EXT writes FOLDER/NAME_001.EXT ... and FOLDER/fleet_truth.json")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option_function<double>(
      "--spread",
      [c](double v) {
        c->fleet_spread = v;
        c->fleet_spread_given = true;
      },
      "--fleet: sigma of log10 of each noise coefficient across the units (0.1: a factor "
      "1.26) [default: 0.1]");
  cmd->add_option("--outliers", c->fleet_outliers,
                  "--fleet: units with one of N, B, K multiplied by --outlier-factor");
  cmd->add_option_function<double>(
      "--outlier-factor",
      [c](double v) {
        c->outlier_factor = v;
        c->outlier_factor_given = true;
      },
      "--fleet: what an outlier's coefficient is multiplied by [default: 5]");
  return [c] { run(*c); };
}

}  // namespace foglab::cli
