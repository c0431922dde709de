// foglab batch — a fleet of gyros: many recordings analysed in parallel
// (model::run_work_queue(), a file per job), each unit's result written as
// `analyze --json` writes it (OUT/units/NAME.json) the moment it is done,
// then the fleet report (report/fleet.h): fleet.json, fleet.csv, fleet.md
// and fleet.html.
//
// A unit is a gyroscope: a file, or each gyroscope channel of a file that
// has several (gyro_x, gyro_y, gyro_z of an IMU's CSV, MAT file or ROS bag),
// unless --channel names one. A record that fails is listed and the others
// go on. A rerun keeps every unit whose JSON is there, made from the same
// file (not modified since) with the same options, and analyses the rest:
// an interrupted batch loses only the units it was analysing.
#include <fmt/format.h>
#include <glob.h>
#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <set>
#include <string>
#include <vector>

#include "analysis_output.h"
#include "analyze_command.h"
#include "batch.h"
#include "cli_common.h"
#include "commands.h"
#include "foglab/core/error.h"
#include "foglab/core/output.h"
#include "foglab/core/text.h"
#include "foglab/core/version.h"
#include "foglab/io/channels.h"
#include "foglab/io/rosbag.h"
#include "foglab/model/analysis.h"
#include "foglab/model/fleet.h"
#include "foglab/report/fleet.h"
#include "foglab/stats/allan_drift.h"

namespace foglab::cli {
namespace {

namespace fs = std::filesystem;

/// The file types a folder is searched for.
bool is_recording_name(const fs::path& path) {
  static const std::set<std::string> kTypes = {".mat", ".csv", ".tsv", ".txt",
                                               ".dat", ".f32", ".f64", ".bag"};
  const std::string ext = ascii_lower(path.extension().string());
  return kTypes.contains(ext) && !path.filename().string().starts_with(".");
}

/// INPUTS as files: a folder's recordings (not its subfolders), a quoted
/// glob's matches, files as given; each once, in the order given.
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  std::set<fs::path> seen;
  auto add = [&](const std::string& file) {
    std::error_code ec;
    const fs::path key = fs::weakly_canonical(file, ec);
    if (seen.insert(ec ? fs::path(file) : key).second) files.push_back(file);
  };
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (fs::is_directory(input, ec)) {
      std::vector<std::string> found;
      for (const fs::directory_entry& e : fs::directory_iterator(input, ec)) {
        if (e.is_regular_file() && is_recording_name(e.path())) found.push_back(e.path().string());
      }
      if (ec) throw UsageError(fmt::format("INPUTS: cannot list '{}': {}", input, ec.message()));
      if (found.empty()) {
        throw UsageError(fmt::format(
            "INPUTS: the folder '{}' holds no recording (.mat, .csv, .tsv, .txt, .dat, .f32, "
            ".f64, .bag)",
            input));
      }
      std::sort(found.begin(), found.end());
      for (const std::string& f : found) add(f);
    } else if (fs::exists(input, ec)) {
      add(input);
    } else if (input.find_first_of("*?[") != std::string::npos) {
      glob_t matches{};
      const int status = ::glob(input.c_str(), 0, nullptr, &matches);
      std::vector<std::string> found;
      for (std::size_t k = 0; status == 0 && k < matches.gl_pathc; ++k) {
        if (fs::is_regular_file(matches.gl_pathv[k], ec)) found.emplace_back(matches.gl_pathv[k]);
      }
      ::globfree(&matches);
      if (found.empty()) throw UsageError(fmt::format("INPUTS: '{}' matches no file", input));
      for (const std::string& f : found) add(f);
    } else {
      throw UsageError(fmt::format("INPUTS: '{}': no such file or folder", input));
    }
  }
  if (files.empty()) throw UsageError("INPUTS: no recording given");
  return files;
}

