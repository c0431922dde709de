// foglab — the Python module `foglab._foglab` (pybind11): the library's statistics, analysis,
// generator and readers on numpy arrays. python/foglab/__init__.py re-exports it and adds the
// pure-Python parts (compat.py: AllanTools's calling conventions).
//
// Arrays in: a C-contiguous float64 array is read in place (a span over numpy's buffer), any
// other is converted once by pybind11. Arrays out: each result vector is moved into the numpy
// array that owns it (a capsule frees it), never copied. The GIL is released while the
// library computes. Errors: foglab::UsageError is a ValueError (pybind11 maps its base,
// std::invalid_argument), foglab::DataError is foglab.DataError (a RuntimeError); the message
// is the library's.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "analysis_output.h"
#include "batch.h"
#include "cli_common.h"
#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "foglab/core/units.h"
#include "foglab/core/version.h"
#include "foglab/io/reader.h"
#include "foglab/io/rosbag.h"
#include "foglab/model/analysis.h"
#include "foglab/sim/generator.h"
#include "foglab/sim/presets.h"
#include "foglab/stats/allan.h"
#include "foglab/stats/psd.h"
#include "foglab/stats/tau_grid.h"
#include "foglab/stats/time_error.h"

namespace py = pybind11;

namespace foglab::python {
namespace {

using InputArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The samples of a one-dimensional array, in place. With `nan_is_missing` a NaN is a
// missing sample, for io::drop_missing_samples() to make a gap of.
std::span<const double> samples_of(const InputArray& a, const char* name,
                                   bool nan_is_missing = false) {
  if (a.ndim() != 1) {
    throw UsageError(std::string(name) + " must be a one-dimensional array (got " +
                     std::to_string(a.ndim()) + " dimensions)");
  }
  const std::span<const double> samples(a.data(), static_cast<std::size_t>(a.shape(0)));
  // As the file readers do: a value that is not finite is refused by its index, before it
  // turns every statistic into NaN.
  const std::size_t index =
      nan_is_missing
          ? static_cast<std::size_t>(std::find_if(samples.begin(), samples.end(),
                                                  [](double v) { return std::isinf(v); }) -
                                     samples.begin())
          : first_non_finite(samples);
  if (index < samples.size()) {
    const double bad = samples[index];
    throw DataError(std::string(name) + "[" + std::to_string(index) + "] is " +
                    (std::isnan(bad) ? "nan"
                     : bad > 0       ? "inf"
                                     : "-inf") +
                    (nan_is_missing ? ": every sample must be a finite number or NaN (missing)"
                                    : ": every sample must be a finite number"));
  }
  return samples;
}

// A numpy array that takes over `v` (no copy).
template <typename T>
py::array_t<T> to_numpy(std::vector<T>&& v) {
  auto* owned = new std::vector<T>(std::move(v));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(static_cast<py::ssize_t>(owned->size()), owned->data(), free_when_done);
}

// taus: "octave", "decade", "all", "per-decade" (with per_decade), or a sequence of taus [s].
stats::TauGrid tau_grid(const std::variant<std::string, std::vector<double>>& taus,
                        std::int64_t min_clusters, int per_decade) {
  stats::TauGrid grid;
  grid.min_clusters = min_clusters;
  grid.per_decade = per_decade;
  if (const auto* list = std::get_if<std::vector<double>>(&taus)) {
    grid.kind = stats::TauGridKind::list;
    grid.taus_s = *list;
    return grid;
  }
  const std::string& name = std::get<std::string>(taus);
  if (name == "octave") {
    grid.kind = stats::TauGridKind::octave;
  } else if (name == "decade") {
    grid.kind = stats::TauGridKind::decade;
  } else if (name == "all") {
    grid.kind = stats::TauGridKind::all;
  } else if (name == "per-decade") {
    grid.kind = stats::TauGridKind::per_decade;
  } else {
    throw UsageError("taus='" + name +
                     "': expected 'octave', 'decade', 'all', 'per-decade' or a sequence of "
                     "taus in seconds");
  }
  return grid;
}

// The result of allan(): numpy arrays, one entry per tau.
struct PyAllanResult {
  std::string kind;
  std::string input;
  double sample_rate_hz = 0.0;
  std::int64_t phase_points = 0;
  py::array_t<std::int64_t> m, n, segment_points;
  py::array_t<double> tau_s, dev, edf, ci68_low, ci68_high, ci95_low, ci95_high;
  py::array_t<int> alpha;
  std::vector<std::string> alpha_method;
};

PyAllanResult to_python(stats::AllanResult&& r) {
  PyAllanResult p;
  p.kind = std::string(stats::to_string(r.kind));
  p.input = std::string(to_string(r.input));
  p.sample_rate_hz = r.sample_rate_hz;
  p.phase_points = r.phase_points;
  for (const stats::AlphaMethod& method : r.alpha_method) {
    p.alpha_method.push_back(stats::to_string(method));
  }
  p.m = to_numpy(std::move(r.m));
  p.n = to_numpy(std::move(r.n));
  p.segment_points = to_numpy(std::move(r.segment_points));
  p.tau_s = to_numpy(std::move(r.tau_s));
  p.dev = to_numpy(std::move(r.dev));
  p.edf = to_numpy(std::move(r.edf));
  p.ci68_low = to_numpy(std::move(r.ci68_low));
  p.ci68_high = to_numpy(std::move(r.ci68_high));
  p.ci95_low = to_numpy(std::move(r.ci95_low));
  p.ci95_high = to_numpy(std::move(r.ci95_high));
  p.alpha = to_numpy(std::move(r.alpha));
  return p;
}

PyAllanResult allan(const InputArray& data, double rate, const std::string& kind,
                    const std::variant<std::string, std::vector<double>>& taus,
                    const std::string& input, std::int64_t min_clusters, int per_decade,
                    bool confidence, bool bias_correction, const std::string& noise_id) {
  const std::span<const double> samples = samples_of(data, "data");
  stats::AllanOptions options;
  options.kind = stats::allan_kind_from_string(kind);
  options.grid = tau_grid(taus, min_clusters, per_decade);
  options.confidence = confidence;
  options.bias_correction = bias_correction;
  options.noise_rules = stats::noise_rules_from_string(noise_id);
  const InputKind input_kind_value = input_kind_from_string(input);
  stats::AllanResult r;
  {
    py::gil_scoped_release release;
    r = stats::allan_deviation(samples, rate, input_kind_value, options);
  }
  return to_python(std::move(r));
}

// time_error(): MTIE or TIE rms on a tau grid, as a dict of numpy arrays.
py::dict time_error(const InputArray& data, double rate, const std::string& kind,
                    const std::variant<std::string, std::vector<double>>& taus,
                    const std::string& input, std::int64_t min_clusters, int per_decade) {
  const std::span<const double> samples = samples_of(data, "data");
  const stats::TimeErrorKind which = stats::time_error_kind_from_string(kind);
  const stats::TauGrid grid = tau_grid(taus, min_clusters, per_decade);
  const InputKind input_kind_value = input_kind_from_string(input);
  stats::TimeErrorResult r;
  {
    py::gil_scoped_release release;
    r = stats::time_error(samples, rate, input_kind_value, which, grid);
  }
  py::dict d;
  d["kind"] = std::string(stats::to_string(r.kind));
  d["input"] = std::string(to_string(r.input));
  d["sample_rate_hz"] = r.sample_rate_hz;
  d["angle_points"] = r.angle_points;
  d["m"] = to_numpy(std::move(r.m));
  d["n"] = to_numpy(std::move(r.n));
  d["tau_s"] = to_numpy(std::move(r.tau_s));
  d["value"] = to_numpy(std::move(r.value));
  return d;
}

py::dict psd(const InputArray& data, double rate, std::size_t segment_length, double overlap) {
  const std::span<const double> samples = samples_of(data, "data");
  stats::WelchOptions options;
  options.segment_length = segment_length;
  options.overlap = overlap;
  stats::PsdResult r;
  {
    py::gil_scoped_release release;
    r = stats::welch_psd(samples, rate, options);
  }
  py::dict d;
  d["sample_rate_hz"] = r.sample_rate_hz;
  d["segment_length"] = r.segment_length;
  d["segments"] = r.segments;
  d["resolution_hz"] = r.resolution_hz;
  d["frequency_hz"] = to_numpy(std::move(r.frequency_hz));
  d["psd"] = to_numpy(std::move(r.psd));
  d["sqrt_psd"] = to_numpy(std::move(r.sqrt_psd));
  return d;
}

// Gaps as (before_sample, missing) pairs, the form read() returns them in.
std::vector<Gap> gaps_of(const std::vector<std::pair<std::int64_t, std::int64_t>>& pairs) {
  std::vector<Gap> gaps;
  gaps.reserve(pairs.size());
  for (const auto& [before_sample, missing] : pairs) gaps.push_back({before_sample, missing});
  return gaps;
}

// analyze(): the JSON document of `foglab analyze --json` (docs/json.md), as Python objects.
// As the CLI reads a file: `gaps` are those of the samples given (read()'s), a NaN sample (or
// temperature) is a missing row, left out and made a gap, and nothing is interpolated.
py::object analyze(const InputArray& rate, double rate_hz,
                   const std::optional<InputArray>& temperature, const std::string& units,
                   const std::string& channel,
                   const std::vector<std::pair<std::int64_t, std::int64_t>>& gaps,
                   bool nan_is_missing, double max_missing_percent) {
  model::AnalysisOptions options;
  options.max_missing_share = cli::max_missing_share_of(max_missing_percent, "max_missing_percent");
  const std::span<const double> samples = samples_of(rate, "rate", nan_is_missing);
  const SampleUnit unit = rate_unit_from_string(units);
  // The analysis consumes its record: a copy, in the internal unit, with room for the angle
  // record's one point more.
  std::vector<double> values;
  values.reserve(samples.size() + 1);
  const double factor = to_internal_unit(unit);
  for (const double v : samples) values.push_back(v * factor);
  std::vector<double> temperature_c;
  if (temperature) {
    const std::span<const double> t = samples_of(*temperature, "temperature", nan_is_missing);
    if (t.size() != samples.size()) {
      throw UsageError("temperature has " + std::to_string(t.size()) + " samples, rate " +
                       std::to_string(samples.size()) + ": they must pair one to one");
    }
    temperature_c.assign(t.begin(), t.end());
  }
  io::Series series;
  series.path = "<array>";
  series.channel = channel;
  series.sample_rate_hz = rate_hz;
  series.sample_rate_source = io::SampleRateSource::option;
  series.gaps = gaps_of(gaps);
  check_gaps(series.gaps, static_cast<std::int64_t>(samples.size()), "gaps");
  series.values = std::move(values);
  if (nan_is_missing) io::drop_missing_samples(series, temperature ? &temperature_c : nullptr);
  cli::AnalysisJsonInput json_input;
  json_input.units = units;
  json_input.temperature_channel = temperature ? "temperature" : "";
  std::string text;
  {
    py::gil_scoped_release release;
    json_input.input = cli::input_json(series);
    json_input.input["samples"] = series.values.size();
    if (!temperature) json_input.record_mean_deg_h = compensated_mean(series.values);
    model::AnalysisResult result =
        model::analyze(series.values, temperature_c, rate_hz, options, series.gaps);
    nlohmann::json document = cli::analysis_json(result, json_input, options);
    if (sensor_of(unit) == Sensor::accelerometer) {
      document = cli::accelerometer_json(std::move(document));
    }
    text = document.dump();
  }
  return py::module_::import("json").attr("loads")(text);
}

py::list gaps_list(const std::vector<Gap>& gaps) {
  py::list list;
  for (const Gap& g : gaps) list.append(py::make_tuple(g.before_sample, g.missing_samples));
  return list;
}

// read(): one channel of a file as analyze reads it, or the six channels of a ROS bag.
py::dict read_file(const std::string& path, const std::string& channel,
                   const std::optional<double>& rate_hz, const std::string& units,
                   const std::string& topic, bool nan_is_missing) {
  py::dict d;
  if (io::has_bag_extension(path)) {
    io::BagReadOptions options;
    options.topic = topic;
    options.sample_rate_hz = rate_hz;
    io::ImuRecord r;
    {
      py::gil_scoped_release release;
      r = io::read_imu_bag(path, options);
    }
    d["path"] = r.path;
    d["topic"] = r.topic;
    d["frame_id"] = r.frame_id;
    d["sample_rate_hz"] = r.sample_rate_hz;
    d["start_time_s"] = r.start_time_s;
    d["gaps"] = gaps_list(r.gaps);
    d["notes"] = english(r.notes);
    static constexpr const char* kAxes[] = {"x", "y", "z"};
    for (std::size_t j = 0; j < 3; ++j) {
      d[py::str(std::string("gyro_") + kAxes[j] + "_rad_s")] =
          to_numpy(std::move(r.angular_velocity_rad_s[j]));
      d[py::str(std::string("accel_") + kAxes[j] + "_m_s2")] =
          to_numpy(std::move(r.linear_acceleration_m_s2[j]));
    }
    return d;
  }
  if (!topic.empty()) throw UsageError("topic='" + topic + "': '" + path + "' is not a ROS bag");
  io::ReadOptions options;
  options.channel = channel;
  options.sample_rate_hz = rate_hz;
  options.unit = rate_unit_from_string(units);
  options.nan_is_missing = nan_is_missing;
  io::Series series;
  {
    py::gil_scoped_release release;
    series = io::read_series(path, options);
    if (nan_is_missing) io::drop_missing_samples(series, nullptr);
  }
  d["path"] = series.path;
  d["channel"] = series.channel;
  d["unit"] = std::string(to_string(internal_unit(sensor_of(options.unit))));
  d["sample_rate_hz"] = series.sample_rate_hz;
  d["start_time_s"] = series.start_time_s;
  d["gaps"] = gaps_list(series.gaps);
  d["channels"] = series.available_channels;
  d["notes"] = english(series.notes);
  d["missing_value_rows"] = series.nan_left_out.samples;
  d["values"] = to_numpy(std::move(series.values));
  return d;
}

// generate(): a synthetic static recording and its truth, from a preset and/or the terms.
py::dict generate(const std::string& preset, const std::optional<double>& rate_hz, double hours,
                  std::uint64_t seed, std::uint64_t stream, const std::string& temperature,
                  const py::dict& terms) {
  sim::ErrorModel model;
  double fs = 0.0;
  if (!preset.empty()) {
    const sim::Preset& p = sim::find_preset(preset);
    model = p.model;
    fs = p.sample_rate_hz;
  }
  // The model's fields by keyword, in the units of `foglab generate`'s options.
  using Field = double& (*)(sim::ErrorModel&);
  static const std::pair<std::string_view, Field> kTerms[] = {
      {"N", [](sim::ErrorModel& m) -> double& { return m.noise.N; }},
      {"B", [](sim::ErrorModel& m) -> double& { return m.noise.B; }},
      {"K", [](sim::ErrorModel& m) -> double& { return m.noise.K; }},
      {"R", [](sim::ErrorModel& m) -> double& { return m.noise.R; }},
      {"Q", [](sim::ErrorModel& m) -> double& { return m.noise.Q; }},
      {"gm_sigma", [](sim::ErrorModel& m) -> double& { return m.noise.gm_sigma; }},
      {"gm_tc", [](sim::ErrorModel& m) -> double& { return m.noise.gm_tc; }},
      {"bias", [](sim::ErrorModel& m) -> double& { return m.bias; }},
      {"input_rate", [](sim::ErrorModel& m) -> double& { return m.input_rate; }},
  };
  for (const auto& [key, value] : terms) {
    const std::string name = py::str(key);
    const auto* term = std::find_if(std::begin(kTerms), std::end(kTerms),
                                    [&](const auto& t) { return t.first == name; });
    if (term == std::end(kTerms)) {
      std::string names;
      for (const auto& t : kTerms) {
        if (!names.empty()) names += ", ";
        names += t.first;
      }
      throw UsageError("generate(" + name + "=...): expected one of " + names);
    }
    term->second(model) = value.cast<double>();
  }
  if (rate_hz) fs = *rate_hz;
  if (!(fs > 0.0)) throw UsageError("generate(): give rate_hz (no preset sets it)");
  sim::GeneratorOptions options;
  options.sample_rate_hz = fs;
  options.duration_s = hours * 3600.0;
  options.seed = seed;
  options.stream = stream;
  const sim::TemperatureProfile profile = sim::parse_temperature(temperature);
  sim::Recording r;
  {
    py::gil_scoped_release release;
    r = sim::generate(model, profile, options);
  }
  py::dict d;
  d["sample_rate_hz"] = r.sample_rate_hz;
  d["time_s"] = to_numpy(std::move(r.time_s));
  d["rate_deg_h"] = to_numpy(std::move(r.rate_deg_h));
  d["temperature_c"] = to_numpy(std::move(r.temperature_c));
  d["truth"] = py::module_::import("json").attr("loads")(cli::model_json(model).dump());
  return d;
}

// ---- a fleet (foglab batch) -----------------------------------------------------------

// The batch options of the keywords: those of `foglab batch` (docs/cli.md), snake_case.
cli::BatchCommand batch_command(const py::kwargs& options) {
  cli::BatchCommand c;
  for (const auto& [key, value] : options) {
    const std::string k = py::str(key);
    if (value.is_none()) continue;
    if (k == "channel") {
      c.analyze.input.channel = value.cast<std::string>();
    } else if (k == "rate_hz") {
      c.analyze.input.sample_rate_hz = value.cast<double>();
    } else if (k == "units") {
      c.analyze.input.units = value.cast<std::string>();
      c.analyze.input.units_given = true;
    } else if (k == "format") {
      c.analyze.input.format = value.cast<std::string>();
    } else if (k == "time") {
      c.analyze.input.time_channel = value.cast<std::string>();
    } else if (k == "decimal_comma") {
      c.analyze.input.decimal_comma = value.cast<bool>();
    } else if (k == "topic") {
      c.analyze.topic = value.cast<std::string>();
    } else if (k == "temp") {
      c.analyze.temp_channel = value.cast<std::string>();
    } else if (k == "temp_degree") {
      c.analyze.temp_degree = py::str(value);
    } else if (k == "taus") {
      c.analyze.taus = value.cast<std::string>();
    } else if (k == "workers") {
      c.workers = value.cast<unsigned>();
    } else if (k == "outlier_z") {
      c.outlier_z = value.cast<double>();
    } else if (k == "redo") {
      c.redo = value.cast<bool>();
    } else if (k == "plots") {
      c.no_plots = !value.cast<bool>();
    } else {
      throw UsageError("unknown option '" + k +
                       "'; the options are channel, rate_hz, units, format, time, "
                       "decimal_comma, topic, temp, temp_degree, taus, workers, outlier_z, redo, "
                       "plots");
    }
  }
  return c;
}

py::list batch_files(const std::vector<std::string>& inputs) {
  py::list out;
  for (const cli::BatchFile& f : cli::batch_files(inputs))
    out.append(py::make_tuple(f.path, f.name));
  return out;
}

// One file's units analysed here, nothing written (a Dask task): a dict per unit.
py::list batch_file_units(const std::string& path, const std::string& name,
                          const py::kwargs& options) {
  const cli::BatchCommand c = batch_command(options);
  std::vector<cli::UnitOutcome> units;
  {
    py::gil_scoped_release release;
    const model::AnalysisOptions analysis = cli::batch_analysis_options(c, path);
    units = cli::batch_file_units(c, {path, name}, analysis, "");
  }
  py::list out;
  for (const cli::UnitOutcome& u : units) {
    py::dict d;
    d["name"] = u.name;
    d["channel"] = u.channel;
    d["input"] = u.input;
    d["json"] = u.json;
    d["error"] = u.error;
    d["exit_code"] = u.exit_code;
    out.append(d);
  }
  return out;
}

// Whether a file's units all stand in `units_dir` from an earlier run (batch's rule).
bool batch_file_kept(const std::string& path, const std::string& name,
                     const std::string& units_dir, const py::kwargs& options) {
  const cli::BatchCommand c = batch_command(options);
  py::gil_scoped_release release;
  return cli::batch_file_kept(c, {path, name}, units_dir);
}

// The whole batch, as `foglab batch` runs it: the fleet.json document.
py::object batch(const std::vector<std::string>& inputs, const std::string& out,
                 const py::kwargs& options) {
  cli::BatchCommand c = batch_command(options);
  c.inputs = inputs;
  c.out = out;
  std::string text;
  {
    py::gil_scoped_release release;
    text = cli::run_batch(c).fleet_json;
  }
  return py::module_::import("json").attr("loads")(text);
}

}  // namespace
}  // namespace foglab::python

