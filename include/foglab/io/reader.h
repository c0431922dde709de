// foglab — reading gyro records: MAT files, text tables, raw binary, stdin.
//
// Supported inputs (docs/conventions.md, docs/cli.md):
//   * MAT files v4, v5, v7 (compressed) and v7.3 (HDF5), read through matio.
//     Variables are chosen by name; the lab's layout is `f` (sample rate,
//     Hz), `t` (time, s), `Y1`, `Y2` (rate, deg/h), `T1`, `T2` (degC).
//   * Text: CSV, TSV, semicolon- or whitespace-separated columns, an
//     optional header line of names, `#` comment lines; UTF-8 or UTF-16
//     with a byte-order mark, any line ends; decimal commas with
//     ReadOptions::decimal_comma; a column is chosen by header name or by
//     1-based index.
//   * Raw little-endian float32/float64 (`.f32`/`.f64` or an explicit
//     format); these carry no sample rate, so one must be given.
//   * "-" reads text (or raw, with an explicit format) from standard input;
//     a FIFO or a device is read once too (is_stream()).
//
// The sample rate comes, in this order, from ReadOptions::sample_rate_hz,
// from a MAT variable `f`, or from a uniformly sampled time column (`t`,
// `time` or `time_s`; the naming rules are in channels.h). When `f` gives
// the rate, a MAT time vector `t`/`time`/`time_s` beside it is still checked
// (same length as the channel, increasing). A time axis may have gaps: a
// step of at least 1.5 reference steps is round(step / reference) - 1
// missing samples, listed in Series::gaps (core/gaps.h) so that a record
// with a gap is never analysed as if it were continuous, and nothing is
// interpolated. Non-monotonic time is a data error whose message says to
// give ReadOptions::sample_rate_hz to ignore the time; that option skips
// every time check (and finds no gaps). Irregular steps (neither within 1 %
// of the reference nor a gap) are a data error too, naming the first, unless
// they are at least 16 and 1 % of the steps and the times scatter about a
// uniform grid (rms at most 0.25 of a step about it): a logger's clock
// stamping a sensor's samples. The times are then read as the ROS bag
// reader reads its stamps (rosbag.h): each sample on the grid's nearest slot,
// a slot skipped a gap, a row on the slot of the row before it dropped, the
// rate the least-squares slope of time against slot; Series::time_jitter
// says how, with a note. With ReadOptions::nan_is_missing a NaN
// sample (an empty text cell) is a missing sample: drop_missing_samples()
// leaves its row out and makes a gap of it, with or without a time axis.
// An explicit ReadOptions::time_channel is used before `f`. Text headers
// match the time names without regard to case, except that a column named
// exactly `T` is the lab's temperature. The reference step is the median of
// the first 64 steps.
//
// Channel names: MAT variables by name; text columns by header name (exact,
// else without regard to case) or, for a string of digits that is not a
// name, by 1-based index; columns of a table without a header are named "1",
// "2", ...; a raw file's one channel is "1". The default channel leaves out
// `f`, the time and the lab's temperatures (`T`, `T1`, `T2`, ...; MAT only).
// In a text table only the cells of the columns read are parsed, so a
// column of dates or words elsewhere does not matter.
//
// MAT files are read through matio into the result vector directly (any
// numeric class is converted to double on the way, and an integer class
// gets a note in Series::notes; the time vector, when it
// gives the rate, is read and released first), so reading takes about one
// copy of the channel in memory. Damaged files (truncated, garbage, corrupt
// compressed data) are DataErrors, and matio/HDF5 never print to stderr. An
// HDF5 file that is not a v7.3 MAT file (no MATLAB header) is a DataError
// saying so.
//
// Errors: an unusable option is a UsageError (exit 2); unusable content is a
// DataError (exit 3) whose message names the file and the variable, line,
// column or sample index, and what was expected.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/core/gaps.h"
#include "foglab/core/language.h"
#include "foglab/core/units.h"

