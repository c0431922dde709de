// foglab — internals shared by the readers in src/io (not a public header).
//
// read_series() in reader.cc validates the options, picks the format and
// hands the file to one of the format readers below. A format reader fills a
// Series with the chosen channel's samples *in the file's unit*, the sample
// rate and its source, and the channel list; reader.cc then checks that the
// samples are finite and converts them to deg/h. Every message a reader
// throws starts with the file's name (see quoted_path()).
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "foglab/io/channels.h"
#include "foglab/io/reader.h"

namespace foglab::io::internal {

/// A FILE* the readers own: closed when it goes out of scope, also when a
/// constructor or a check throws on the way.
struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

/// Whether `path` ends in `extension` (lower case, with its dot), ASCII case
/// ignored, with a name before it.
bool has_extension(const std::string& path, std::string_view extension);

/// "'PATH'" for a file, "standard input" for "-": how messages name a source.
std::string quoted_path(const std::string& path);

/// Throws DataError("<quoted path>: <what>").
[[noreturn]] void throw_data_error(const std::string& path, std::string_view what);

/// Throws UsageError("cannot open '<path>': <reason>") unless `path` is "-" or
/// a regular file that can be opened for reading.
void require_readable(const std::string& path);

/// Size in bytes of a regular file; nullopt for "-", a pipe or a device,
/// which are read as streams (throws UsageError as above if unreadable).
std::optional<std::uint64_t> regular_file_size(const std::string& path);

/// `names` joined with ", " (for messages listing channels).
std::string join_names(const std::vector<std::string>& names);

/// A value for messages, to 12 significant digits (0.1 + 0.2 shows as 0.3).
std::string format_value(double value);

/// "; to analyse the samples as evenly spaced anyway, give ... --fs ...": how
/// to proceed past a bad time axis, appended to its messages.
extern const char* const kIgnoreTimeHint;

/// What a time axis says: the sample rate, the gaps, the first time; for times read as a
/// grid with jitter, how they sit on it and the rows to drop.
struct TimeAxis {
  double rate_hz = 0.0;   ///< [Hz]
  std::vector<Gap> gaps;  ///< core/gaps.h; Gap::before_sample counts the rows kept
  double start_s = 0.0;   ///< [s]
  std::optional<TimeJitter> jitter;
  /// Rows (0-based, increasing) on the slot of the row before them, or earlier; the values
  /// read beside the times lose them (stamp_grid.h's drop_entries).
  std::vector<std::size_t> dropped;
};

/// Checks a time axis sample by sample: every time must be finite, every step
/// positive (else "time is not increasing") and either within 1% of the
/// reference step plus the time's resolution or at least 1.5 reference steps:
/// a gap, of round(step / reference) - 1 missing samples. Other steps are
/// irregular. result() refuses a few of them (fewer than 16, or under 1 % of
/// the steps: "not uniformly sampled ... an irregular step", naming the
/// first); more are a logger's jitter when the times scatter about a uniform
/// grid (stamp_grid.h), and the axis is that grid. The times are kept for it
/// (8 bytes a sample until result()). The reference step is the median of the
/// first 64 steps, so one odd step at the start does not make every regular
/// step look wrong. The
/// resolution is that of the stored or printed times (single precision,
/// "%.3f"): rounding each time moves a step by up to one resolution unit.
/// It is allowed for only while it is below half the reference step; a
/// coarser one (integer seconds at 1 Hz) means the times are exact.
/// Messages give the 1-based sample index (and the line, when given) and the
/// two time values; they are DataErrors naming `path`.
class TimeAxisCheck {
 public:
  TimeAxisCheck(const std::string& path, std::string name, double resolution_s);
  /// The next time [s]; `line` (0: none) is quoted in messages;
  /// `resolution_s` raises the resolution for this and later samples.
  void add(double time_s, std::size_t line = 0, double resolution_s = 0.0);
  /// Once all samples are in: the rate (n - 1 + missing) / (t[n-1] - t[0])
  /// [Hz], the gaps and the first time; at least two samples are needed.
  TimeAxis result();

 private:
  static constexpr std::size_t kHeadSteps = 64;
  void settle_reference();
  TimeAxis jittered_axis();
  std::string where(std::size_t index, std::size_t line) const;

