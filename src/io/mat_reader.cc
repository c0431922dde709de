// foglab — MAT files v4, v5, v7 (compressed) and v7.3 (HDF5) through matio.
//
// What matio 1.5.23 does with damaged files (found by experiment; the tests
// in tests/io/mat_reader_test.cc pin it down):
//   * it never aborts: Mat_Critical() only logs, and the library never calls
//     Mat_Error() (the one function that aborts). Without a log function of
//     ours, matio stays silent but HDF5 prints its error stack to stderr, so
//     every session installs one (MatioSession) and keeps the messages.
//   * a garbage file makes Mat_Open() return NULL; an empty file opens as a
//     v4 file with no variables; a truncated v7.3 file *opens* (HDF5 reports
//     "File has been truncated" only through the log).
//   * a v4 or v5 file cut inside a variable's data is listed normally and
//     Mat_VarReadData() returns 0 after a short read, leaving the rest of
//     the buffer untouched; a cut or damaged compressed (v7) stream is the
//     same, with a log message. Hence three guards here: a walk over the
//     file's top-level elements that checks each lies inside the file (v4,
//     v5/v7), the log messages of each read, and a NaN sentinel with a
//     private payload written before the read and looked for after it.
//   * matio converts the stored type to the variable's class on reading; we
//     set the class of the variable's info to double before reading, so it
//     delivers doubles straight into our vector (no second full copy) for
//     every numeric class and every file version.
#include <fcntl.h>
#include <fmt/format.h>
#include <matio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "foglab/core/error.h"
#include "foglab/core/numeric.h"
#include "readers_internal.h"

namespace {

struct LogRecord {
  int level = 0;
  std::string text;
};

// Each thread records only while it is inside a session; matio calls made
// elsewhere are dropped silently (never printed raw).
thread_local std::vector<LogRecord> t_records;
thread_local int t_session_depth = 0;

std::recursive_mutex& matio_mutex() {
  static std::recursive_mutex mutex;
  return mutex;
}

}  // namespace

extern "C" {
// matio's log callback: must not throw into C code.
static void foglab_matio_log(int log_level, char* message) {
  if (t_session_depth == 0 || message == nullptr) return;
  try {
    t_records.push_back({log_level, std::string(message)});
  } catch (...) {
  }
}
}

namespace foglab::io::internal {

MatioSession::MatioSession() {
  matio_mutex().lock();
  if (t_session_depth++ == 0) t_records.clear();
  // Re-installed every time: another part of the program may have installed
  // its own function since. This also routes HDF5's error stack to us.
  Mat_LogInitFunc("foglab", &foglab_matio_log);
}

MatioSession::~MatioSession() {
  if (--t_session_depth == 0) t_records.clear();
  matio_mutex().unlock();
}

std::vector<std::string> MatioSession::messages(bool with_warnings) const {
  std::vector<std::string> out;
  for (const LogRecord& record : t_records) {
    const bool error = (record.level & (MATIO_LOG_LEVEL_ERROR | MATIO_LOG_LEVEL_CRITICAL)) != 0;
    const bool warning = (record.level & MATIO_LOG_LEVEL_WARNING) != 0;
    if (!error && !(with_warnings && warning)) continue;
    std::string text = record.text;
    // HDF5 stacks arrive as "HDF5 error #000 in H5Fopen()\n file: ...\n
    // major: ...\n minor: File has been truncated": keep the minor part.
    if (text.rfind("HDF5", 0) == 0) {
      const auto minor = text.find("minor: ");
      text = "HDF5: " + (minor == std::string::npos ? text : text.substr(minor + 7));
    }
    out.push_back(std::move(text));
  }
  return out;
}

void MatioSession::clear() { t_records.clear(); }

namespace {

// A quiet NaN with a private payload: written before a read, it marks every
// sample matio did not deliver.
constexpr std::uint64_t kUnreadBits = 0x7ff8'f0c1'ab5e'0001ULL;
constexpr double kUnread = std::bit_cast<double>(kUnreadBits);

// How much bigger than the file a numeric variable can be: zlib's largest
// compression ratio is 1032:1; uncompressed data take at least a byte each.
constexpr double kMaxCompressionRatio = 1100.0;

// The most useful of a session's messages: HDF5 stacks are walked from the
// API call down, so their last entry is the specific one; matio's own first
// message names the cause, later ones repeat "an error occurred".
std::string summary(const std::vector<std::string>& messages) {
  if (messages.empty()) return {};
  for (auto it = messages.rbegin(); it != messages.rend(); ++it) {
    if (it->rfind("HDF5: ", 0) == 0) return *it;
  }
  return messages.front();
}

std::string matio_error_text(int error) {
  switch (error) {
    case MATIO_E_GENERIC_READ_ERROR:
      return "read error";
    case MATIO_E_INDEX_TOO_BIG:
      return "index too big";
    case MATIO_E_FILE_FORMAT_VIOLATION:
      return "file format violation";
    case MATIO_E_BAD_ARGUMENT:
      return "bad argument";
    case MATIO_E_OUTPUT_BAD_DATA:
      return "bad data";
    case MATIO_E_OPERATION_NOT_SUPPORTED:
      return "operation not supported";
    case MATIO_E_OUT_OF_MEMORY:
      return "out of memory";
    case MATIO_E_READ_VARIABLE_DOES_NOT_EXIST:
      return "variable does not exist";
    default:
      return fmt::format("matio error {}", error);
  }
}

// --- variables ---

struct MatCloser {
  void operator()(mat_t* mat) const { Mat_Close(mat); }
};

struct VarDeleter {
  void operator()(matvar_t* var) const { Mat_VarFree(var); }
};
using VarPtr = std::unique_ptr<matvar_t, VarDeleter>;

bool is_integer_class(matio_classes c) {
  switch (c) {
    case MAT_C_INT8:
    case MAT_C_UINT8:
    case MAT_C_INT16:
    case MAT_C_UINT16:
    case MAT_C_INT32:
    case MAT_C_UINT32:
    case MAT_C_INT64:
    case MAT_C_UINT64:
      return true;
    default:
      return false;
  }
}

struct VarInfo {
  std::string name;
  matio_classes class_type = MAT_C_EMPTY;
  bool complex = false;
  bool logical = false;
  std::vector<std::size_t> dims;