/// The units' names: each file's stem, with its folder in front where two
/// stems are equal ("a_unit1", "b_unit1"), and a number where that is not
/// enough.
std::vector<std::string> unit_names(const std::vector<std::string>& files) {
  std::map<std::string, int> stems;
  for (const std::string& f : files) ++stems[fs::path(f).stem().string()];
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (const std::string& f : files) {
    const fs::path p(f);
    std::string name = p.stem().string();
    if (stems[name] > 1) name = p.parent_path().filename().string() + "_" + name;
    std::string unique = name;
    for (int k = 2; taken.contains(unique); ++k) unique = fmt::format("{}_{}", name, k);
    for (char& ch : unique) {
      if (ch == '/' || ch == '\\' || static_cast<unsigned char>(ch) < 32) ch = '_';
    }
    taken.insert(unique);
    names.push_back(unique);
  }
  return names;
}

bool is_bag_file(const BatchCommand& c, const std::string& file) {
  const std::string& f = c.analyze.input.format;
  return f == "rosbag" || f == "bag" || (f == "auto" && io::has_bag_extension(file));
}

/// The gyroscope channels of `file` that are units: --channel's, else
/// each gyroscope channel of a file with several, else "" (the reader's
/// choice, as `analyze` makes it).
std::vector<std::string> unit_channels(const BatchCommand& c, const std::string& file) {
  if (!c.analyze.input.channel.empty()) return {c.analyze.input.channel};
  if (is_bag_file(c, file)) return {"gyro_x", "gyro_y", "gyro_z"};
  std::vector<std::string> gyros;
  try {
    for (const std::string& name : io::inertial_channels(
             io::list_channels(file, parse_format_option(c.analyze.input.format, file)))) {
      if (io::sensor_by_name(name) == Sensor::gyroscope) gyros.push_back(name);
    }
  } catch (const std::exception&) {
    gyros.clear();  // read as one channel, and refused with the reader's message
  }
  if (gyros.size() >= 2) return gyros;
  return {""};
}

/// The unit of the samples as the unit's JSON records it: a bag's are ROS's.
std::string units_of(const BatchCommand& c, const std::string& file) {
  return is_bag_file(c, file) ? "rad/s" : c.analyze.input.units;
}

/// Whether the JSON of an earlier run at `json_path` can stand for the unit of `file` and
/// `channel` under `c`: the same file, not modified since, the same channel and options.
bool reusable(const BatchCommand& c, const std::string& file, const std::string& channel,
              const std::string& json_path) {
  std::error_code ec;
  const auto json_time = fs::last_write_time(json_path, ec);
  if (ec) return false;
  const auto file_time = fs::last_write_time(file, ec);
  if (ec || file_time > json_time) return false;
  try {
    std::ifstream in(json_path);
    const nlohmann::json doc = nlohmann::json::parse(in);
    const nlohmann::json& input = doc.at("input");
    if (input.at("path") != file) return false;
    if (!channel.empty() && input.at("channel") != channel) return false;
    if (input.at("units") != units_of(c, file)) return false;
    if (c.analyze.input.sample_rate_hz &&
        input.at("sample_rate_hz") != *c.analyze.input.sample_rate_hz) {
      return false;
    }
    const nlohmann::json& options = doc.at("options");
    return options.at("taus") == c.analyze.taus &&
           options.at("temp_degree") == c.analyze.temp_degree;
  } catch (const std::exception&) {
    return false;  // unreadable or another kind of file: analysed again
  }
}

/// A unit's name: the file's, with the channel after a dot when the file has several units.
std::string unit_name(const BatchFile& file, const std::vector<std::string>& channels,
                      const std::string& channel) {
  return channels.size() > 1 ? file.name + "." + channel : file.name;
}

/// Where a unit's `analyze --json` document lives in the units folder.
std::string unit_json_path(const std::string& units_dir, const std::string& name) {
  return (fs::path(units_dir) / (name + ".json")).string();
}

/// A JSON number, NaN for null (docs/json.md writes NaN and infinity as null).
double number_or_nan(const nlohmann::json& v) {
  return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
}

