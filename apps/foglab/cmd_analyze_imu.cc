// foglab analyze, the IMU form: several channels of one recording (three
// gyroscopes and three accelerometers of a CSV, a MAT file or a ROS bag)
// analysed in parallel by model::analyze_records(), then one JSON (an entry
// per channel), one Markdown summary (a row per axis), one HTML report
// (report/imu.h) and Kalibr's imu.yaml for both sensors. An accelerometer
// is read in m/s^2 and analysed like a gyroscope; its outputs speak in its
// terms (analysis_output.h accelerometer_json()).
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "analysis_output.h"
#include "analyze_command.h"
#include "cli_common.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/output.h"
#include "foglab/core/version.h"
#include "foglab/io/channels.h"
#include "foglab/io/rosbag.h"
#include "foglab/model/analysis.h"
#include "foglab/report/imu.h"
#include "foglab/report/report.h"

namespace foglab::cli {
namespace {

/// A ROS bag: by its extension, or --format rosbag.
bool is_bag(const AnalyzeCommand& c) {
  if (c.input.format == "rosbag" || c.input.format == "bag") return true;
  return c.input.format == "auto" && io::has_bag_extension(c.input.path);
}

/// --channels split at commas ("all": every channel of `available`).
std::vector<std::string> requested_channels(const AnalyzeCommand& c,
                                            const std::vector<std::string>& available) {
  if (c.channels == "all") return available;
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= c.channels.size()) {
    const std::size_t comma = std::min(c.channels.find(',', start), c.channels.size());
    std::string name = c.channels.substr(start, comma - start);
    start = comma + 1;
    if (name.empty()) {
      throw UsageError(fmt::format("--channels '{}': an empty channel name", c.channels));
    }
    if (std::find(out.begin(), out.end(), name) != out.end()) {
      throw UsageError(fmt::format("--channels '{}': {} is named twice", c.channels, name));
    }
    out.push_back(std::move(name));
  }
  return out;
}

/// The channels to analyse: --channels, else every inertial channel (a
/// bag: its six), else --channel's one (empty: the reader's default).
std::vector<std::string> channels_to_analyse(const AnalyzeCommand& c, bool bag) {
  if (bag) {
    const std::vector<std::string> six(io::kImuChannels.begin(), io::kImuChannels.end());
    if (!c.input.channel.empty() && !c.channels.empty()) {
      throw UsageError("--channel and --channels: give one of them");
    }
    if (c.channels.empty() && c.input.channel.empty()) return six;
    AnalyzeCommand one = c;
    if (one.channels.empty()) one.channels = c.input.channel;
    std::vector<std::string> wanted = requested_channels(one, six);
    for (const std::string& w : wanted) {
      if (std::find(six.begin(), six.end(), w) == six.end()) {
        throw UsageError(fmt::format("'{}': a ROS bag's IMU channels are {}; there is no '{}'",
                                     c.input.path, io::list_names(six), w));
      }
    }
    return wanted;
  }
  if (!c.channels.empty()) {
    if (!c.input.channel.empty()) throw UsageError("--channel and --channels: give one of them");
    if (c.input.path.empty() || c.input.path == "-" || io::is_stream(c.input.path)) {
      throw UsageError(
          fmt::format("--channels {}: several channels are read from a file, not from {}",
                      c.channels, c.input.path.empty() ? "the built-in sample" : "a stream"));
    }
    std::vector<std::string> available =
        io::list_channels(c.input.path, parse_format_option(c.input.format, c.input.path));
    // "all": the data channels, not the time or a temperature.
    std::erase_if(available, [](const std::string& name) {
      return io::is_time_channel_name(name, io::NameMatch::ignore_case) ||
             io::is_lab_temperature_name(name) || name == "f" ||
             io::find_channel({"temperature", "temp"}, name, io::NameMatch::ignore_case);
    });
    std::vector<std::string> wanted = requested_channels(c, available);
    for (const std::string& w : wanted) {
      const bool index =
          std::all_of(w.begin(), w.end(), [](unsigned char ch) { return std::isdigit(ch) != 0; });
      if (!index && !io::find_channel(available, w, io::NameMatch::ignore_case)) {
        throw UsageError(
            fmt::format("--channels {}: '{}' has no data channel '{}'; its data "
                        "channels are {}",
                        c.channels, c.input.path, w, io::list_names(available)));
      }
    }
    return wanted;
  }
  if (c.input.channel.empty() && !c.input.path.empty() && c.input.path != "-" &&
      !io::is_stream(c.input.path)) {
    // A file that cannot be listed is read (and refused, with the reader's
    // message) as one channel.
    std::vector<std::string> inertial;
    try {
      inertial = io::inertial_channels(
          io::list_channels(c.input.path, parse_format_option(c.input.format, c.input.path)));
    } catch (const std::exception&) {
      inertial.clear();
    }
    if (inertial.size() >= 2) return inertial;
  }
  return {c.input.channel};
}

/// One channel: what it is, and what its outputs need besides the analysis.
struct ChannelRun {
  std::string name;  ///< empty until read when the reader chooses it
  SampleUnit unit = SampleUnit::deg_per_hour;
  Sensor sensor = Sensor::gyroscope;
  std::vector<std::string> notes;
  AnalysisJsonInput json_input;
  report::ReportInput report_input;
};

/// The temperatures read so far, by channel name: the channels of an IMU
/// share one, read once.
class TemperatureCache {
 public:
  Temperature get(const AnalyzeCommand& c, const io::Series& series,
                  std::vector<std::string>& notes) {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> wanted = c.temp_channel.empty()
                                          ? io::paired_temperature_names(series.channel)
                                          : std::vector<std::string>{c.temp_channel};
    const std::string key = fmt::format("{}", fmt::join(wanted, ","));
    if (const auto found = cache_.find(key); found != cache_.end()) return found->second;
    Temperature t = load_temperature(c, series, notes);
    cache_.emplace(key, t);
    return t;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, Temperature> cache_;
};

/// The bag's timing as JSON (what the stamps said).
nlohmann::json bag_input_json(const io::ImuRecord& bag) {
  return {{"format", "rosbag"},
          {"topic", bag.topic},
          {"frame_id", bag.frame_id},
          {"message_type", io::kImuMessageType},
          {"start_time_s", bag.start_time_s},
          {"timing",
           {{"messages", bag.timing.messages},
            {"median_step_s", number(bag.timing.median_step_s)},
            {"jitter_rms_s", number(bag.timing.jitter_rms_s)},
            {"jitter_max_s", number(bag.timing.jitter_max_s)},
            {"duplicates_dropped", bag.timing.duplicates_dropped},
            {"stamp_source", bag.timing.stamp_source}}},
          {"units_in_bag",
           {{"angular_velocity", "rad/s (sensor_msgs/Imu, REP 103), converted to deg/h"},
            {"linear_acceleration", "m/s^2 (sensor_msgs/Imu, REP 103)"}}}};
}

/// The bag's timing in one sentence (a note).
std::string bag_timing_note(const io::ImuRecord& bag) {
  return fmt::format(
      "'{}' topic {}: {} messages, {:.6g} Hz from the {} (median step {:.6g} s, jitter {:.3g} s "
      "rms, {:.3g} s at most), {} gap(s) with {} sample(s) missing, {} duplicate(s) dropped; "
      "angular velocity read in rad/s and converted to deg/h, linear acceleration in m/s^2",
      bag.path, bag.topic, bag.timing.messages, bag.sample_rate_hz, bag.timing.stamp_source,
      bag.timing.median_step_s, bag.timing.jitter_rms_s, bag.timing.jitter_max_s, bag.gaps.size(),
      missing_samples(bag.gaps), bag.timing.duplicates_dropped);
}

}  // namespace

io::Series bag_axis_series(io::ImuRecord& record, const std::string& name, const std::string& path,
                           bool rate_from_option) {
  const auto axis = static_cast<std::size_t>(
      std::find(io::kImuChannels.begin(), io::kImuChannels.end(), name) - io::kImuChannels.begin());
  if (axis >= io::kImuChannels.size()) {
    throw UsageError(fmt::format("'{}': a ROS bag's IMU channels are {}; there is no '{}'", path,
                                 io::list_names({io::kImuChannels.begin(), io::kImuChannels.end()}),
                                 name));
  }
  std::vector<double>& source =
      axis < 3 ? record.angular_velocity_rad_s[axis] : record.linear_acceleration_m_s2[axis - 3];
  io::Series series;
  series.path = path;
  series.channel = name;
  series.values = std::move(source);
  const double factor =
      to_internal_unit(axis < 3 ? SampleUnit::rad_per_second : SampleUnit::m_per_s2);
  for (double& v : series.values) v *= factor;
  series.sample_rate_hz = record.sample_rate_hz;
  series.sample_rate_source =
      rate_from_option ? io::SampleRateSource::option : io::SampleRateSource::time_channel;
  series.sample_rate_channel = "header.stamp";
  series.gaps = record.gaps;
  series.start_time_s = record.start_time_s;
  return series;
}

std::optional<std::vector<std::string>> imu_channels(const AnalyzeCommand& c) {
  const bool bag = is_bag(c);
  const UnitSpec spec = parse_unit_spec(c.input.units, c.input.path);
  const bool wanted = !c.channels.empty() || bag || c.input.units.find('=') != std::string::npos ||
                      (spec.all && sensor_of(*spec.all) == Sensor::accelerometer) ||
                      io::sensor_by_name(c.input.channel) == Sensor::accelerometer;
  std::vector<std::string> names = channels_to_analyse(c, bag);
  if (!wanted && names.size() < 2) return std::nullopt;
  return names;
}

void run_imu_analysis(const AnalyzeCommand& c, const std::vector<std::string>& names) {
  const model::AnalysisOptions options = checked_analysis_options(c);
  const bool bag = is_bag(c);

  // A bag is read whole, once; its units are ROS's.
  std::optional<io::ImuRecord> record;
  if (bag) {
    if (c.input.units_given) {
      throw UsageError(fmt::format(
          "--units {}: '{}' is a ROS bag, whose sensor_msgs/Imu messages carry angular velocity "
          "in rad/s and linear acceleration in m/s^2 (REP 103); --units does not apply",
          c.input.units, c.input.path));
    }
    if (!c.temp_channel.empty()) {
      throw UsageError(fmt::format(
          "--temp {}: sensor_msgs/Imu messages carry no temperature ('{}' is a ROS bag)",
          c.temp_channel, c.input.path));
    }
    progress(fmt::format("reading '{}'", c.input.path));
    io::BagReadOptions read;
    read.topic = c.topic;
    read.sample_rate_hz = c.input.sample_rate_hz;
    read.max_samples = c.input.max_samples ? *c.input.max_samples : default_max_samples();
    record = io::read_imu_bag(c.input.path, read);
    for (const Message& m : record->notes) note(m.text());
    note(bag_timing_note(*record));
    note("sensor_msgs/Imu carries no temperature: each axis's systematic part is its mean");
  } else if (!c.topic.empty()) {
    throw UsageError(fmt::format("--topic {}: '{}' is not a ROS bag (.bag)", c.topic,
                                 c.input.path.empty() ? "the built-in sample" : c.input.path));
  }

  const UnitSpec spec =
      bag || !c.input.units_given ? UnitSpec{} : parse_unit_spec(c.input.units, c.input.path);
  std::vector<ChannelRun> runs(names.size());
  for (std::size_t k = 0; k < names.size(); ++k) {
    ChannelRun& run = runs[k];
    run.name = names[k];
    if (bag) {
      run.unit = io::sensor_by_name(run.name) == Sensor::gyroscope ? SampleUnit::rad_per_second
                                                                   : SampleUnit::m_per_s2;
    } else {
      run.unit = channel_unit(spec, run.name, c.input.path, run.notes);
    }
    run.sensor = sensor_of(run.unit);
  }
  for (const auto& [name, unit] : spec.channels) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      throw UsageError(fmt::format("--units {}={}: {} is not among the channels analysed ({})",
                                   name, to_string(unit), name, io::list_names(names)));
    }
  }
  if (names.size() > 1) {
    note(fmt::format("analysing {} channels of '{}' in parallel: {}", names.size(), c.input.path,
                     io::list_names(names)));
  }

  TemperatureCache temperatures;
  std::atomic<std::size_t> finished{0};
  auto load = [&](std::size_t k) {
    ChannelRun& run = runs[k];
    model::RecordToAnalyse out;
    io::Series series;
    if (bag) {
      series = bag_axis_series(*record, run.name, c.input.path, c.input.sample_rate_hz.has_value());
    } else {
      InputOptions in = c.input;
      in.units = "deg/h";  // set per channel below
      io::ReadOptions read = read_options(in);
      read.channel = run.name;
      read.unit = run.unit;
      read.nan_is_missing = true;  // left out below, with the temperature's NaN rows
      progress(fmt::format("reading '{}' channel {}", c.input.path,
                           run.name.empty() ? "(default)" : run.name));
      series = io::read_series(c.input.path, read);
      for (const Message& m : series.notes) note(m.text());
      if (run.name.empty()) {
        run.name = series.channel;
        run.unit = channel_unit(spec, run.name, c.input.path, run.notes);
        if (run.unit != read.unit) {
          // Converted again, not read again: the source may be a stream.
          const double factor = to_internal_unit(run.unit) / to_internal_unit(read.unit);
          for (double& v : series.values) v *= factor;
        }
        run.sensor = sensor_of(run.unit);
      }
    }
    for (const std::string& text : run.notes) note(text);
    Temperature temperature = bag ? Temperature{} : temperatures.get(c, series, run.notes);
    if (!bag) {
      leave_missing_samples(series, temperature.channel.empty() ? nullptr : &temperature.values_c);
    }
    const double record_mean = temperature.channel.empty() ? compensated_mean(series.values) : NAN;

    run.json_input.input = input_json(series);
    run.json_input.temperature_channel = temperature.channel;
    run.json_input.record_mean_deg_h = record_mean;
    run.json_input.units = std::string(to_string(run.unit));
    run.json_input.temp_degree = c.temp_degree;
    run.json_input.taus = c.taus;
    run.json_input.notes = run.notes;
    report::ReportInput& ri = run.report_input;
    ri.file_name = series.path;
    ri.channel = series.channel;
    ri.temperature_channel = temperature.channel;
    ri.input_unit = std::string(to_string(run.unit));
    ri.sensor = run.sensor;
    for (const std::string& text : run.notes) ri.notes.push_back(Message::verbatim(text));
    if (temperature.channel.empty()) ri.record_mean_deg_h = record_mean;
    if (!c.report_path.empty()) {
      ri.preview = report::preview_record(series.values, temperature.values_c,
                                          series.sample_rate_hz, 2000, series.gaps);
    }
    progress(fmt::format("analysing {} ({} samples)", run.name, series.values.size()));
    out.rate_deg_h = std::move(series.values);
    out.temperature_c = std::move(temperature.values_c);
    out.sample_rate_hz = series.sample_rate_hz;
    out.gaps = std::move(series.gaps);
    return out;
  };
  auto done = [&](std::size_t k) {
    progress(fmt::format("[{}/{}] {} analysed", ++finished, runs.size(), runs[k].name));
  };
  auto label = [&](std::size_t k) {
    return fmt::format("'{}' channel {}", c.input.path, runs[k].name);
  };
  const std::vector<model::AnalysisResult> results =
      model::analyze_records(runs.size(), load, options, 0, done, label);
  const nlohmann::json bag_json = bag ? bag_input_json(*record) : nlohmann::json(nullptr);
  const std::string rostopic = bag ? record->topic : "/imu0";
  record.reset();

  std::vector<report::ImuAxis> axes;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    axes.push_back({runs[k].name, runs[k].sensor, &results[k]});
  }
  const std::string title =
      fmt::format("IMU noise analysis of '{}'", c.input.path.empty() ? "-" : c.input.path);

  // Render everything first, then write: a failure never leaves half the outputs.
  std::string json, csv, html, yaml, markdown;
  if (!c.json_path.empty()) {
    nlohmann::json per_channel = nlohmann::json::array();
    for (std::size_t k = 0; k < runs.size(); ++k) {
      nlohmann::json j = analysis_json(results[k], runs[k].json_input, options);
      if (runs[k].sensor == Sensor::accelerometer) j = accelerometer_json(std::move(j));
      j["sensor"] = std::string(to_string(runs[k].sensor));
      j["filter"] = sensor_terms_json(results[k], runs[k].sensor);
      per_channel.push_back(std::move(j));
    }
    if (runs.size() == 1) {
      json = json_text(per_channel[0]);
    } else {
      const report::KalibrValues kv = report::kalibr_values(axes);
      nlohmann::json input = {{"path", c.input.path},
                              {"channels", names},
                              {"sample_rate_hz", results[0].sample_rate_hz}};
      if (bag) input.update(bag_json);
      nlohmann::json doc = {
          {"input", input},
          {"channels", per_channel},
          {"kalibr",
           {{"gyroscope_noise_density", number(kv.gyroscope_noise_density)},
            {"gyroscope_random_walk", number(kv.gyroscope_random_walk)},
            {"accelerometer_noise_density", number(kv.accelerometer_noise_density)},
            {"accelerometer_random_walk", number(kv.accelerometer_random_walk)},
            {"update_rate", results[0].sample_rate_hz},
            {"units",
             {{"gyroscope_noise_density", "rad/s/sqrt(Hz)"},
              {"gyroscope_random_walk", "rad/s^2/sqrt(Hz)"},
              {"accelerometer_noise_density", "m/s^2/sqrt(Hz)"},
              {"accelerometer_random_walk", "m/s^3/sqrt(Hz)"},
              {"update_rate", "Hz"}}},
            {"of", "the root mean square over each sensor's axes; continuous-time"}}},
          {"foglab_version", std::string(version())}};
      json = json_text(doc);
    }
  }
  if (!c.csv_path.empty()) {
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const std::string table = in_sensor_units(analysis_csv(results[k]), runs[k].sensor);
      if (runs.size() == 1) {
        csv = table;
        break;
      }
      // One table: a channel column in front, the header once (in deg/h
      // for gyroscopes and m/s^2 for accelerometers: a unit column says which).
      std::size_t line = 0, start = 0;
      while (start < table.size()) {
        const std::size_t end = table.find('\n', start);
        const std::string row = table.substr(start, end - start);
        if (line == 0 && k == 0) {
          std::string header = row;
          for (const std::string_view unit : {"_deg_h", "_m_s2"}) {
            for (std::size_t at = header.find(unit); at != std::string::npos;
                 at = header.find(unit)) {
              header.erase(at, unit.size());
            }
          }
          csv += "channel,unit," + header + "\n";
        } else if (line > 0) {
          csv += fmt::format("{},{},{}\n", runs[k].name, to_string(internal_unit(runs[k].sensor)),
                             row);
        }
        ++line;
        start = end == std::string::npos ? table.size() : end + 1;
      }
    }
  }
  if (!c.report_path.empty()) {
    progress("drawing the report's plots");
    std::vector<report::Report> reports;
    for (std::size_t k = 0; k < runs.size(); ++k) {
      report::ReportOptions o;
      o.id_prefix = fmt::format("a{}", k + 1);
      reports.push_back(report::make_report(results[k], runs[k].report_input, o));
      if (reports.back().plots_skipped && k == 0) note(reports.back().plots_note);
    }
    html = runs.size() == 1 && runs[0].sensor == Sensor::gyroscope
               ? report::html_document(reports[0])
               : report::imu_html(axes, reports, title, {});
  }
  if (!c.kalibr_path.empty()) {
    yaml = report::kalibr_imu_yaml(axes, c.input.path, results[0].sample_rate_hz, rostopic);
  }
  markdown = runs.size() == 1 ? report::markdown_summary(results[0], runs[0].report_input)
                              : report::imu_markdown(axes, title);
  if (!c.json_path.empty()) write_text_file(c.json_path, json);
  if (!c.csv_path.empty()) write_text_file(c.csv_path, csv);
  if (!c.report_path.empty()) write_text_file(c.report_path, html);
  if (!c.kalibr_path.empty()) write_text_file(c.kalibr_path, yaml);
  if (c.json_path != "-" && c.csv_path != "-") std::cout << markdown;
}

}  // namespace foglab::cli