  double numel() const {
    double n = 1;
    for (std::size_t d : dims) n *= static_cast<double>(d);
    return n;
  }
  bool is_vector() const {
    int long_dims = 0;
    for (std::size_t d : dims) long_dims += d > 1 ? 1 : 0;
    return long_dims <= 1;
  }
  bool numeric() const {
    const bool number =
        class_type == MAT_C_DOUBLE || class_type == MAT_C_SINGLE || is_integer_class(class_type);
    return number && !logical;
  }
  // Something read_series can return: a real numeric vector with samples.
  bool readable() const { return numeric() && !complex && is_vector() && numel() >= 1; }
};

VarInfo to_info(const matvar_t& var) {
  VarInfo info;
  info.name = var.name != nullptr ? var.name : "";
  info.class_type = var.class_type;
  info.complex = var.isComplex != 0;
  info.logical = var.isLogical != 0;
  if (var.dims != nullptr) info.dims.assign(var.dims, var.dims + std::max(var.rank, 0));
  return info;
}

std::string class_name(const VarInfo& var) {
  if (var.logical) return "logical";
  switch (var.class_type) {
    case MAT_C_EMPTY:
      return "empty";
    case MAT_C_CELL:
      return "cell";
    case MAT_C_STRUCT:
      return "struct";
    case MAT_C_OBJECT:
      return "object";
    case MAT_C_CHAR:
      return "char";
    case MAT_C_SPARSE:
      return "sparse";
    case MAT_C_DOUBLE:
      return "double";
    case MAT_C_SINGLE:
      return "single";
    case MAT_C_INT8:
      return "int8";
    case MAT_C_UINT8:
      return "uint8";
    case MAT_C_INT16:
      return "int16";
    case MAT_C_UINT16:
      return "uint16";
    case MAT_C_INT32:
      return "int32";
    case MAT_C_UINT32:
      return "uint32";
    case MAT_C_INT64:
      return "int64";
    case MAT_C_UINT64:
      return "uint64";
    case MAT_C_FUNCTION:
      return "function handle";
    case MAT_C_OPAQUE:
      return "opaque object";
  }
  return "unknown class";
}

// "1000x1 double", "complex 1000x1 double", "3x4 double matrix", "1x5 char".
std::string describe(const VarInfo& var) {
  const std::string dims = fmt::format("{}", fmt::join(var.dims, "x"));
  std::string text = fmt::format("{}{} {}", var.complex ? "complex " : "", dims, class_name(var));
  if (var.numeric() && !var.is_vector()) text += " matrix";
  return text;
}

// Why a variable cannot be a channel ("" if it can).
std::string unreadable_reason(const VarInfo& var) {
  if (var.readable()) return {};
  std::string text = fmt::format("variable '{}' is {}", var.name, describe(var));
  if (var.numeric() && var.numel() < 1) return text + " (empty)";
  return text + "; expected a real numeric vector (double, single or integer)";
}

class MatFile {
 public:
  MatFile(const std::string& path, MatioSession& session) : path_(path), session_(session) {
    const std::optional<std::uint64_t> size = regular_file_size(path);
    if (!size) {
      throw UsageError(
          fmt::format("cannot read '{}' as a MAT file: it is not a regular file "
                      "(matio needs to seek)",
                      path));
    }
    size_ = *size;
    if (size_ == 0) throw_data_error(path, "the MAT file is empty");
    check_mat4_first_header(path, size_);
    if (hdf5_signature_offset(path, size_) == std::uint64_t{512}) {
      check_hdf5_driver_block(path, size_, 512);
      probe_mat73_in_child(path);
    }
    session_.clear();
    mat_.reset(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
    const auto messages = session_.messages(false);
    if (!mat_) {
      if (const std::optional<std::uint64_t> at = hdf5_signature_offset(path, size_)) {
        throw_data_error(
            path, fmt::format("an HDF5 file (signature at byte {}) but not a MAT file: a v7.3 "
                              "MAT file is an HDF5 file that starts with MATLAB's 128-byte "
                              "header, and this one has none (written by h5py, Octave's "
                              "save -hdf5 or the HDF5 library?); save the variables from "
                              "MATLAB with save -v7.3 or from Octave with save -v7, or export "
                              "them as CSV",
                              *at));
      }
      std::string detail = summary(messages);
      if (detail.find("does not seem to be a valid MAT file") != std::string::npos) detail.clear();
      throw_data_error(path, "not a MAT file (v4, v5, v7 or v7.3), or damaged beyond reading" +
                                 (detail.empty() ? "" : " (matio: " + detail + ")"));
    }
    version_ = Mat_GetVersion(mat_.get());
    if (!messages.empty()) {
      throw_data_error(path, "the MAT file is corrupt or truncated (" + summary(messages) + ")");
    }
    if (version_ == MAT_FT_MAT5) check_mat5_layout(path, size_);
    if (version_ == MAT_FT_MAT4) check_mat4_layout(path, size_);
    list_variables();
  }
  MatFile(const MatFile&) = delete;
  MatFile& operator=(const MatFile&) = delete;

  const std::vector<VarInfo>& variables() const { return variables_; }

  const VarInfo* find(std::string_view name) const {
    for (const VarInfo& var : variables_) {
      if (var.name == name) return &var;
    }
    return nullptr;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const VarInfo& var : variables_) out.push_back(var.name);
    return out;
  }