report::FleetTerm term_of(const nlohmann::json& j) {
  constexpr auto num = number_or_nan;
  report::FleetTerm t;
  t.status = j.at("status").get<std::string>();
  // A term left out: its 95 % upper bound where the data pull it above zero, else none.
  t.value = t.status == "upper_bound" && !j.at("value").is_number() ? num(j.at("upper_95"))
                                                                    : num(j.at("value"));
  const nlohmann::json& ci = j.at("ci95");
  const bool pair = ci.is_array() && ci.size() == 2;
  t.ci95_low = pair ? num(ci[0]) : std::numeric_limits<double>::quiet_NaN();
  t.ci95_high = pair ? num(ci[1]) : std::numeric_limits<double>::quiet_NaN();
  return t;
}

/// A unit's row from its JSON (the `analyze --json` contract, docs/json.md).
report::FleetRow row_of(const std::string& name, const std::string& file,
                        const std::string& json_path) {
  std::ifstream in(json_path);
  const nlohmann::json doc = nlohmann::json::parse(in);
  auto num = [&](const char* key) { return number_or_nan(doc.at(key)); };
  report::FleetRow r;
  r.unit = name;
  r.file = file;
  r.channel = doc.at("input").at("channel").get<std::string>();
  const nlohmann::json& noise = doc.at("noise_model");
  r.N = term_of(noise.at("N"));
  r.B = term_of(noise.at("B"));
  r.K = term_of(noise.at("K"));
  r.bias_instability_deg_h = num("bias_instability_deg_h");
  r.bias_instability_tau_s = num("bias_instability_tau_s");
  r.bias_instability_ci95_low = r.bias_instability_ci95_high =
      std::numeric_limits<double>::quiet_NaN();
  const nlohmann::json& allan = doc.at("allan");
  for (std::size_t k = 0; k < allan.at("tau_s").size(); ++k) {
    if (allan["tau_s"][k] == doc.at("bias_instability_tau_s")) {
      r.bias_instability_ci95_low = number_or_nan(allan.at("ci95_low")[k]);
      r.bias_instability_ci95_high = number_or_nan(allan.at("ci95_high")[k]);
    }
  }
  r.arw_deg_sqrt_h = num("arw_deg_per_sqrt_h");
  r.random_bias = doc.at("random_bias_process").get<std::string>();
  const nlohmann::json& cls = doc.at("accuracy_class");
  r.accuracy_class = cls.is_string() ? cls.get<std::string>() : "";
  // The short taus' stationarity check (absent from a unit of an earlier version: not checked).
  if (const auto d = doc.find("allan_drift"); d != doc.end()) {
    stats::AllanDrift drift;
    for (std::size_t k = 0; k < d->at("tau_s").size(); ++k) {
      drift.tau_s.push_back(number_or_nan(d->at("tau_s")[k]));
      drift.trend_z.push_back(number_or_nan(d->at("trend_z")[k]));
      drift.last_to_first.push_back(number_or_nan(d->at("last_to_first_ratio")[k]));
      drift.drifting.push_back(d->at("drifting")[k].get<bool>());
    }
    r.short_tau_trend = drift.calls();
    r.short_tau_checked = !drift.tau_s.empty();
  }
  return r;
}

nlohmann::json term_json(const report::FleetTerm& t) {
  return {{"value", number(t.value)},
          {"ci95", {number(t.ci95_low), number(t.ci95_high)}},
          {"status", t.status}};
}

