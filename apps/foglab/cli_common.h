// foglab CLI — options and plumbing shared by the subcommands. No algorithms
// live here: the commands parse, call the library and write what it returns.
#pragma once

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "foglab/core/csv.h"
#include "foglab/core/error.h"
#include "foglab/core/units.h"
#include "foglab/io/reader.h"
#include "foglab/report/report.h"
#include "foglab/sim/error_model.h"
#include "foglab/sim/lab2_variants.h"
#include "foglab/stats/tau_grid.h"

namespace foglab::cli {

/// Where a command reads its record from.
struct InputOptions {
  std::string path;  ///< FILE, "-" for stdin, empty for the built-in sample
  std::string channel;
  std::optional<double> sample_rate_hz;
  std::string format = "auto";
  std::string units = "deg/h";
  bool units_given = false;  ///< --units was on the command line (not its default)
  std::string time_channel;
  bool decimal_comma = false;
  std::optional<std::size_t> max_samples;  ///< empty: default_max_samples()
};

/// The most samples a record may have when --max-samples is not given:
/// what a sixteenth of the memory free for this process holds (available
/// memory, within `ulimit -v`), at least a million.
std::size_t default_max_samples();

/// A JSON document as text, indented by 2, with a final newline. Bytes that
/// are not UTF-8 (a file name or a column name in Latin-1) become U+FFFD
/// instead of an error.
std::string json_text(const nlohmann::json& document);

/// The ReadOptions of `options` (channel, rate, format, units, time,
/// decimal comma, sample limit, kMaxSampleMagnitude).
io::ReadOptions read_options(const InputOptions& options);

/// Adds FILE and --channel/--fs/--format/--units/--time/--decimal-comma/
/// --max-samples to `command`.
void add_input_options(CLI::App& command, InputOptions& options, bool file_optional);
/// The same without FILE (a command that reads several files).
void add_reading_options(CLI::App& command, InputOptions& options);

/// --taus parsed; a UsageError names the option and, when given, `path`.
stats::TauGrid parse_taus_option(const std::string& text, const std::string& path);

/// --format and --units parsed; a UsageError names the option and `path`.
io::InputFormat parse_format_option(const std::string& text, const std::string& path);
RateUnit parse_units_option(const std::string& text, const std::string& path);

/// --units as analyze reads it: one unit for every channel ("deg/s"), or
/// items by sensor ("gyro=deg/s,accel=g") and by channel ("ax=mg"), with
/// at most one bare unit among them (for the channels no item names).
struct UnitSpec {
  std::optional<SampleUnit> all;
  std::optional<SampleUnit> gyroscope, accelerometer;
  std::vector<std::pair<std::string, SampleUnit>> channels;
};
UnitSpec parse_unit_spec(const std::string& text, const std::string& path);

/// The unit of `channel` under `spec`: its own item, else its sensor's (by
/// its name, io::sensor_by_name()), else the bare unit, else deg/h (m/s^2,
/// with a note, for a channel named as an accelerometer's). A unit of the
/// other sensor than the channel's name says is a UsageError ("mixed
/// units").
SampleUnit channel_unit(const UnitSpec& spec, const std::string& channel, const std::string& path,
                        std::vector<std::string>& notes);

/// Runs `work` on a loaded series: a usage or data error from the library is
/// rethrown with the file and channel in front, so that the message names them.
template <typename Work>
decltype(auto) naming_the_input(const io::Series& series, Work&& work) {
  try {
    return work();
  } catch (const DataError& e) {
    throw DataError(fmt::format("'{}' channel {}: {}", series.path, series.channel, e.what()));
  } catch (const UsageError& e) {
    throw UsageError(fmt::format("'{}' channel {}: {}", series.path, series.channel, e.what()));
  }
}

/// Reads the record (or makes the built-in sample when no FILE was given),
/// printing the reader's notes (an integer MAT class converted, ...). A NaN
/// sample is a missing one: its row is left out and becomes a gap
/// (leave_missing_samples()), unless `keep_nan_rows` leaves that to the
/// caller, which pairs a second channel with the record first.
io::Series load_input(const InputOptions& options, bool keep_nan_rows = false);

/// Leaves out the rows whose sample is NaN in `series` or in `paired` (may
/// be null; io::drop_missing_samples()) and says what was left out and
/// which gaps the record has.
void leave_missing_samples(io::Series& series, std::vector<double>* paired);

/// A JSON number, or null for NaN/Inf.
nlohmann::json number(double value);
nlohmann::json numbers(const std::vector<double>& values);

/// An error model as JSON, in the units of docs/conventions.md (truth files, answer keys).
nlohmann::json model_json(const sim::ErrorModel& model);
/// N, B, K, R, Q, gm_sigma, gm_tc of a noise model (units: model_units_json()).
nlohmann::json noise_model_json(const NoiseModel& model);
/// {name: unit} of kNoiseParameters, the units of noise_model_json().
nlohmann::json noise_units_json();
/// The unit of every field of model_json().
nlohmann::json model_units_json();

/// Describes where the data came from, for every JSON output.
nlohmann::json input_json(const io::Series& series);
/// Where the sample rate came from, in the CLI's words: "option --fs",
/// "variable f", "time column t", "built-in".
std::string sample_rate_source_text(const io::Series& series);

/// A library message in the CLI's terms: the API fields it names
/// (ReadOptions::sample_rate_hz, TauGrid::min_clusters, parse_tau_grid("x"),
/// ...) become the flags that set them (--fs, --min-clusters, --taus 'x').
/// The one place where the library's vocabulary meets the command line's;
/// run_command_line() applies it to every error and note.
std::string in_cli_terms(std::string message);

/// The lab-2 variant options from the commands' --seed and hidden --hours
/// (shorter runs; UsageError unless > 0).
sim::Lab2Options lab2_options(std::uint64_t seed, const std::optional<double>& hours);

/// Prints a note on stderr ("foglab: note: ..."), once: a note already printed word for word
/// (each channel of a file read in parallel says what the file's time axis says) is not repeated.
void note(const std::string& text);

/// Announces a long step on stderr ("foglab: reading ..."), only when stderr
/// is a terminal; nothing when it is redirected.
void progress(const std::string& step);

/// While one lives, note() on its thread adds the note (in the CLI's
/// terms) to `into` instead of printing it, and progress() is silent:
/// batch's workers keep each unit's notes with the unit. Nests.
class CollectNotes {
 public:
  explicit CollectNotes(std::vector<std::string>& into);
  ~CollectNotes();
  CollectNotes(const CollectNotes&) = delete;
  CollectNotes& operator=(const CollectNotes&) = delete;

 private:
  std::vector<std::string>* previous_;
};

/// The labs' title block options (the manual's title page): --student,
/// --group, --date.
struct TitleOptions {
  std::string student, group, date;
};

/// Adds --student, --group and --date to a lab command.
void add_title_options(CLI::App* cmd, TitleOptions& t);

/// The title block of lab `lab` (variant when known), the date today's
/// (YYYY-MM-DD, local time) unless --date gave one.
report::TitleBlock title_block(const TitleOptions& t, int lab, std::optional<int> variant);

}  // namespace foglab::cli