  // Reads a readable() variable as doubles straight into the result.
  std::vector<double> read(const VarInfo& var) {
    session_.clear();
    VarPtr info(Mat_VarReadInfo(mat_.get(), var.name.c_str()));
    if (!info) fail_read(var, summary(session_.messages(false)));
    const VarInfo fresh = to_info(*info);
    if (!fresh.readable()) throw_data_error(path_, unreadable_reason(fresh));

    const double numel = fresh.numel();
    const bool compressed = info->compression == MAT_COMPRESSION_ZLIB || version_ == MAT_FT_MAT73;
    const double limit = static_cast<double>(size_) * (compressed ? kMaxCompressionRatio : 1.0);
    if (numel > limit) {
      throw_data_error(path_, fmt::format("the MAT file is corrupt: variable '{}' claims {} "
                                          "elements, more than a {}-byte file can hold",
                                          var.name, describe(fresh), size_));
    }
    std::vector<int> start(fresh.dims.size(), 0), stride(fresh.dims.size(), 1), edge;
    for (std::size_t d : fresh.dims) {
      if (d > static_cast<std::size_t>(INT_MAX)) {
        throw_data_error(path_, fmt::format("variable '{}' has {} elements; matio reads at most "
                                            "{} per dimension",
                                            var.name, d, INT_MAX));
      }
      edge.push_back(static_cast<int>(d));
    }

    // One spare element: the Allan integration turns the record into its
    // angle record in place, which is one sample longer.
    std::vector<double> values =
        large_vector(static_cast<std::size_t>(numel), kUnread, static_cast<std::size_t>(numel) + 1);
    // matio delivers the class recorded in the info, converting from the
    // stored type (int16, single, ...) on the way: ask for doubles.
    info->class_type = MAT_C_DOUBLE;
    session_.clear();
    const int error = Mat_VarReadData(mat_.get(), info.get(), values.data(), start.data(),
                                      stride.data(), edge.data());
    const auto messages = session_.messages(true);
    if (error != 0 || !messages.empty()) {
      fail_read(var, messages.empty() ? matio_error_text(error) : summary(messages));
    }
    // matio fills the array from its start, so a short read leaves the
    // marker at the end. A marker anywhere else would be a NaN that a
    // reader taking NaN for a missing sample (ReadOptions::nan_is_missing)
    // would accept: it is looked for too.
    std::size_t read = values.size();
    while (read > 0 && std::bit_cast<std::uint64_t>(values[read - 1]) == kUnreadBits) --read;
    const auto unread =
        std::find_if(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(read),
                     [](double v) { return std::bit_cast<std::uint64_t>(v) == kUnreadBits; });
    if (unread != values.begin() + static_cast<std::ptrdiff_t>(read)) {
      throw_data_error(path_, fmt::format("the MAT file is corrupt: sample {} of variable '{}' "
                                          "({}) was not read",
                                          unread - values.begin() + 1, var.name, describe(fresh)));
    }
    if (read < values.size()) {
      throw_data_error(path_, fmt::format("the MAT file is corrupt or truncated: variable "
                                          "'{}' ({}) ends after {} samples",
                                          var.name, describe(fresh), read));
    }
    return values;
  }