nlohmann::json fleet_json(const BatchCommand& c, const report::FleetReport& fleet,
                          const std::vector<std::string>& files,
                          const std::map<std::string, std::string>& json_of) {
  std::map<std::string, std::vector<std::string>> stands_out;
  for (const model::FleetOutlier& o : fleet.summary.outliers) {
    stands_out[o.unit].push_back(o.parameter);
  }
  nlohmann::json units = nlohmann::json::array();
  for (const report::FleetRow& r : fleet.rows) {
    units.push_back(
        {{"unit", r.unit},
         {"file", r.file},
         {"channel", r.channel},
         {"json", json_of.at(r.unit)},
         {"N", term_json(r.N)},
         {"B", term_json(r.B)},
         {"K", term_json(r.K)},
         {"bias_instability_deg_h", number(r.bias_instability_deg_h)},
         {"bias_instability_tau_s", number(r.bias_instability_tau_s)},
         {"arw_deg_per_sqrt_h", number(r.arw_deg_sqrt_h)},
         {"random_bias_process", r.random_bias},
         {"accuracy_class",
          r.accuracy_class.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.accuracy_class)},
         {"stands_out_on", stands_out[r.unit]},
         {"short_tau_trend_tau_s", r.short_tau_checked ? nlohmann::json(r.short_tau_trend.tau_s)
                                                       : nlohmann::json(nullptr)}});
  }
  nlohmann::json parameters = nlohmann::json::array();
  for (const model::ParameterSpread& p : fleet.summary.parameters) {
    parameters.push_back({{"name", p.name},
                          {"units_counted", p.units},
                          {"median", number(p.median)},
                          {"spread_log10", number(p.spread_log10)},
                          {"spread_factor", number(p.spread_factor)},
                          {"p05", number(p.p05)},
                          {"p95", number(p.p95)},
                          {"minimum", number(p.minimum)},
                          {"maximum", number(p.maximum)}});
  }
  nlohmann::json outliers = nlohmann::json::array();
  for (const model::FleetOutlier& o : fleet.summary.outliers) {
    outliers.push_back({{"unit", o.unit},
                        {"parameter", o.parameter},
                        {"value", number(o.value)},
                        {"modified_z", number(o.modified_z)},
                        {"times_median", number(o.times_median)}});
  }
  nlohmann::json failures = nlohmann::json::array();
  for (const report::FleetFailure& f : fleet.failures) {
    failures.push_back({{"input", f.input}, {"exit_code", f.exit_code}, {"error", f.message}});
  }
  nlohmann::json units_of = {{"N", "deg/h/sqrt(Hz)"},
                             {"B", "deg/h"},
                             {"K", "deg/h/sqrt(s)"},
                             {"bias_instability", "deg/h"},
                             {"bias_instability_deg_h", "deg/h"},
                             {"bias_instability_tau_s", "s"},
                             {"arw_deg_per_sqrt_h", "deg/sqrt(h)"},
                             {"short_tau_trend_tau_s", "s"},
                             {"spread_log10", "decades (1.4826 MAD of log10 of the values)"},
                             {"spread_factor", "1 (10^spread_log10)"},
                             {"modified_z", "1 (robust sigmas of log10 from the median)"}};
  return {{"foglab_version", std::string(version())},
          {"inputs", files},
          {"options",
           {{"units", c.analyze.input.units},
            {"channel", c.analyze.input.channel},
            {"taus", c.analyze.taus},
            {"temp_degree", c.analyze.temp_degree},
            {"outlier_z", c.outlier_z}}},
          {"units_analysed", fleet.rows.size()},
          {"units_kept_from_earlier_run", fleet.reused},
          {"units", units},
          {"fleet",
           {{"parameters", parameters},
            {"outliers", outliers},
            {"classes", fleet.summary.classes},
            {"about",
             "median and spread of log10 of each parameter over the units where it was resolved; "
             "a unit stands out when its modified z-score 0.6745 (log10 x - median)/MAD exceeds "
             "outlier_z in magnitude (Iglewicz and Hoaglin 1993)"}}},
          {"failures", failures},
          {"units_of", units_of}};
}