namespace foglab::io {

/// The container format of an input file.
enum class InputFormat {
  automatic,  ///< by extension: .mat -> mat, .f32/.f64 -> raw, otherwise text
  mat,        ///< MATLAB MAT-file v4/v5/v7/v7.3
  text,       ///< CSV/TSV/whitespace text
  f32,        ///< raw little-endian IEEE float32
  f64,        ///< raw little-endian IEEE float64
};

/// "auto", "mat", "text", "f32", "f64".
std::string_view to_string(InputFormat format);
/// Parses the names above (also "csv", "tsv", "float32", "float64");
/// throws UsageError listing them otherwise.
InputFormat input_format_from_string(std::string_view text);

/// Where a record's sample rate came from.
enum class SampleRateSource {
  option,        ///< ReadOptions::sample_rate_hz
  variable_f,    ///< the MAT variable `f`
  time_channel,  ///< a uniformly sampled time variable or column (Series::sample_rate_channel)
  builtin,       ///< the built-in sample (sample.h)
};
/// "option", "variable_f", "time_channel", "builtin".
std::string_view to_string(SampleRateSource source);

/// How to read one channel of a record.
struct ReadOptions {
  /// Variable (MAT) or column (text: header name or 1-based index). Empty:
  /// the only data channel; with several, `Y1` if present, else an error
  /// listing the candidates.
  std::string channel;
  /// [Hz] Sample rate; overrides the file's `f` or time column. Must be > 0.
  std::optional<double> sample_rate_hz;
  InputFormat format = InputFormat::automatic;
  /// Unit of the samples; they are converted to deg/h (phase: (deg/h)*s),
  /// or for an acceleration unit (m/s^2, g, mg) to m/s^2.
  SampleUnit unit = SampleUnit::deg_per_hour;
  /// Time variable/column; empty: `t`, `time` or `time_s` when present.
  std::string time_channel;
  /// The largest magnitude a sample may have once converted (deg/h, or degC
  /// for a temperature); a larger one is a DataError naming the sample. No
  /// limit by default, so that any finite double round-trips; the CLI's
  /// analyses use kMaxSampleMagnitude.
  double max_magnitude = std::numeric_limits<double>::infinity();
  /// Text: numbers are written with a decimal comma ("0,25"); the fields
  /// are then separated by tabs, semicolons or blanks, never commas.
  /// Without it, a table that looks so is refused with that hint.
  bool decimal_comma = false;
  /// The most samples read from one file (text or raw); more is a
  /// DataError naming the limit. No limit by default; the CLI sets one
  /// from the memory available (--max-samples), so that an endless
  /// stream (/dev/zero, a FIFO) ends with a message, not the machine's
  /// memory.
  std::optional<std::size_t> max_samples;
  /// A NaN sample of the channel is a missing sample, not an error: it is
  /// kept as NaN (so is an empty cell of the channel in a text table), for
  /// drop_missing_samples() to turn into gaps. An infinity is still a
  /// DataError. Off by default; the CLI's record analyses set it.
  bool nan_is_missing = false;
};

/// A limit for ReadOptions::max_magnitude (core/units.h).
inline constexpr double kMaxSampleMagnitude = foglab::kMaxSampleMagnitude;

/// What drop_missing_samples() took out of a record (rows whose sample, or
/// whose paired sample, is NaN).
struct MissingSamples {
  std::int64_t samples = 0;    ///< rows left out
  std::int64_t stretches = 0;  ///< runs of consecutive rows left out
  std::int64_t at_start = 0;   ///< rows before the first one kept (the record starts later)
  std::int64_t at_end = 0;     ///< rows after the last one kept (the record ends earlier)
};

/// How the times of a time axis that is not evenly spaced sit on the uniform sampling grid
/// they were read as (a logger's clock stamping a sensor's samples).
struct TimeJitter {
  std::size_t irregular_steps = 0;  ///< steps neither within 1 % of the median nor a gap
  std::size_t steps = 0;            ///< steps between the times read
  double median_step_s = 0.0;       ///< [s] median step between consecutive times
  double rms_s = 0.0;               ///< [s] rms of time minus the fitted line of time against slot
  double max_s = 0.0;               ///< [s] largest magnitude of that difference
  std::size_t rows_dropped = 0;     ///< rows on the slot of the row before them, or earlier
};

/// One channel read from a file, converted to foglab's units.
struct Series {
  std::string path;             ///< as given; "-" for standard input
  std::string channel;          ///< name of the chosen variable or column
  /// Samples [deg/h] (phase records: [(deg/h)*s]); [m/s^2] when read in an
  /// acceleration unit (ReadOptions::unit).
  std::vector<double> values;
  double sample_rate_hz = 0.0;  ///< [Hz]
  /// Where the sample rate came from.
  SampleRateSource sample_rate_source = SampleRateSource::option;
  /// The time variable or column that gave it (time_channel), else empty.
  std::string sample_rate_channel;
  /// Stretches of missing samples the time axis shows (empty without a
  /// time axis, or with ReadOptions::sample_rate_hz).
  std::vector<Gap> gaps;
  /// The NaN rows drop_missing_samples() left out (none before it runs).
  MissingSamples nan_left_out;
  /// [s] The time axis' first time (0 without one).
  double start_time_s = 0.0;
  /// Set when the time axis was not evenly spaced and was read as a grid with jitter (see
  /// above); the samples are then those on distinct slots of that grid.
  std::optional<TimeJitter> time_jitter;
  /// Every data channel the file holds (for messages and listings). MAT:
  /// the real numeric vectors of two or more samples, in file order (v7.3:
  /// name order), `t` and `T1` included, scalars such as `f` not; text:
  /// every column; raw: "1".
  std::vector<std::string> available_channels;
  /// Every variable (MAT) or column (text) the file holds, usable as a
  /// channel or not (a char, struct or complex variable, `f`); raw: "1".
  /// Tells a name that is absent from one whose content is unusable.
  std::vector<std::string> variables;
  /// What a user should know about how the samples were read (a MAT
  /// variable of an integer class converted to double); the CLI prints each
  /// as a note.
  std::vector<Message> notes;
};

/// Reads one channel. Checks that the values are finite (a NaN or Inf is a
/// DataError naming the 1-based sample index; a NaN is kept with
/// ReadOptions::nan_is_missing), no larger in magnitude than
/// ReadOptions::max_magnitude (an absurd value such as 1e308 is then a
/// DataError too), and that there is at least one sample. Throws UsageError
/// / DataError as described above.
Series read_series(const std::string& path, const ReadOptions& options);

/// Leaves out every row whose sample is NaN in `series` or in `paired` (a
/// channel read from the same rows, such as the temperature; may be null):
/// a NaN is a missing sample. Series::gaps (read from the time axis, with
/// Series::values still holding every row) are rebuilt so that each run of
/// left-out rows inside the record is a gap, merged with a gap of the time
/// axis beside it; rows left out at either end shorten the record
/// (Series::start_time_s moves to the first sample kept); what was left
/// out is stored in Series::nan_left_out too. Nothing is interpolated. Throws DataError naming the
/// file and the channel when no row is left. Without a NaN it changes nothing.
MissingSamples drop_missing_samples(Series& series, std::vector<double>* paired);

/// Whether `path` can be read only once: standard input ("-"), a FIFO, a
/// device. Such a source is opened once, and a second channel (a
/// temperature) cannot be read from it.
bool is_stream(const std::string& path);

/// Names of the data channels (variables or columns) in a file.
std::vector<std::string> list_channels(const std::string& path,
                                       InputFormat format = InputFormat::automatic);

/// Every variable name a file holds, usable as a channel or not (a MAT
/// file's char, struct or complex variables too; text columns and raw files
/// as list_channels()), without reading any data: Series::variables of a
/// read. Asking read_series() for an unusable one gives the reason.
std::vector<std::string> list_variables(const std::string& path,
                                        InputFormat format = InputFormat::automatic);

}  // namespace foglab::io