  std::string path_;
  std::string name_;
  double resolution_s_;
  std::size_t count_ = 0;
  double first_s_ = 0.0;
  double previous_s_ = 0.0;
  // the first kHeadSteps + 1 times (and their lines), until the reference
  // step is known
  std::vector<double> head_s_;
  std::vector<std::size_t> head_lines_;
  bool settled_ = false;
  double reference_s_ = 0.0;
  std::vector<Gap> gaps_;
  // every time, from the first [ns], for the grid of a jittered axis
  std::vector<std::int64_t> times_ns_;
  bool times_fit_ = true;
  std::size_t irregular_steps_ = 0;
  std::size_t faults_ = 0;   // irregular steps and times that do not increase
  std::string first_fault_;  // its message
};

/// A whole time vector, checked as by TimeAxisCheck.
TimeAxis time_axis_of(const std::string& path, std::string_view name,
                      std::span<const double> time_s, double resolution_s);

/// Gives `series` (its values read, one a row of the time axis) what the time axis
/// `time_name` says: the gaps and the first time, the rate too when `rate_from_axis`; for a
/// jittered axis its rows on an earlier slot dropped from the values, Series::time_jitter and
/// the notes.
void apply_time_axis(Series& series, TimeAxis axis, const std::string& time_name,
                     bool rate_from_axis);

/// Throws DataError unless a rate read from the file is finite and > 0.
void check_file_sample_rate(const std::string& path, double rate_hz, std::string_view source);

/// One stretch of matio calls. matio keeps global state (its log function)
/// and the serial HDF5 library under v7.3 files is not thread-safe, so a
/// session holds a process-wide lock. It routes matio's (and HDF5's) log
/// messages into the session instead of stderr. matio 1.5.23 reports
/// problems only through these messages (its Mat_Critical() only logs; the
/// library never calls the aborting Mat_Error()) and sometimes returns
/// "success" after a short read, so callers check messages() after each
/// call that matters. A MAT writer should hold a session too.
class MatioSession {
 public:
  MatioSession();
  ~MatioSession();
  MatioSession(const MatioSession&) = delete;
  MatioSession& operator=(const MatioSession&) = delete;

  /// matio's messages since the last clear(): errors and critical messages,
  /// plus warnings when `with_warnings`. HDF5 error stacks are reduced to
  /// their innermost "minor" description.
  std::vector<std::string> messages(bool with_warnings) const;
  void clear();
};

// --- the format readers (mat_reader.cc, text_reader.cc, raw_reader.cc) ---
// Each returns the channel in the file's unit; `options.sample_rate_hz`, when
// set, has been validated and is used instead of anything in the file.

Series read_mat(const std::string& path, const ReadOptions& options);
std::vector<std::string> list_mat_channels(const std::string& path);
std::vector<std::string> list_mat_variables(const std::string& path);

Series read_text(const std::string& path, const ReadOptions& options);
std::vector<std::string> list_text_channels(const std::string& path);

/// `format` is InputFormat::f32 or InputFormat::f64.
Series read_raw(const std::string& path, const ReadOptions& options, InputFormat format);

// Structural checks of a MAT file before matio reads it (mat_checks.cc);
// each throws DataError naming the file.
/// v5/v7: every top-level element lies inside the file's `size` bytes;
/// returns how many there are.
std::size_t check_mat5_layout(const std::string& path, std::uint64_t size);
/// v4: every variable (header, name, data) lies inside the file.
void check_mat4_layout(const std::string& path, std::uint64_t size);
/// A file without v5's header marks whose first bytes read as a v4 header
/// claiming more than the file holds is refused before matio allocates it.
void check_mat4_first_header(const std::string& path, std::uint64_t size);
/// An HDF5 superblock (version 0 or 1) at `signature_at` whose driver
/// information block claims more than the file's `size` bytes is refused
/// before HDF5 allocates and zero-fills what it claims.
void check_hdf5_driver_block(const std::string& path, std::uint64_t size,
                             std::uint64_t signature_at);
/// Opens a v7.3 file's metadata in a child process; throws when HDF5 crashes.
void probe_mat73_in_child(const std::string& path);
/// The offset of an HDF5 superblock signature (0, 512, 1024, ...), if any.
std::optional<std::uint64_t> hdf5_signature_offset(const std::string& path, std::uint64_t size);

}  // namespace foglab::io::internal