/// One unit analysed: its JSON text. Throws as the analysis does.
std::string analyse_unit(const BatchCommand& c, const std::string& file, const std::string& channel,
                         const model::AnalysisOptions& options, std::optional<io::ImuRecord>& bag) {
  std::vector<std::string> notes;
  const CollectNotes collect(notes);
  AnalyzeCommand one = c.analyze;
  one.input.path = file;
  one.input.channel = channel;
  one.input.units = units_of(c, file);
  io::Series series;
  const bool from_bag = is_bag_file(c, file);
  if (from_bag) {
    if (!bag) {
      io::BagReadOptions read;
      read.topic = c.analyze.topic;
      read.sample_rate_hz = c.analyze.input.sample_rate_hz;
      read.max_samples =
          c.analyze.input.max_samples ? *c.analyze.input.max_samples : default_max_samples();
      bag = io::read_imu_bag(file, read);
    }
    series = bag_axis_series(*bag, channel, file, c.analyze.input.sample_rate_hz.has_value());
  } else {
    series = load_input(one.input, true);  // analyse_series() leaves the NaN rows out
  }
  ChannelAnalysis a = analyse_series(one, std::move(series), options, false, !from_bag);
  a.json_input.notes.insert(a.json_input.notes.begin(), notes.begin(), notes.end());
  return json_text(analysis_json(a.result, a.json_input, options));
}

}  // namespace

std::vector<BatchFile> batch_files(const std::vector<std::string>& inputs) {
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (input == "-" || (io::is_stream(input) && !fs::is_directory(input, ec))) {
      throw UsageError(fmt::format(
          "INPUTS: '{}' is read once (standard input, a FIFO or a device); batch reads files",
          input));
    }
  }
  const std::vector<std::string> files = expand_inputs(inputs);
  const std::vector<std::string> names = unit_names(files);
  std::vector<BatchFile> out;
  for (std::size_t k = 0; k < files.size(); ++k) out.push_back({files[k], names[k]});
  return out;
}

model::AnalysisOptions batch_analysis_options(const BatchCommand& c,
                                              const std::string& first_file) {
  if (!(c.outlier_z > 0.0) || !std::isfinite(c.outlier_z)) {
    throw UsageError(fmt::format("--outlier-z must be a positive number, got {}", c.outlier_z));
  }
  AnalyzeCommand probe = c.analyze;
  probe.input.path = first_file;
  return checked_analysis_options(probe);
}

std::vector<UnitOutcome> batch_file_units(const BatchCommand& c, const BatchFile& file,
                                          const model::AnalysisOptions& options,
                                          const std::string& units_dir) {
  const std::vector<std::string> channels = unit_channels(c, file.path);
  std::vector<UnitOutcome> outcomes;
  std::optional<io::ImuRecord> bag;
  for (const std::string& channel : channels) {
    UnitOutcome u;
    u.name = unit_name(file, channels, channel);
    u.channel = channel;
    u.input = channel.empty() ? file.path : file.path + " channel " + channel;
    const std::string json_path =
        units_dir.empty() ? "" : unit_json_path(units_dir, u.name);
    if (!json_path.empty() && !c.redo && reusable(c, file.path, channel, json_path)) {
      u.kept = true;
      outcomes.push_back(std::move(u));
      continue;
    }
    try {
      u.json = analyse_unit(c, file.path, channel, options, bag);
      if (!json_path.empty()) {
        write_text_file(json_path, u.json);
        u.json.clear();  // on disk now: a fleet of thousands need not hold every document
      }
    } catch (const UsageError& e) {
      u.error = in_cli_terms(e.what());
      u.exit_code = 2;
    } catch (const DataError& e) {
      u.error = in_cli_terms(e.what());
      u.exit_code = 3;
    } catch (const std::bad_alloc&) {
      u.error =
          "out of memory: the record and its analysis need more memory than this process may "
          "use (fewer --workers)";
      u.exit_code = 1;
    } catch (const std::exception& e) {
      u.error = fmt::format("internal error: {}", e.what());
      u.exit_code = 1;
    }
    if (!u.error.empty()) u.json.clear();
    outcomes.push_back(std::move(u));
  }
  return outcomes;
}

bool batch_file_kept(const BatchCommand& c, const BatchFile& file, const std::string& units_dir) {
  const std::vector<std::string> channels = unit_channels(c, file.path);
  return std::all_of(channels.begin(), channels.end(), [&](const std::string& channel) {
    return reusable(c, file.path, channel,
                    unit_json_path(units_dir, unit_name(file, channels, channel)));
  });
}