PYBIND11_MODULE(_foglab, m) {
  using namespace foglab::python;
  namespace fl = foglab;
  m.doc() = "foglab: stability statistics and noise identification of gyros and IMUs (C++ core)";
  m.attr("__version__") = std::string(fl::version());

  py::register_exception<fl::DataError>(m, "DataError", PyExc_RuntimeError);

  py::class_<PyAllanResult>(m, "AllanResult",
                            "One statistic over a tau grid; every array has one entry per tau.")
      .def_readonly("kind", &PyAllanResult::kind)
      .def_readonly("input", &PyAllanResult::input)
      .def_readonly("sample_rate_hz", &PyAllanResult::sample_rate_hz)
      .def_readonly("phase_points", &PyAllanResult::phase_points)
      .def_readonly("segment_points", &PyAllanResult::segment_points)
      .def_readonly("m", &PyAllanResult::m, "averaging factors, tau = m / rate")
      .def_readonly("tau_s", &PyAllanResult::tau_s, "[s]")
      .def_readonly("dev", &PyAllanResult::dev, "in the data's unit (TDEV: times s)")
      .def_readonly("n", &PyAllanResult::n, "terms in each estimate")
      .def_readonly("alpha", &PyAllanResult::alpha, "noise exponent, S_y(f) ~ f^alpha")
      .def_readonly("alpha_method", &PyAllanResult::alpha_method)
      .def_readonly("edf", &PyAllanResult::edf, "equivalent degrees of freedom")
      .def_readonly("ci68_low", &PyAllanResult::ci68_low)
      .def_readonly("ci68_high", &PyAllanResult::ci68_high)
      .def_readonly("ci95_low", &PyAllanResult::ci95_low)
      .def_readonly("ci95_high", &PyAllanResult::ci95_high)
      .def("__repr__", [](const PyAllanResult& r) {
        return "<foglab.AllanResult " + r.kind + " of " + std::to_string(r.phase_points) +
               " phase points, " + std::to_string(r.tau_s.size()) + " taus>";
      });

  m.def("allan", &allan, py::arg("data"), py::arg("rate"), py::arg("kind") = "oadev",
        py::arg("taus") = "octave", py::arg("input") = "rate", py::arg("min_clusters") = 10,
        py::arg("per_decade") = 10, py::arg("confidence") = true, py::arg("bias_correction") = true,
        py::arg("noise_id") = "foglab",
        "One stability statistic (adev, oadev, mdev, hdev, ohdev, tdev, totdev, mtotdev, "
        "ttotdev, htotdev, theo1) of `data` sampled at `rate` [Hz], with noise identification, "
        "edf and 68/95 % intervals. bias_correction: HTOTDEV divided by Riley's bias factor "
        "(as Stable32). noise_id: 'foglab' or 'stable32' (Stable32's alpha, tau for tau).");
  m.def("time_error", &time_error, py::arg("data"), py::arg("rate"), py::arg("kind") = "mtie",
        py::arg("taus") = "octave", py::arg("input") = "rate", py::arg("min_clusters") = 10,
        py::arg("per_decade") = 10,
        "MTIE or TIE rms ('mtie', 'tierms') of `data` sampled at `rate` [Hz] on a tau grid, as "
        "`foglab allan --kind mtie` computes it: a dict of tau_s, value (the angle's unit: the "
        "rate's times s), n (windows) and m. A rate record is integrated with its bias kept.");
  m.def(
      "max_factor",
      [](const std::string& kind, std::int64_t phase_points) {
        return fl::stats::max_factor(fl::stats::allan_kind_from_string(kind), phase_points);
      },
      py::arg("kind"), py::arg("phase_points"),
      "The largest averaging factor m at which `kind` has a term for that many phase points.");
  m.def("psd", &psd, py::arg("data"), py::arg("rate"), py::arg("segment_length") = 0,
        py::arg("overlap") = 0.5,
        "Welch's two-sided PSD [(unit)^2/Hz] of `data` sampled at `rate` [Hz] (Hann window).");
  m.def("read", &read_file, py::arg("path"), py::arg("channel") = "",
        py::arg("rate_hz") = py::none(), py::arg("units") = "deg/h", py::arg("topic") = "",
        py::arg("nan_is_missing") = true,
        "One channel of a MAT, text or raw file as `foglab analyze` reads it (values in deg/h, "
        "or m/s^2 for an acceleration unit), or the six channels of a ROS bag's "
        "sensor_msgs/Imu topic (rad/s and m/s^2); `gaps` lists (before_sample, missing). "
        "A NaN sample (an empty text cell) is a missing one, its row left out and counted in "
        "`missing_value_rows`, runs of them gaps; nan_is_missing=False makes it a DataError.");
  m.def(
      "generate",
      [](const std::string& preset, const std::optional<double>& rate_hz, double hours,
         std::uint64_t seed, std::uint64_t stream, const std::string& temperature,
         const py::kwargs& terms) {
        return generate(preset, rate_hz, hours, seed, stream, temperature, terms);
      },
      py::arg("preset") = "", py::arg("rate_hz") = py::none(), py::arg("hours") = 1.0,
      py::arg("seed") = 1, py::arg("stream") = 0, py::arg("temperature") = "const",
      "A synthetic static recording (the generator of `foglab generate`): a preset and/or the "
      "terms N, B, K, R, Q, gm_sigma, gm_tc, bias, input_rate as keywords (deg/h units); "
      "returns time_s, rate_deg_h, temperature_c and the truth.");
  m.def("batch", &batch, py::arg("inputs"), py::arg("out"),
        "A fleet, as `foglab batch INPUTS --out OUT` analyses it (docs/cli.md#batch): files, "
        "folders or globs; options channel, rate_hz, units, format, time, decimal_comma, topic, "
        "temp, temp_degree, taus, workers, outlier_z, redo, plots. Writes OUT/units/*.json and "
        "OUT/fleet.{json,csv,md,html}; returns the fleet.json document. A record that fails is "
        "listed under 'failures', not raised.");
  m.def("_batch_files", &batch_files, py::arg("inputs"),
        "The files of a batch's inputs with their units' names: [(path, name)].");
  m.def("_batch_file_units", &batch_file_units, py::arg("path"), py::arg("name"),
        "One file's units analysed (nothing written): [{name, channel, input, json, error, "
        "exit_code}].");
  m.def("_batch_file_kept", &batch_file_kept, py::arg("path"), py::arg("name"),
        py::arg("units_dir"),
        "Whether every unit of a file stands in units_dir from an earlier run (what batch "
        "keeps).");
  m.def("analyze", &analyze, py::arg("rate"), py::arg("rate_hz"),
        py::arg("temperature") = py::none(), py::arg("units") = "deg/h",
        py::arg("channel") = "rate",
        py::arg("gaps") = std::vector<std::pair<std::int64_t, std::int64_t>>{},
        py::arg("nan_is_missing") = true, py::arg("max_missing_percent") = 1.0,
        "The whole analysis of a static record: the document `foglab analyze --json` writes "
        "(docs/json.md), as dicts and lists. `gaps` are the record's as read() gives them "
        "((before_sample, missing) pairs); a NaN sample or temperature is a missing one, its "
        "row left out and runs of them gaps, as the CLI reads a file (nothing is "
        "interpolated); nan_is_missing=False makes it a DataError. max_missing_percent: "
        "the most of an Allan cluster's samples that may be missing across a gap (the CLI's "
        "--max-missing-percent; 0 keeps the contiguous stretches alone).");
}