 private:
  void list_variables() {
    session_.clear();
    Mat_Rewind(mat_.get());
    while (true) {
      VarPtr var(Mat_VarReadNextInfo(mat_.get()));
      if (!var) break;
      variables_.push_back(to_info(*var));
    }
    const auto messages = session_.messages(false);
    if (!messages.empty()) {
      throw_data_error(path_, "the MAT file is corrupt (" + summary(messages) + ")");
    }
  }

  [[noreturn]] void fail_read(const VarInfo& var, const std::string& detail) {
    throw_data_error(path_, fmt::format("cannot read variable '{}'; the MAT file is corrupt or "
                                        "truncated{}",
                                        var.name, detail.empty() ? "" : " (" + detail + ")"));
  }

  std::string path_;
  MatioSession& session_;
  std::unique_ptr<mat_t, MatCloser> mat_;
  mat_ft version_ = MAT_FT_UNDEFINED;
  std::uint64_t size_ = 0;
  std::vector<VarInfo> variables_;
};

// Channels: readable vectors with more than one sample (a scalar such as
// `f` is a parameter, not a record), in file order.
std::vector<std::string> available_channels(const MatFile& file) {
  std::vector<std::string> out;
  for (const VarInfo& var : file.variables()) {
    if (var.readable() && var.numel() >= 2) out.push_back(var.name);
  }
  return out;
}

std::string listing(const MatFile& file) {
  std::vector<std::string> items;
  for (const VarInfo& var : file.variables()) {
    items.push_back(fmt::format("{} ({})", var.name, describe(var)));
  }
  return items.empty() ? std::string("none") : join_names(items);
}

const VarInfo& require_variable(const std::string& path, const MatFile& file,
                                const std::string& name, std::string_view role) {
  const VarInfo* var = file.find(name);
  if (var == nullptr) {
    const auto names = file.names();
    throw_data_error(path, fmt::format("no {}variable '{}'; variables present: {}", role, name,
                                       names.empty() ? std::string("none") : join_names(names)));
  }
  return *var;
}

// The time variable: the option's, else the first of t, time, time_s.
const VarInfo* find_time_variable(const std::string& path, const MatFile& file,
                                  const ReadOptions& options) {
  if (!options.time_channel.empty()) {
    return &require_variable(path, file, options.time_channel, "time ");
  }
  for (std::string_view name : kTimeChannelNames) {
    if (const VarInfo* var = file.find(name)) return var;
  }
  return nullptr;
}

const VarInfo& choose_channel(const std::string& path, const MatFile& file,
                              const ReadOptions& options, const VarInfo* time) {
  if (!options.channel.empty()) {
    const VarInfo& var = require_variable(path, file, options.channel, "");
    if (!var.readable()) throw_data_error(path, unreadable_reason(var));
    return var;
  }
  std::vector<const VarInfo*> candidates;
  for (const VarInfo& var : file.variables()) {
    if (!var.readable() || var.numel() < 2 || var.name == "f" || &var == time ||
        is_lab_temperature_name(var.name)) {
      continue;
    }
    candidates.push_back(&var);
  }
  if (candidates.size() == 1) return *candidates.front();
  for (const VarInfo* var : candidates) {
    if (var->name == kDefaultDataChannels[0]) return *var;
  }
  if (candidates.empty()) {
    throw_data_error(path, fmt::format("no data channel: expected a real numeric vector other "
                                       "than f, the time and temperatures (T, T1, ...); "
                                       "variables present: {}",
                                       listing(file)));
  }
  std::vector<std::string> names;
  for (const VarInfo* var : candidates) names.push_back(var->name);
  throw_data_error(path, fmt::format("several data channels ({}) and none is Y1: choose one "
                                     "with ReadOptions::channel",
                                     join_names(names)));
}

TimeAxis time_axis_variable(const std::string& path, MatFile& file, const VarInfo& time,
                            const VarInfo& channel) {
  if (!time.readable()) throw_data_error(path, unreadable_reason(time));
  if (time.numel() != channel.numel()) {
    throw_data_error(path,
                     fmt::format("time variable '{}' has {} samples but '{}' has {}{}", time.name,
                                 time.numel(), channel.name, channel.numel(), kIgnoreTimeHint));
  }
  const std::vector<double> time_s = file.read(time);
  // single-precision time steps carry float rounding, not gaps
  double resolution_s = 0.0;
  if (time.class_type == MAT_C_SINGLE) {
    resolution_s =
        4.0 * FLT_EPSILON * std::max(std::fabs(time_s.front()), std::fabs(time_s.back()));
  }
  return time_axis_of(path, time.name, time_s, resolution_s);
}

}  // namespace

Series read_mat(const std::string& path, const ReadOptions& options) {
  MatioSession session;
  MatFile file(path, session);
  Series series;
  series.path = path;
  series.available_channels = available_channels(file);

  series.variables = file.names();

  const VarInfo* time = find_time_variable(path, file, options);
  const VarInfo& channel = choose_channel(path, file, options, time);
  series.channel = channel.name;
  if (is_integer_class(channel.class_type)) {
    const bool wide = channel.class_type == MAT_C_INT64 || channel.class_type == MAT_C_UINT64;
    series.notes.emplace_back(Text::io_note_mat_integer, quoted_path(path), channel.name,
                              describe(channel),
                              wide ? Message(Text::io_note_mat_integer_wide) : Message());
  }

  // The rate first: the time vector is read and freed before the channel,
  // so that at most one full-length vector is held at a time.
  std::optional<TimeAxis> axis;
  std::string axis_name;
  bool rate_from_axis = false;
  if (!options.sample_rate_hz) {
    const VarInfo* f = file.find("f");
    if (options.time_channel.empty() && f != nullptr) {
      if (!f->numeric() || f->complex || f->numel() != 1) {
        throw_data_error(path, fmt::format("variable 'f' should be the sample rate in Hz (a "
                                           "real scalar) but is {}",
                                           describe(*f)));
      }
      const double rate_hz = file.read(*f).front();
      check_file_sample_rate(path, rate_hz, "variable f");
      series.sample_rate_hz = rate_hz;
      series.sample_rate_source = SampleRateSource::variable_f;
      // A time vector beside f must agree with the channel too: a record
      // of another length is refused, and its gaps are the record's.
      if (time != nullptr && time != &channel && time->readable() && time->numel() >= 2) {
        axis = time_axis_variable(path, file, *time, channel);
        axis_name = time->name;
      }
    } else if (time != nullptr) {
      axis = time_axis_variable(path, file, *time, channel);
      axis_name = time->name;
      rate_from_axis = true;
    } else {
      throw UsageError(
          fmt::format("{} has no sample rate (no variable f and no time variable "
                      "t, time or time_s): give ReadOptions::sample_rate_hz",
                      quoted_path(path)));
    }
  }
  series.values = file.read(channel);
  if (axis) apply_time_axis(series, std::move(*axis), axis_name, rate_from_axis);
  return series;
}

std::vector<std::string> list_mat_channels(const std::string& path) {
  MatioSession session;
  MatFile file(path, session);
  return available_channels(file);
}

std::vector<std::string> list_mat_variables(const std::string& path) {
  MatioSession session;
  MatFile file(path, session);
  return file.names();
}

}  // namespace foglab::io::internal