BatchSummary run_batch(const BatchCommand& c) {
  if (c.out.empty()) throw UsageError("--out: the batch's folder is required");
  const std::vector<BatchFile> files = batch_files(c.inputs);
  const model::AnalysisOptions options = batch_analysis_options(c, files.front().path);
  std::error_code ec;
  if (fs::exists(c.out, ec) && !fs::is_directory(c.out, ec)) {
    throw UsageError(fmt::format("--out '{}': is a file, not a folder", c.out));
  }
  for (const BatchFile& f : files) {
    const RunPath inputs[] = {{"INPUTS", f.path}};
    const RunPath outputs[] = {{"--out", (fs::path(c.out) / "fleet.json").string()}};
    check_outputs(inputs, outputs);
  }
  const fs::path units_dir = fs::path(c.out) / "units";
  fs::create_directories(units_dir, ec);
  if (ec) cannot_write(units_dir.string(), ec.message());
  note(
      fmt::format("{} recording(s); each unit's result in '{}'", files.size(), units_dir.string()));

  std::vector<std::vector<UnitOutcome>> outcomes(files.size());
  std::mutex mutex;  // the progress count
  std::size_t done = 0;
  auto job = [&](std::size_t k) {
    outcomes[k] = batch_file_units(c, files[k], options, units_dir.string());
    const std::lock_guard<std::mutex> lock(mutex);
    ++done;
    for (const UnitOutcome& u : outcomes[k]) {
      progress(fmt::format("[{}/{} files] {}: {}", done, files.size(), u.name,
                           u.kept            ? "kept"
                           : u.error.empty() ? "analysed"
                                             : "failed: " + u.error));
    }
  };
  const auto errors =
      model::run_work_queue(files.size(), job, c.workers, model::OnFailure::keep_going);

  // The fleet, in the order of the inputs.
  BatchSummary summary;
  summary.files = files.size();
  report::FleetReport fleet;
  fleet.outlier_z = c.outlier_z;
  std::map<std::string, std::string> json_of;
  for (std::size_t k = 0; k < files.size(); ++k) {
    if (errors[k]) {  // not a record's failure (those are outcomes): the file's listing
      UnitOutcome u;
      u.input = files[k].path;
      u.exit_code = 1;
      try {
        std::rethrow_exception(errors[k]);
      } catch (const std::exception& e) {
        u.error = in_cli_terms(e.what());
      }
      summary.failures.push_back(std::move(u));
      continue;
    }
    for (const UnitOutcome& u : outcomes[k]) {
      if (!u.error.empty()) {
        summary.failures.push_back(u);
        continue;
      }
      const std::string json_path = unit_json_path(units_dir.string(), u.name);
      try {
        fleet.rows.push_back(row_of(u.name, files[k].path, json_path));
        json_of[u.name] = fs::relative(json_path, c.out).string();
        ++(u.kept ? summary.kept : summary.analysed);
      } catch (const std::exception& e) {
        UnitOutcome bad = u;
        bad.error = fmt::format("'{}': not an analyze --json document: {}", json_path, e.what());
        bad.exit_code = 3;
        summary.failures.push_back(std::move(bad));
      }
    }
  }
  fleet.reused = summary.kept;
  for (const UnitOutcome& u : summary.failures) {
    fleet.failures.push_back({u.input, u.error, u.exit_code});
  }
  fleet.title = fmt::format("Fleet of {} gyroscope(s)", fleet.rows.size());
  model::FleetOptions fleet_options;
  fleet_options.outlier_z = c.outlier_z;
  std::vector<std::string> parameters;
  for (const report::FleetParameter& p : report::kFleetParameters) parameters.push_back(p.name);
  fleet.summary =
      model::summarize_fleet(report::fleet_units(fleet.rows), parameters, fleet_options);

  progress("drawing the fleet's plots");
  report::ReportOptions report_options;
  report_options.plots = !c.no_plots;
  std::vector<std::string> paths;
  for (const BatchFile& f : files) paths.push_back(f.path);
  const std::string markdown = report::fleet_markdown(fleet);
  const std::string html = report::fleet_html(fleet, report_options);
  const std::string csv = report::fleet_csv(fleet);
  summary.fleet_json = json_text(fleet_json(c, fleet, paths, json_of));
  const fs::path out(c.out);
  write_text_file((out / "fleet.md").string(), markdown);
  write_text_file((out / "fleet.csv").string(), csv);
  write_text_file((out / "fleet.html").string(), html);
  write_text_file((out / "fleet.json").string(), summary.fleet_json);  // last
  summary.units = fleet.rows.size();
  summary.outliers = fleet.summary.outliers;
  return summary;
}

namespace {

void run(const BatchCommand& c) {
  const BatchSummary s = run_batch(c);
  std::cout << fmt::format(
      "{} unit(s) from {} recording(s): {} analysed, {} kept from an earlier run, {} failed\n",
      s.units, s.files, s.analysed, s.kept, s.failures.size());
  for (const model::FleetOutlier& o : s.outliers) {
    std::cout << fmt::format("stands out: {} {} = {:.4g} (x{:.3g} the fleet's median, z {:+.1f})\n",
                             o.unit, o.parameter, o.value, o.times_median, o.modified_z);
  }
  const fs::path out(c.out);
  std::cout << fmt::format("fleet report: {}, fleet.md, fleet.csv, fleet.json\n",
                           (out / "fleet.html").string());
  if (!s.failures.empty()) {
    throw DataError(fmt::format(
        "{} of {} record(s) failed (listed in '{}'); the fleet report holds the others; a "
        "rerun analyses only what is missing",
        s.failures.size(), s.failures.size() + s.units, (out / "fleet.md").string()));
  }
}

}  // namespace

std::function<void()> register_batch(CLI::App& app) {
  auto c = std::make_shared<BatchCommand>();
  CLI::App* cmd = app.add_subcommand(
      "batch",
      "analyse a fleet of gyros: many recordings in parallel, each unit's analyze --json, and the "
      "fleet report (spread of N, B, K and bias instability, units that stand out, classes)");
  cmd->add_option("INPUTS", c->inputs,
                  "recordings: files, folders (their .mat/.csv/.tsv/.txt/.dat/.f32/.f64/.bag) or "
                  "quoted globs ('runs/*.mat')")
      ->required();
  cmd->add_option("--out", c->out,
                  "folder for units/NAME.json (each unit as analyze --json writes it) and "
                  "fleet.html, fleet.md, fleet.csv, fleet.json (created if needed; a rerun keeps "
                  "the units already there)")
      ->required();
  add_reading_options(*cmd, c->analyze.input);
  cmd->add_option("--topic", c->analyze.topic, "ROS bags: the sensor_msgs/Imu topic");
  cmd->add_option("--temp", c->analyze.temp_channel,
                  "temperature channel [degC]; default: the one paired with the rate channel");
  cmd->add_option("--temp-degree", c->analyze.temp_degree,
                  "degree of the temperature polynomial: auto, 0, 1, 2 or 3")
      ->capture_default_str();
  cmd->add_option("--taus", c->analyze.taus, "Allan tau grid (as analyze)")->capture_default_str();
  cmd->add_option("--workers", c->workers,
                  "recordings analysed at once (default: one per core; fewer for long records "
                  "that do not fit in memory together)");
  cmd->add_option("--outlier-z", c->outlier_z,
                  "a unit stands out beyond this modified z-score of log10 of a parameter")
      ->capture_default_str();
  cmd->add_flag("--redo", c->redo, "analyse every unit again, even those already in --out");
  cmd->add_flag("--no-plots", c->no_plots, "write the HTML report without plots (no gnuplot)");
  return [c] { run(*c); };
}

}  // namespace foglab::cli
